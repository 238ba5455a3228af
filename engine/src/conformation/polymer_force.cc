#include "dlmfd/conformation/polymer_force.h"

#include <algorithm>

#include "../mesh/grid_kernels.h"
#include "../mesh/mirror_image.h"

namespace dlmfd {
namespace {

// Mean of tau_p = G (A - I) over a triangle with vertices k0, k1, k2.
struct MeanStress {
  double t11, t12, t22;
};

inline MeanStress Mean(double modulus, const double* a11, const double* a12, const double* a22,
                       std::size_t k0, std::size_t k1, std::size_t k2) {
  const double third = modulus / 3.0;
  return MeanStress{third * (a11[k0] + a11[k1] + a11[k2] - 3.0),
                    third * (a12[k0] + a12[k1] + a12[k2]),
                    third * (a22[k0] + a22[k1] + a22[k2] - 3.0)};
}

// The integrals on the SW-NE triangles, added into fx, fy.
void AddSwNePolymerForce(const Grid& grid, bool px, bool py, double polymer_modulus,
                         const double* a11, const double* a12, const double* a22, double* fx,
                         double* fy) {
  const int nx = grid.nx, ny = grid.ny;
  // |T| grad phi = (h^2/2)(gx, gy)/h: the h cancels to h/2 times the unit-mesh gradients (+-1, 0).
  const double half_h = 0.5 * grid.h;
  // Gather form (grid_kernels.h): node (i, j) sums over its 6 triangles, so rows are written by one
  // thread each; squares counter-clockwise from NE, T1 before T2, as the FEM rows.
  const int last_i = px ? nx - 1 : nx;
  const int last_j = py ? ny - 1 : ny;
  // Any node: the sum over its (up to 6) triangles, wrapping across periodic sides.
  auto any_node = [&](int i, int j) {
    double sx = 0.0, sy = 0.0;  // sum of (grad phi_i . mean tau) per unit h/2
    const kernels::CellsBeside x = kernels::OwnCells(i, nx, px);
    const kernels::CellsBeside y = kernels::RowOffsets(grid, kernels::OwnCells(j, ny, py));
    kernels::ForEachTriangleAround(x, y, [&](const kernels::TriangleAround& t) {
      const double gx = t.gx, gy = t.gy;
      const MeanStress m = Mean(polymer_modulus, a11, a12, a22, t.k0, t.k1, t.k2);
      sx += gx * m.t11 + gy * m.t12;
      sy += gx * m.t12 + gy * m.t22;
    });
    const std::size_t k = grid.Index(i, j);
    fx[k] -= half_h * sx;
    fy[k] -= half_h * sy;
  };
  // Nodes with all 6 triangles inside (1 <= i, j <= n - 1): the same sums collected per neighbour.
  // Each triangle gives (1/3) grad phi_i to each of its vertices; summed over the triangles that
  // share an edge with the node, the unit-gradient weights of the neighbours are
  //   x: E -2, NE -1, N +1, W +2, SW +1, S -1;   y: E +1, NE -1, N -2, W -1, SW +1, S +2,
  // and the node's own weights (and with them the -I of tau_p) sum to zero.
  const long row = nx + 1;
  auto dx = [row](const double* a, long k) {
    return -2.0 * a[k + 1] - a[k + row + 1] + a[k + row] + 2.0 * a[k - 1] + a[k - row - 1] -
           a[k - row];
  };
  auto dy = [row](const double* a, long k) {
    return a[k + 1] - a[k + row + 1] - 2.0 * a[k + row] - a[k - 1] + a[k - row - 1] +
           2.0 * a[k - row];
  };
  const double scale = half_h * polymer_modulus / 3.0;
#pragma omp parallel for schedule(static)
  for (int j = 0; j <= last_j; ++j) {
    if (j == 0 || j == ny) {
      for (int i = 0; i <= last_i; ++i) any_node(i, j);
      continue;
    }
    any_node(0, j);
    const long base = static_cast<long>(grid.Index(0, j));
    for (long i = 1; i < nx; ++i) {
      const long k = base + i;
      fx[k] -= scale * (dx(a11, k) + dy(a12, k));
      fy[k] -= scale * (dx(a12, k) + dy(a22, k));
    }
    if (last_i == nx) any_node(nx, j);
  }
}

}  // namespace

void AddPolymerForce(const Grid& grid, const DomainParams& domain, double polymer_modulus,
                     const double* a11, const double* a12, const double* a22, double* fx,
                     double* fy) {
  const bool px = domain.PeriodicX(), py = domain.PeriodicY();
  if (domain.diagonals == MeshDiagonals::kSwNe) {
    AddSwNePolymerForce(grid, px, py, polymer_modulus, a11, a12, a22, fx, fy);
    return;
  }
  // Slot 0: the mirrored A, then the NW-SE force; slot 1: the SW-NE force.
  const std::size_t n = grid.NodeCount();
  double *m = kernels::MirrorScratch(0, 5 * n), *f = kernels::MirrorScratch(1, 2 * n);
  kernels::MirrorInX(grid, px, 1.0, a11, m);
  kernels::MirrorInX(grid, px, -1.0, a12, m + n);
  kernels::MirrorInX(grid, px, 1.0, a22, m + 2 * n);
  std::fill(m + 3 * n, m + 5 * n, 0.0);
  AddSwNePolymerForce(grid, px, py, polymer_modulus, m, m + n, m + 2 * n, m + 3 * n, m + 4 * n);
  std::fill(f, f + 2 * n, 0.0);
  AddSwNePolymerForce(grid, px, py, polymer_modulus, a11, a12, a22, f, f + n);
  kernels::AverageWithMirrorImage(grid, px, -1.0, m + 3 * n, f);
  kernels::AverageWithMirrorImage(grid, px, 1.0, m + 4 * n, f + n);
  // The periodic duplicates get none (the mean wrote node 0's value into column nx).
  for (double* fc : {f, f + n}) {
    if (px) {
      for (int j = 0; j <= grid.ny; ++j) fc[grid.Index(grid.nx, j)] = 0.0;
    }
    if (py) std::fill_n(fc + grid.Index(0, grid.ny), grid.nx + 1, 0.0);
  }
#pragma omp parallel for schedule(static) if (n > 16384)
  for (std::size_t k = 0; k < n; ++k) {
    fx[k] += f[k];
    fy[k] += f[n + k];
  }
}

}  // namespace dlmfd
