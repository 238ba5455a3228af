// Row kernels of the wave stiffness K_V on both diagonals (domain.diagonals = "both";
// AdvectionWave, advection_wave.cc): one row of cells or nodes a call, on raw rows with unaliased
// arguments, so that each loop is a straight vector loop (compiled for AVX2 and the baseline).
//
// Cell ci of a row has the corners a = low[ci], b = low[ci + 1], c = high[ci + 1], d = high[ci]
// (low, high: the node rows below and above it) and the triangles T1 = (a, b, c), T2 = (a, c, d)
// (SW-NE) and T3 = (a, b, d), T4 = (b, c, d) (NW-SE). Each has the weights (method notes 3)
//   W_T / h^2 = (1/24) (sum_k V_k V_k^T + S S^T) = [[a_t, b_t], [b_t, c_t]],  S = sum_k V_k,
// over its vertices k. The mean of the four triangles' K_V is, on the differences
// e = (u_b - u_a, u_c - u_a, u_d - u_a), the symmetric matrix M of the cell:
//   bb = (a1 + a3 - 2 b1 + c1 + c4) / 2,  bc = (b1 - b4 - c1 - c4) / 2,  bd = (b3 + b4) / 2,
//   cc = (a2 + a4 + 2 b4 + c1 + c4) / 2,  cd = -(a2 + a4 - b2 + b4) / 2,
//   dd = (a2 + a4 - 2 b2 + c2 + c3) / 2,
// and the cell's shares of the rows of its corners are (s_b, s_c, s_d) = M e, s_a = -(s_b + s_c +
// s_d) (K_V's rows and columns sum to zero).
#pragma once

namespace dlmfd::wave_rows {

// M of `cells` cells of one row from the velocity V = (x, y) on the node rows below (x0, y0) and
// above (x1, y1); out[0..5] = bb, bc, bd, cc, cd, dd of the row's cells.
void CellMatrixRow(int cells, const double* x0, const double* x1, const double* y0,
                   const double* y1, double* const out[6]);

// The shares (s_a, s_b, s_c, s_d) -> share[0..3] of `cells` cells of one row for the field f on
// the node rows below (f0) and above (f1); m[0..5] as CellMatrixRow writes them.
void CellSharesRow(int cells, const double* const m[6], const double* f0, const double* f1,
                   double* const share[4]);

// K_V u at `nodes` nodes of one row: out[i] = a[i] + b[i] + c[i] + d[i], the shares of the cells
// whose corner a, b, c, d the node is (the caller offsets each row to its node).
void GatherRow(int nodes, const double* a, const double* b, const double* c, const double* d,
               double* out);

}  // namespace dlmfd::wave_rows
