// Matrix-free P1 operators on the uniform SW-NE mesh (method notes 1, section 1): each function
// sweeps the node rows that own a Galerkin row and calls one kernel of grid_kernels.h per node;
// periodic duplicates get a zero row, as in the assembled matrices. With MeshDiagonals::kBoth, G,
// B and B^T return the mean of the form on the SW-NE triangles and on the NW-SE ones, each node's
// row gathered from both triangulations in the same sweep (grid_kernels.h, Diagonal).
#include <algorithm>
#include <cstddef>
#include <vector>

#include "dlmfd/core/target_clones.h"
#include "dlmfd/mesh/fem_operators.h"
#include "grid_kernels.h"

namespace dlmfd {
namespace {

using kernels::AxisWrap;
using kernels::CellsBeside;
using kernels::FoldedCells;
using kernels::FoldedRows;
using kernels::Rows;
using kernels::RowsAt;

// Below this many nodes the OpenMP start-up costs more than the sweep.
constexpr std::size_t kParallelNodes = 16384;

// Zero rows of the periodic duplicates (last column and/or last row).
void ZeroDuplicates(const Grid& grid, const AxisWrap& ax, const AxisWrap& ay, double* out) {
  if (ax.periodic) {
    for (int j = 0; j <= grid.ny; ++j) out[grid.Index(grid.nx, j)] = 0.0;
  }
  if (ay.periodic) {
    std::fill(out + grid.Index(0, grid.ny), out + grid.Index(0, grid.ny) + grid.NodesX(), 0.0);
  }
}

// Scratch node arrays of the calling thread (two slots); each grows once, then is reused (no
// allocation per call).
double* Scratch(int slot, std::size_t size) {
  thread_local std::vector<double> buffers[2];
  if (buffers[slot].size() < size) buffers[slot].resize(size);
  return buffers[slot].data();
}

// Calls node(im, i, ip) for every row-owning node of a row: the ends with their wrapped or missing
// neighbours, the interior with literal ones so that the kernel's neighbour tests fold away.
template <typename NodeFn>
inline void SweepRow(const AxisWrap& ax, NodeFn&& node) {
  const int last = ax.Lines() - 1;
  node(ax.Prev(0), 0, ax.Next(0));
  for (int i = 1; i < last; ++i) node(i - 1, i, i + 1);
  if (last > 0) node(ax.Prev(last), last, ax.Next(last));
}

}  // namespace

void ApplyLumpedMass(const Grid& grid, const BoundaryTopology& topo, const double* f, double* out) {
  const AxisWrap ax(grid.nx, topo.x), ay(grid.ny, topo.y);
  const double h2 = grid.h * grid.h;
  const int lines_x = ax.Lines(), lines_y = ay.Lines();
#pragma omp parallel for schedule(static) if (grid.NodeCount() > kParallelNodes)
  for (int j = 0; j < lines_y; ++j) {
    const double wy = h2 * ay.Weight(j);
    const double* in = f + grid.Index(0, j);
    double* o = out + grid.Index(0, j);
    for (int i = 0; i < lines_x; ++i) o[i] = wy * ax.Weight(i) * in[i];
  }
  ZeroDuplicates(grid, ax, ay, out);
}

void LumpedMassDiagonal(const Grid& grid, const BoundaryTopology& topo, double* out) {
  const AxisWrap ax(grid.nx, topo.x), ay(grid.ny, topo.y);
  const double h2 = grid.h * grid.h;
  for (int j = 0; j <= grid.ny; ++j) {
    for (int i = 0; i <= grid.nx; ++i) {
      out[grid.Index(i, j)] = h2 * ax.Weight(i) * ay.Weight(j);
    }
  }
}

void ApplyStiffness(const Grid& grid, const BoundaryTopology& topo, const double* u, double* out) {
  const AxisWrap ax(grid.nx, topo.x), ay(grid.ny, topo.y);
  const int lines_y = ay.Lines();
#pragma omp parallel for schedule(static) if (grid.NodeCount() > kParallelNodes)
  for (int j = 0; j < lines_y; ++j) {
    const Rows r = RowsAt(grid, ay, u, j);
    const double wy = ay.Weight(j);
    double* o = out + grid.Index(0, j);
    SweepRow(
        ax, [&](int im, int i, int ip) __attribute__((always_inline)) {
          o[i] = kernels::StiffnessAt(r, im, i, ip, ax.Weight(i), wy);
        });
  }
  ZeroDuplicates(grid, ax, ay, out);
}

namespace {

using kernels::Diagonal;

// Calls generic(im, i, ip) as SweepRow does, except that on an interior row (its neighbour rows
// j - 1 and j + 1, no wrap) the nodes between the row's ends go to interior(first, end), the nodes
// first <= i < end: there all eight neighbours lie at fixed offsets, and each form has a short
// closed form (below), which the compiler does not find from the generic gather's sum over 6 (or
// 2 x 6) triangles (floating-point sums are not reassociated); on the paper's grid the closed forms
// take about half the time (docs/evidence/performance.md, "Full Oldroyd-B step": the interior rows
// as closed forms). With both triangulations the interior is a straight loop of its own with
// unaliased arguments, compiled for AVX2 and the baseline (the *Interior functions).
template <typename Generic, typename Interior>
inline void SweepRowSplit(const AxisWrap& ax, bool interior_row, Generic&& generic,
                          Interior&& interior) {
  if (!interior_row) {
    SweepRow(ax, generic);
    return;
  }
  const int last = ax.Lines() - 1;
  generic(ax.Prev(0), 0, ax.Next(0));
  if (last > 1) interior(1, last);
  if (last > 0) generic(ax.Prev(last), last, ax.Next(last));
}

bool InteriorRow(const AxisWrap& ay, int j) {
  return j > 0 && ay.Prev(j) == j - 1 && ay.Next(j) == j + 1;
}

// The three forms below on the SW-NE mesh (kBoth false), or with both triangulations as their
// mean (kBoth true), each node's row gathered from the triangles of both around it in one sweep:
// the arguments are read once and nothing is mirrored or copied. Interior nodes of interior rows by
// the closed forms of the Interior* functions, c the node's entry and `row` the row stride.

// (6/h) G at an interior node, SW-NE: (2 (E - W) + NE - N + S - SW, 2 (N - S) + NE - E + W - SW).
[[gnu::always_inline]] inline void InteriorGradientSwNe(const double* c, long row, double& sx,
                                                        double& sy) {
  const double ne = c[row + 1], sw = c[-1 - row];
  sx = 2.0 * (c[1] - c[-1]) + ne - c[row] + c[-row] - sw;
  sy = 2.0 * (c[row] - c[-row]) + ne - c[1] + c[-1] - sw;
}

// (12/h) times the mean of the two G at an interior node: (4 (E - W) + NE - NW + SE - SW, 4 (N - S)
// + NE + NW - SE - SW), the sum of the SW-NE rows above and the NW-SE rows 2 (E - W) + N - NW + SE
// - S, 2 (N - S) + NW - W + E - SE.
[[gnu::always_inline]] inline void InteriorGradientBoth(const double* c, long row, double& sx,
                                                        double& sy) {
  const double ne = c[row + 1], nw = c[row - 1], se = c[1 - row], sw = c[-1 - row];
  sx = 4.0 * (c[1] - c[-1]) + ne - nw + se - sw;
  sy = 4.0 * (c[row] - c[-row]) + ne + nw - se - sw;
}

// (6/h) (G_x u + G_y v) at an interior node, SW-NE: 2 (uE - uW) + uNE - uN + uS - uSW + 2 (vN -
// vS) + vNE - vE + vW - vSW; NW-SE: 2 (uE - uW) + uN - uNW + uSE - uS + 2 (vN - vS) + vNW - vW + vE
// - vSE.
[[gnu::always_inline]] inline double InteriorDivergenceSwNe(const double* a, const double* b,
                                                            long row) {
  return 2.0 * (a[1] - a[-1]) + a[row + 1] - a[row] + a[-row] - a[-1 - row] +
         2.0 * (b[row] - b[-row]) + b[row + 1] - b[1] + b[-1] - b[-1 - row];
}
[[gnu::always_inline]] inline double InteriorDivergenceNwSe(const double* a, const double* b,
                                                            long row) {
  return 2.0 * (a[1] - a[-1]) + a[row] - a[row - 1] + a[1 - row] - a[-row] +
         2.0 * (b[row] - b[-row]) + b[row - 1] - b[-1] + b[1] - b[1 - row];
}
// Their sum: 4 (uE - uW) + uNE - uNW + uSE - uSW + 4 (vN - vS) + vNE + vNW - vSE - vSW.
[[gnu::always_inline]] inline double InteriorDivergenceBoth(const double* a, const double* b,
                                                            long row) {
  return 4.0 * (a[1] - a[-1]) + a[row + 1] - a[row - 1] + a[1 - row] - a[-1 - row] +
         4.0 * (b[row] - b[-row]) + b[row + 1] + b[row - 1] - b[1 - row] - b[-1 - row];
}

// (6/h) G^T q at an interior node (the node's own weight is zero), q = I_p p of the triangulation:
// SW-NE x -2 E - NE + N + 2 W + SW - S, y E - NE - 2 N - W + SW + 2 S; NW-SE x -2 E - SE + S + 2 W
// + NW - N, y -E - NW - 2 N + W + SE + 2 S.
[[gnu::always_inline]] inline void InteriorGradientTransposeSwNe(const double* a, long row,
                                                                 double& sx, double& sy) {
  sx = 2.0 * (a[-1] - a[1]) - a[row + 1] + a[row] + a[-1 - row] - a[-row];
  sy = a[1] - a[row + 1] - 2.0 * a[row] - a[-1] + a[-1 - row] + 2.0 * a[-row];
}
[[gnu::always_inline]] inline void InteriorGradientTransposeNwSe(const double* b, long row,
                                                                 double& sx, double& sy) {
  sx = 2.0 * (b[-1] - b[1]) - b[1 - row] + b[-row] + b[row - 1] - b[row];
  sy = b[-1] - b[1] - b[row - 1] - 2.0 * b[row] + b[1 - row] + 2.0 * b[-row];
}

// Nodes 0 .. count - 1 of an interior row's interior with both triangulations (a, b: SW-NE's and
// NW-SE's I_p p at the first node; ou, ov: B^T p there): the sum of the two closed forms above, one
// straight loop with unaliased arguments, compiled for AVX2 and the baseline.
DLMFD_AVX2_CLONES void TransposeBothInterior(int count, long row, double scale,
                                             const double* __restrict a, const double* __restrict b,
                                             double* __restrict ou, double* __restrict ov) {
  for (int i = 0; i < count; ++i) {
    double sx, sy, mx, my;
    InteriorGradientTransposeSwNe(a + i, row, sx, sy);
    InteriorGradientTransposeNwSe(b + i, row, mx, my);
    ou[i] = scale * (sx + mx);
    ov[i] = scale * (sy + my);
  }
}

// One fine row of both triangulations' I_p p (grid_kernels.h, ProlongRow), compiled for AVX2 and
// the baseline. On an even row (no high) the two are the same numbers (each odd node the mean of
// the same two coarse values), so NW-SE's row is a copy.
DLMFD_AVX2_CLONES void ProlongBothRow(const AxisWrap& cx, const double* low, const double* high,
                                      int fine_lines, double* out, double* out2) {
  kernels::ProlongRow<Diagonal::kSwNe>(cx, low, high, fine_lines, out);
  if (high) {
    kernels::ProlongRow<Diagonal::kNwSe>(cx, low, high, fine_lines, out2);
  } else {
    std::copy_n(out, fine_lines, out2);
  }
}

// The interior kernels with both triangulations: nodes of one interior row, straight loops with
// unaliased arguments, compiled for AVX2 and the baseline.
// G: count nodes from f's, gx's and gy's first (scale h/12: the mean of the two).
DLMFD_AVX2_CLONES void GradientBothInterior(int count, long row, double scale,
                                            const double* __restrict f, double* __restrict gx,
                                            double* __restrict gy) {
  for (int i = 0; i < count; ++i) {
    double sx, sy;
    InteriorGradientBoth(f + i, row, sx, sy);
    gx[i] = scale * sx;
    gy[i] = scale * sy;
  }
}
// G_x u + G_y v at the nodes first <= i < end of a row (pointers at its node 0): the sum of the
// two rows at every node, then on an odd row the odd-odd nodes' SW-NE row in w and NW-SE row in w2
// (DivergenceOnVelocityNodes).
DLMFD_AVX2_CLONES void DivergenceBothInterior(bool odd_row, int first, int end, long row,
                                              double scale, const double* __restrict u,
                                              const double* __restrict v, double* __restrict w,
                                              double* __restrict w2) {
  for (int i = first; i < end; ++i) w[i] = scale * InteriorDivergenceBoth(u + i, v + i, row);
  if (!odd_row) return;
  for (int i = first | 1; i < end; i += 2) {
    w[i] = scale * InteriorDivergenceSwNe(u + i, v + i, row);
    w2[i] = scale * InteriorDivergenceNwSe(u + i, v + i, row);
  }
}

// (gx, gy) = G f on every row-owning node.
template <bool kBoth>
void IntegratedGradient(const Grid& grid, const AxisWrap& ax, const AxisWrap& ay, const double* f,
                        double* gx, double* gy) {
  const double scale = kBoth ? grid.h / 12.0 : grid.h / 6.0;  // the mean of two h/6-scaled sums
  const long row = grid.NodesX();
  const int lines_y = ay.Lines();
#pragma omp parallel for schedule(static) if (grid.NodeCount() > kParallelNodes)
  for (int j = 0; j < lines_y; ++j) {
    const CellsBeside y = FoldedRows(grid, ay, j);
    const double* r = f + grid.Index(0, j);
    double* ox = gx + grid.Index(0, j);
    double* oy = gy + grid.Index(0, j);
    SweepRowSplit(
        ax, InteriorRow(ay, j),
        [&](int im, int i, int ip) __attribute__((always_inline)) {
          double sx, sy;
          kernels::GradientSumsAt<Diagonal::kSwNe>(f, FoldedCells(im, i, ip), y, sx, sy);
          if constexpr (kBoth) {
            double mx, my;
            kernels::GradientSumsAt<Diagonal::kNwSe>(f, FoldedCells(im, i, ip), y, mx, my);
            sx += mx;
            sy += my;
          }
          ox[i] = scale * sx;
          oy[i] = scale * sy;
        },
        [&](int first, int end) __attribute__((always_inline)) {
          if constexpr (kBoth) {
            GradientBothInterior(end - first, row, scale, r + first, ox + first, oy + first);
          } else {
            for (int i = first; i < end; ++i) {
              double sx, sy;
              InteriorGradientSwNe(r + i, row, sx, sy);
              ox[i] = scale * sx;
              oy[i] = scale * sy;
            }
          }
        });
  }
}

// w = G_x u + G_y v on every row-owning velocity node (kBoth false). With both triangulations the
// two restrictions differ only at the odd-odd nodes (the 2h-squares' centres), so w holds the sum
// of the SW-NE and NW-SE rows elsewhere and the SW-NE row there, and w2 the NW-SE row there only
// (grid_kernels.h, RestrictBothAt).
template <bool kBoth>
void DivergenceOnVelocityNodes(const Grid& grid, const AxisWrap& ax, const AxisWrap& ay,
                               const double* u, const double* v, double* w, double* w2) {
  const double scale = grid.h / 6.0;
  const long row = grid.NodesX();
  const int lines_y = ay.Lines();
#pragma omp parallel for schedule(static) if (grid.NodeCount() > kParallelNodes)
  for (int j = 0; j < lines_y; ++j) {
    const CellsBeside y = FoldedRows(grid, ay, j);
    double* out = w + grid.Index(0, j);
    double* out2 = kBoth ? w2 + grid.Index(0, j) : nullptr;
    const double* ru = u + grid.Index(0, j);
    const double* rv = v + grid.Index(0, j);
    const bool odd_row = j % 2 != 0;
    auto generic = [&](int im, int i, int ip) __attribute__((always_inline)) {
      const CellsBeside x = FoldedCells(im, i, ip);
      const double sw_ne = scale * kernels::DivergenceSumsAt<Diagonal::kSwNe>(u, v, x, y);
      if constexpr (kBoth) {
        const double nw_se = scale * kernels::DivergenceSumsAt<Diagonal::kNwSe>(u, v, x, y);
        if (odd_row && i % 2 != 0) {
          out[i] = sw_ne;
          out2[i] = nw_se;
        } else {
          out[i] = sw_ne + nw_se;
        }
      } else {
        out[i] = sw_ne;
      }
    };
    SweepRowSplit(ax, InteriorRow(ay, j), generic, [&](int first, int end) {
      if constexpr (kBoth) {
        DivergenceBothInterior(odd_row, first, end, row, scale, ru, rv, out, out2);
      } else {
        for (int i = first; i < end; ++i)
          out[i] = scale * InteriorDivergenceSwNe(ru + i, rv + i, row);
      }
    });
  }
}

// B = I_p^T (G_x u + G_y v): the fine rows restricted to the 2h mesh; with both triangulations the
// mean of the SW-NE pair's and the NW-SE pair's (each restricts with its own 2h triangles).
template <bool kBoth>
void Divergence(const Grid& grid, const BoundaryTopology& pressure_topo, const double* u,
                const double* v, double* out) {
  const AxisWrap ax(grid.nx, pressure_topo.x), ay(grid.ny, pressure_topo.y);
  const Grid coarse = grid.Coarse();
  const AxisWrap cx(coarse.nx, pressure_topo.x), cy(coarse.ny, pressure_topo.y);
  double* w = Scratch(0, grid.NodeCount());
  double* w2 = kBoth ? Scratch(1, grid.NodeCount()) : nullptr;
  DivergenceOnVelocityNodes<kBoth>(grid, ax, ay, u, v, w, w2);
  const int lines_x = cx.Lines(), lines_y = cy.Lines();
#pragma omp parallel for schedule(static) if (coarse.NodeCount() > kParallelNodes)
  for (int jc = 0; jc < lines_y; ++jc) {
    const Rows r = RowsAt(grid, ay, w, 2 * jc);
    double* o = out + coarse.Index(0, jc);
    if constexpr (kBoth) {
      const Rows r2 = RowsAt(grid, ay, w2, 2 * jc);
      for (int ic = 0; ic < lines_x; ++ic) {
        const int i = 2 * ic;
        o[ic] = kernels::RestrictBothAt(r, r2, ax.Prev(i), i, ax.Next(i));
      }
    } else {
      for (int ic = 0; ic < lines_x; ++ic) {
        const int i = 2 * ic;
        o[ic] = kernels::RestrictAt<Diagonal::kSwNe>(r, ax.Prev(i), i, ax.Next(i));
      }
    }
  }
  ZeroDuplicates(coarse, cx, cy, out);
}

// B^T p = G^T I_p p; with both triangulations the mean of the two pairs' (each prolongs with its
// own 2h triangles and gathers over its own h triangles), in one prolongation and one gather sweep.
template <bool kBoth>
void DivergenceTranspose(const Grid& grid, const BoundaryTopology& pressure_topo, const double* p,
                         double* out_u, double* out_v) {
  const AxisWrap ax(grid.nx, pressure_topo.x), ay(grid.ny, pressure_topo.y);
  const Grid coarse = grid.Coarse();
  const AxisWrap cx(coarse.nx, pressure_topo.x), cy(coarse.ny, pressure_topo.y);
  double* fine = Scratch(0, grid.NodeCount());
  double* fine2 = kBoth ? Scratch(1, grid.NodeCount()) : nullptr;
  const int lines_x = ax.Lines(), lines_y = ay.Lines();
  const double scale = kBoth ? 0.5 * (grid.h / 6.0) : grid.h / 6.0;
  const long row = grid.NodesX();
#pragma omp parallel if (grid.NodeCount() > kParallelNodes)
  {
#pragma omp for schedule(static)
    for (int j = 0; j < lines_y; ++j) {
      const int cj = j / 2;
      const double* low = p + coarse.Index(0, cj);
      const double* high = (j % 2 != 0) ? p + coarse.Index(0, cy.Next(cj)) : nullptr;
      if constexpr (kBoth) {
        ProlongBothRow(cx, low, high, lines_x, fine + grid.Index(0, j), fine2 + grid.Index(0, j));
      } else {
        kernels::ProlongRow<Diagonal::kSwNe>(cx, low, high, lines_x, fine + grid.Index(0, j));
      }
    }
#pragma omp for schedule(static)
    for (int j = 0; j < lines_y; ++j) {
      const CellsBeside y = FoldedRows(grid, ay, j);
      double* ou = out_u + grid.Index(0, j);
      double* ov = out_v + grid.Index(0, j);
      const double* r1 = fine + grid.Index(0, j);
      const double* r2 = kBoth ? fine2 + grid.Index(0, j) : nullptr;
      auto generic = [&](int im, int i, int ip) __attribute__((always_inline)) {
        const CellsBeside x = FoldedCells(im, i, ip);
        double sx, sy;
        kernels::GradientTransposeSumsAt<Diagonal::kSwNe>(fine, x, y, sx, sy);
        if constexpr (kBoth) {
          double mx, my;
          kernels::GradientTransposeSumsAt<Diagonal::kNwSe>(fine2, x, y, mx, my);
          sx += mx;
          sy += my;
        }
        ou[i] = scale * sx;
        ov[i] = scale * sy;
      };
      if (!kBoth || !InteriorRow(ay, j)) {
        SweepRowSplit(ax, InteriorRow(ay, j), generic, [&](int first, int end) {
          for (int i = first; i < end; ++i) {
            double sx, sy;
            InteriorGradientTransposeSwNe(r1 + i, row, sx, sy);
            ou[i] = scale * sx;
            ov[i] = scale * sy;
          }
        });
        continue;
      }
      // Both triangulations on an interior row: the ends by the generic gather, and between them
      // the closed forms in one straight loop.
      const int last = ax.Lines() - 1;
      generic(ax.Prev(0), 0, ax.Next(0));
      if (last > 1) TransposeBothInterior(last - 1, row, scale, r1 + 1, r2 + 1, ou + 1, ov + 1);
      if (last > 0) generic(ax.Prev(last), last, ax.Next(last));
    }
  }
  ZeroDuplicates(grid, ax, ay, out_u);
  ZeroDuplicates(grid, ax, ay, out_v);
}

}  // namespace

void ApplyIntegratedGradient(const Grid& grid, const BoundaryTopology& topo, const double* f,
                             double* gx, double* gy, MeshDiagonals diagonals) {
  const AxisWrap ax(grid.nx, topo.x), ay(grid.ny, topo.y);
  if (diagonals == MeshDiagonals::kBoth) {
    IntegratedGradient<true>(grid, ax, ay, f, gx, gy);
  } else {
    IntegratedGradient<false>(grid, ax, ay, f, gx, gy);
  }
  ZeroDuplicates(grid, ax, ay, gx);
  ZeroDuplicates(grid, ax, ay, gy);
}

void ApplyDivergence(const Grid& grid, const BoundaryTopology& pressure_topo, const double* u,
                     const double* v, double* out, MeshDiagonals diagonals) {
  if (diagonals == MeshDiagonals::kBoth) {
    Divergence<true>(grid, pressure_topo, u, v, out);
  } else {
    Divergence<false>(grid, pressure_topo, u, v, out);
  }
}

void ApplyDivergenceTranspose(const Grid& grid, const BoundaryTopology& pressure_topo,
                              const double* p, double* out_u, double* out_v,
                              MeshDiagonals diagonals) {
  if (diagonals == MeshDiagonals::kBoth) {
    DivergenceTranspose<true>(grid, pressure_topo, p, out_u, out_v);
  } else {
    DivergenceTranspose<false>(grid, pressure_topo, p, out_u, out_v);
  }
}

}  // namespace dlmfd
