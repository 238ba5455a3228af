#include "dlmfd/conformation/velocity_gradient.h"

#include "../mesh/grid_kernels.h"
#include "../mesh/mirror_image.h"

namespace dlmfd {
namespace {

struct GradientSum {
  double ux = 0.0, uy = 0.0, vx = 0.0, vy = 0.0;
  int count = 0;
};

// The gradients of the (up to) 6 triangles that touch node (i, j) (grid_kernels.h), summed in the
// order NE square (T1, T2), SW square (T1, T2), NW square (T1), SE square (T2).
GradientSum SumAround(const Grid& g, bool px, bool py, const double* u, const double* v, int i,
                      int j) {
  const double inv_h = 1.0 / g.h;
  const kernels::CellsBeside x = kernels::OwnCells(i, g.nx, px);
  const kernels::CellsBeside y = kernels::RowOffsets(g, kernels::OwnCells(j, g.ny, py));
  GradientSum sum;
  kernels::ForEachTriangleAround<kernels::SquareOrder::kFullSquaresFirst>(
      x, y, [&](const kernels::TriangleAround& t) {
        sum.ux += kernels::TriangleDx(u, t) * inv_h;
        sum.uy += kernels::TriangleDy(u, t) * inv_h;
        sum.vx += kernels::TriangleDx(v, t) * inv_h;
        sum.vy += kernels::TriangleDy(v, t) * inv_h;
        ++sum.count;
      });
  return sum;
}

// Interior nodes i = 1 .. count of one row (p points at node (1, j)): the closed form of the
// 6-triangle average. Compiled for AVX2 and for the baseline, chosen at load time.
__attribute__((target_clones("avx2", "default"))) void InteriorRow(
    int count, std::ptrdiff_t row, double inv_6h, const double* __restrict u,
    const double* __restrict v, double* __restrict l11, double* __restrict l12,
    double* __restrict l21, double* __restrict l22) {
  for (int i = 0; i < count; ++i) {
    const double* p = u + i;
    const double* q = v + i;
    l11[i] = (2.0 * (p[1] - p[-1]) + p[row + 1] - p[row] + p[-row] - p[-row - 1]) * inv_6h;
    l12[i] = (2.0 * (p[row] - p[-row]) + p[row + 1] - p[1] + p[-1] - p[-row - 1]) * inv_6h;
    l21[i] = (2.0 * (q[1] - q[-1]) + q[row + 1] - q[row] + q[-row] - q[-row - 1]) * inv_6h;
    l22[i] = (2.0 * (q[row] - q[-row]) + q[row + 1] - q[1] + q[-1] - q[-row - 1]) * inv_6h;
  }
}

// The average on the SW-NE triangles.
void SwNeGradient(const Grid& grid, bool periodic_x, bool periodic_y, const double* u,
                  const double* v, double* l11, double* l12, double* l21, double* l22) {
  const int nx = grid.nx, ny = grid.ny;
  const std::ptrdiff_t row = nx + 1;
  const double inv_6h = 1.0 / (6.0 * grid.h);
#pragma omp parallel for schedule(static)
  for (int j = 0; j <= ny; ++j) {
    const bool interior_row = j > 0 && j < ny;
    if (interior_row && nx > 1) {
      const std::size_t k = grid.Index(1, j);
      InteriorRow(nx - 1, row, inv_6h, u + k, v + k, l11 + k, l12 + k, l21 + k, l22 + k);
    }
    for (int i = 0; i <= nx; ++i) {
      if (interior_row && i > 0 && i < nx) continue;  // done above
      const std::size_t k = grid.Index(i, j);
      const GradientSum s = SumAround(grid, periodic_x, periodic_y, u, v, i, j);
      const double inv = 1.0 / s.count;
      l11[k] = s.ux * inv;
      l12[k] = s.uy * inv;
      l21[k] = s.vx * inv;
      l22[k] = s.vy * inv;
    }
  }
}

}  // namespace

void NodeVelocityGradient(const Grid& grid, bool periodic_x, bool periodic_y, const double* u,
                          const double* v, double* l11, double* l12, double* l21, double* l22,
                          MeshDiagonals diagonals) {
  SwNeGradient(grid, periodic_x, periodic_y, u, v, l11, l12, l21, l22);
  if (diagonals == MeshDiagonals::kSwNe) return;
  // The NW-SE average is the mirror image of the SW-NE average of the mirrored velocity (-S u, S
  // v).
  const std::size_t n = grid.NodeCount();
  double* m = kernels::MirrorScratch(0, 6 * n);
  kernels::MirrorInX(grid, periodic_x, -1.0, u, m);
  kernels::MirrorInX(grid, periodic_x, 1.0, v, m + n);
  SwNeGradient(grid, periodic_x, periodic_y, m, m + n, m + 2 * n, m + 3 * n, m + 4 * n, m + 5 * n);
  kernels::AverageWithMirrorImage(grid, periodic_x, 1.0, m + 2 * n, l11);
  kernels::AverageWithMirrorImage(grid, periodic_x, -1.0, m + 3 * n, l12);
  kernels::AverageWithMirrorImage(grid, periodic_x, -1.0, m + 4 * n, l21);
  kernels::AverageWithMirrorImage(grid, periodic_x, 1.0, m + 5 * n, l22);
}

}  // namespace dlmfd
