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

// The four corners of a cell (a, b, c, d as above) with the products of their velocities, and
// the weights (a_t, b_t, c_t) = (1/24) (sum_k V_k V_k^T + S S^T) of its triangle (p, q, r): the
// one formula of both meshes (the SW-NE path of advection_wave.cc and MatrixLoop here).
struct CellCorners {
  double x[4], y[4], xx[4], xy[4], yy[4];

  CellCorners(double xa, double xb, double xc, double xd, double ya, double yb, double yc,
              double yd)
      : x{xa, xb, xc, xd},
        y{ya, yb, yc, yd} {
    for (int q = 0; q < 4; ++q) {
      xx[q] = x[q] * x[q];
      xy[q] = x[q] * y[q];
      yy[q] = y[q] * y[q];
    }
  }
  void Triangle(int p, int q, int r, double& w11, double& w12, double& w22) const {
    constexpr double kOneOver24 = 1.0 / 24.0;
    const double sx = x[p] + x[q] + x[r], sy = y[p] + y[q] + y[r];
    w11 = kOneOver24 * (xx[p] + xx[q] + xx[r] + sx * sx);
    w12 = kOneOver24 * (xy[p] + xy[q] + xy[r] + sx * sy);
    w22 = kOneOver24 * (yy[p] + yy[q] + yy[r] + sy * sy);
  }
};

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
