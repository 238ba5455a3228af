#include "dlmfd/conformation/velocity_gradient.h"

#include "../mesh/grid_kernels.h"
#include "dlmfd/core/target_clones.h"

namespace dlmfd {
namespace {

using kernels::Diagonal;

struct GradientSum {
  double ux = 0.0, uy = 0.0, vx = 0.0, vy = 0.0;
  int count = 0;
};

// The gradients of the (up to) 6 triangles of the triangulation kD that touch node (i, j)
// (grid_kernels.h), summed in the order NE square, SW square, NW square, SE square (lower triangle
// before upper).
template <Diagonal kD>
GradientSum SumAround(const Grid& g, bool px, bool py, const double* u, const double* v, int i,
                      int j) {
  const double inv_h = 1.0 / g.h;
  const kernels::CellsBeside x = kernels::OwnCells(i, g.nx, px);
  const kernels::CellsBeside y = kernels::RowOffsets(g, kernels::OwnCells(j, g.ny, py));
  GradientSum sum;
  kernels::ForEachTriangleAround<kernels::SquareOrder::kFullSquaresFirst, kD>(
      x, y, [&](const kernels::TriangleAround& t) {
        sum.ux += kernels::TriangleDx<kD>(u, t) * inv_h;
        sum.uy += kernels::TriangleDy<kD>(u, t) * inv_h;
        sum.vx += kernels::TriangleDx<kD>(v, t) * inv_h;
        sum.vy += kernels::TriangleDy<kD>(v, t) * inv_h;
        ++sum.count;
      });
  return sum;
}

// Interior nodes i = 1 .. count of one row (p points at node (1, j)): the closed form of the
// 6-triangle average, or with `both` of the mean of the two triangulations' averages. Compiled for
// AVX2 and for the baseline, chosen at load time.
DLMFD_AVX2_CLONES void InteriorRow(bool both, int count, std::ptrdiff_t row, double inv_6h,
                                   const double* __restrict u, const double* __restrict v,
                                   double* __restrict l11, double* __restrict l12,
                                   double* __restrict l21, double* __restrict l22) {
  if (!both) {
    for (int i = 0; i < count; ++i) {
      const double* p = u + i;
      const double* q = v + i;
      l11[i] = (2.0 * (p[1] - p[-1]) + p[row + 1] - p[row] + p[-row] - p[-row - 1]) * inv_6h;
      l12[i] = (2.0 * (p[row] - p[-row]) + p[row + 1] - p[1] + p[-1] - p[-row - 1]) * inv_6h;
      l21[i] = (2.0 * (q[1] - q[-1]) + q[row + 1] - q[row] + q[-row] - q[-row - 1]) * inv_6h;
      l22[i] = (2.0 * (q[row] - q[-row]) + q[row + 1] - q[1] + q[-1] - q[-row - 1]) * inv_6h;
    }
    return;
  }
  // SW-NE: 2 (E - W) + NE - N + S - SW; NW-SE: 2 (E - W) + N - NW + SE - S (and likewise in y).
  for (int i = 0; i < count; ++i) {
    const double* p = u + i;
    const double* q = v + i;
    l11[i] = (2.0 * (p[1] - p[-1]) + 0.5 * (p[row + 1] - p[row - 1] + p[-row + 1] - p[-row - 1])) *
             inv_6h;
    l12[i] =
        (2.0 * (p[row] - p[-row]) + 0.5 * (p[row + 1] + p[row - 1] - p[-row + 1] - p[-row - 1])) *
        inv_6h;
    l21[i] = (2.0 * (q[1] - q[-1]) + 0.5 * (q[row + 1] - q[row - 1] + q[-row + 1] - q[-row - 1])) *
             inv_6h;
    l22[i] =
        (2.0 * (q[row] - q[-row]) + 0.5 * (q[row + 1] + q[row - 1] - q[-row + 1] - q[-row - 1])) *
        inv_6h;
  }
}

// The average over the triangles around node k, or with `both` the mean of the two
// triangulations' averages (the counts differ at corners and sides).
void BoundaryNode(const Grid& grid, bool px, bool py, bool both, const double* u, const double* v,
                  int i, int j, double* l11, double* l12, double* l21, double* l22) {
  const std::size_t k = grid.Index(i, j);
  const GradientSum s = SumAround<Diagonal::kSwNe>(grid, px, py, u, v, i, j);
  const double inv = 1.0 / s.count;
  if (!both) {
    l11[k] = s.ux * inv;
    l12[k] = s.uy * inv;
    l21[k] = s.vx * inv;
    l22[k] = s.vy * inv;
    return;
  }
  const GradientSum m = SumAround<Diagonal::kNwSe>(grid, px, py, u, v, i, j);
  const double inv_m = 1.0 / m.count;
  l11[k] = 0.5 * (s.ux * inv + m.ux * inv_m);
  l12[k] = 0.5 * (s.uy * inv + m.uy * inv_m);
  l21[k] = 0.5 * (s.vx * inv + m.vx * inv_m);
  l22[k] = 0.5 * (s.vy * inv + m.vy * inv_m);
}

}  // namespace

void NodeVelocityGradient(const Grid& grid, bool periodic_x, bool periodic_y, const double* u,
                          const double* v, double* l11, double* l12, double* l21, double* l22,
                          MeshDiagonals diagonals) {
  const int nx = grid.nx, ny = grid.ny;
  const std::ptrdiff_t row = nx + 1;
  const double inv_6h = 1.0 / (6.0 * grid.h);
  const bool both = diagonals == MeshDiagonals::kBoth;
#pragma omp parallel for schedule(static)
  for (int j = 0; j <= ny; ++j) {
    const bool interior_row = j > 0 && j < ny;
    if (interior_row && nx > 1) {
      const std::size_t k = grid.Index(1, j);
      InteriorRow(both, nx - 1, row, inv_6h, u + k, v + k, l11 + k, l12 + k, l21 + k, l22 + k);
    }
    for (int i = 0; i <= nx; ++i) {
      if (interior_row && i > 0 && i < nx) continue;  // done above
      BoundaryNode(grid, periodic_x, periodic_y, both, u, v, i, j, l11, l12, l21, l22);
    }
  }
}

}  // namespace dlmfd
