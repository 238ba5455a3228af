// Matrix-free P1 operators on the uniform SW-NE mesh (method notes 1, section 1): each function
// sweeps the node rows that own a Galerkin row and calls one kernel of grid_kernels.h per node;
// periodic duplicates get a zero row, as in the assembled matrices. With MeshDiagonals::kBoth, G,
// B and B^T add the same sweep on the mirrored arguments, which is the form on the NW-SE
// triangles (mirror_image.h), and return the mean.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "dlmfd/mesh/fem_operators.h"
#include "grid_kernels.h"
#include "mirror_image.h"

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

// Scratch node array of the calling thread; grows once, then is reused (no allocation per call).
double* Scratch(std::size_t size) {
  thread_local std::vector<double> buffer;
  if (buffer.size() < size) buffer.resize(size);
  return buffer.data();
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

// w = G_x u + G_y v on every row-owning velocity node.
void DivergenceOnVelocityNodes(const Grid& grid, const AxisWrap& ax, const AxisWrap& ay,
                               const double* u, const double* v, double* w) {
  const double scale = grid.h / 6.0;
  const int lines_y = ay.Lines();
#pragma omp parallel for schedule(static) if (grid.NodeCount() > kParallelNodes)
  for (int j = 0; j < lines_y; ++j) {
    const CellsBeside y = FoldedRows(grid, ay, j);
    double* out = w + grid.Index(0, j);
    SweepRow(ax, [&](int im, int i, int ip) {
      out[i] = scale * kernels::DivergenceSumsAt(u, v, FoldedCells(im, i, ip), y);
    });
  }
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
    SweepRow(ax, [&](int im, int i, int ip) {
      o[i] = kernels::StiffnessAt(r, im, i, ip, ax.Weight(i), wy);
    });
  }
  ZeroDuplicates(grid, ax, ay, out);
}

namespace {

// The three forms below on the SW-NE mesh alone.
void IntegratedGradientOnMesh(const Grid& grid, const BoundaryTopology& topo, const double* f,
                              double* gx, double* gy) {
  const AxisWrap ax(grid.nx, topo.x), ay(grid.ny, topo.y);
  const double scale = grid.h / 6.0;
  const int lines_y = ay.Lines();
#pragma omp parallel for schedule(static) if (grid.NodeCount() > kParallelNodes)
  for (int j = 0; j < lines_y; ++j) {
    const CellsBeside y = FoldedRows(grid, ay, j);
    double* ox = gx + grid.Index(0, j);
    double* oy = gy + grid.Index(0, j);
    SweepRow(ax, [&](int im, int i, int ip) {
      double sx, sy;
      kernels::GradientSumsAt(f, FoldedCells(im, i, ip), y, sx, sy);
      ox[i] = scale * sx;
      oy[i] = scale * sy;
    });
  }
  ZeroDuplicates(grid, ax, ay, gx);
  ZeroDuplicates(grid, ax, ay, gy);
}

void DivergenceOnMesh(const Grid& grid, const BoundaryTopology& pressure_topo, const double* u,
                      const double* v, double* out) {
  const AxisWrap ax(grid.nx, pressure_topo.x), ay(grid.ny, pressure_topo.y);
  const Grid coarse = grid.Coarse();
  const AxisWrap cx(coarse.nx, pressure_topo.x), cy(coarse.ny, pressure_topo.y);
  double* w = Scratch(grid.NodeCount());
  DivergenceOnVelocityNodes(grid, ax, ay, u, v, w);
  const int lines_x = cx.Lines(), lines_y = cy.Lines();
#pragma omp parallel for schedule(static) if (coarse.NodeCount() > kParallelNodes)
  for (int jc = 0; jc < lines_y; ++jc) {
    const Rows r = RowsAt(grid, ay, w, 2 * jc);
    double* o = out + coarse.Index(0, jc);
    for (int ic = 0; ic < lines_x; ++ic) {
      const int i = 2 * ic;
      o[ic] = kernels::RestrictAt(r, ax.Prev(i), i, ax.Next(i));
    }
  }
  ZeroDuplicates(coarse, cx, cy, out);
}

void DivergenceTransposeOnMesh(const Grid& grid, const BoundaryTopology& pressure_topo,
                               const double* p, double* out_u, double* out_v) {
  const AxisWrap ax(grid.nx, pressure_topo.x), ay(grid.ny, pressure_topo.y);
  const Grid coarse = grid.Coarse();
  const AxisWrap cx(coarse.nx, pressure_topo.x), cy(coarse.ny, pressure_topo.y);
  double* fine = Scratch(grid.NodeCount());
  const int lines_x = ax.Lines(), lines_y = ay.Lines();
  const double scale = grid.h / 6.0;
#pragma omp parallel if (grid.NodeCount() > kParallelNodes)
  {
#pragma omp for schedule(static)
    for (int j = 0; j < lines_y; ++j) {
      double* o = fine + grid.Index(0, j);
      const int cj = j / 2;
      const double* low = p + coarse.Index(0, cj);
      const double* high = (j % 2 != 0) ? p + coarse.Index(0, cy.Next(cj)) : nullptr;
      kernels::ProlongRow(cx, low, high, lines_x, o);
    }
#pragma omp for schedule(static)
    for (int j = 0; j < lines_y; ++j) {
      const CellsBeside y = FoldedRows(grid, ay, j);
      double* ou = out_u + grid.Index(0, j);
      double* ov = out_v + grid.Index(0, j);
      SweepRow(ax, [&](int im, int i, int ip) {
        double sx, sy;
        kernels::GradientTransposeSumsAt(fine, FoldedCells(im, i, ip), y, sx, sy);
        ou[i] = scale * sx;
        ov[i] = scale * sy;
      });
    }
  }
  ZeroDuplicates(grid, ax, ay, out_u);
  ZeroDuplicates(grid, ax, ay, out_v);
}

}  // namespace

// On both diagonals: each form's mean with its mirror image (mirror_image.h): a scalar argument f
// goes in as S f; a velocity (u, v) as (-S u, S v); a gradient (gx, gy) comes out as (-S gx, S gy).
void ApplyIntegratedGradient(const Grid& grid, const BoundaryTopology& topo, const double* f,
                             double* gx, double* gy, MeshDiagonals diagonals) {
  IntegratedGradientOnMesh(grid, topo, f, gx, gy);
  if (diagonals == MeshDiagonals::kSwNe) return;
  const std::size_t n = grid.NodeCount();
  const bool px = topo.x.low == EndKind::kPeriodic;
  double *mf = kernels::MirrorScratch(0, n), *mg = kernels::MirrorScratch(1, 2 * n);
  kernels::MirrorInX(grid, px, 1.0, f, mf);
  IntegratedGradientOnMesh(grid, topo, mf, mg, mg + n);
  kernels::AverageWithMirrorImage(grid, px, -1.0, mg, gx);
  kernels::AverageWithMirrorImage(grid, px, 1.0, mg + n, gy);
  const AxisWrap ax(grid.nx, topo.x), ay(grid.ny, topo.y);
  ZeroDuplicates(grid, ax, ay, gx);
  ZeroDuplicates(grid, ax, ay, gy);
}

void ApplyDivergence(const Grid& grid, const BoundaryTopology& pressure_topo, const double* u,
                     const double* v, double* out, MeshDiagonals diagonals) {
  DivergenceOnMesh(grid, pressure_topo, u, v, out);
  if (diagonals == MeshDiagonals::kSwNe) return;
  const std::size_t n = grid.NodeCount();
  const Grid coarse = grid.Coarse();
  const bool px = pressure_topo.x.low == EndKind::kPeriodic;
  double* mirrored = kernels::MirrorScratch(0, 2 * n + coarse.NodeCount());
  kernels::MirrorInX(grid, px, -1.0, u, mirrored);
  kernels::MirrorInX(grid, px, 1.0, v, mirrored + n);
  DivergenceOnMesh(grid, pressure_topo, mirrored, mirrored + n, mirrored + 2 * n);
  kernels::AverageWithMirrorImage(coarse, px, 1.0, mirrored + 2 * n, out);
  const AxisWrap cx(coarse.nx, pressure_topo.x), cy(coarse.ny, pressure_topo.y);
  ZeroDuplicates(coarse, cx, cy, out);
}

void ApplyDivergenceTranspose(const Grid& grid, const BoundaryTopology& pressure_topo,
                              const double* p, double* out_u, double* out_v,
                              MeshDiagonals diagonals) {
  DivergenceTransposeOnMesh(grid, pressure_topo, p, out_u, out_v);
  if (diagonals == MeshDiagonals::kSwNe) return;
  const std::size_t n = grid.NodeCount();
  const Grid coarse = grid.Coarse();
  const bool px = pressure_topo.x.low == EndKind::kPeriodic;
  double* mirrored = kernels::MirrorScratch(0, 2 * n + coarse.NodeCount());
  kernels::MirrorInX(coarse, px, 1.0, p, mirrored + 2 * n);
  DivergenceTransposeOnMesh(grid, pressure_topo, mirrored + 2 * n, mirrored, mirrored + n);
  kernels::AverageWithMirrorImage(grid, px, -1.0, mirrored, out_u);
  kernels::AverageWithMirrorImage(grid, px, 1.0, mirrored + n, out_v);
  const AxisWrap ax(grid.nx, pressure_topo.x), ay(grid.ny, pressure_topo.y);
  ZeroDuplicates(grid, ax, ay, out_u);
  ZeroDuplicates(grid, ax, ay, out_v);
}

}  // namespace dlmfd
