#include "dlmfd/conformation/polymer_force.h"

#include <type_traits>

#include "../mesh/grid_kernels.h"

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

// The integrals on the SW-NE triangles, or with `both` the mean of those on the SW-NE and on the
// NW-SE triangles, added into fx, fy.
void AddMeshPolymerForce(const Grid& grid, bool px, bool py, bool both, double polymer_modulus,
                         const double* a11, const double* a12, const double* a22, double* fx,
                         double* fy) {
  const int nx = grid.nx, ny = grid.ny;
  // |T| grad phi = (h^2/2)(gx, gy)/h: the h cancels to h/2 times the unit-mesh gradients (+-1, 0).
  const double half_h = 0.5 * grid.h;
  // Gather form (grid_kernels.h): node (i, j) sums over its 6 triangles, so rows are written by one
  // thread each; squares counter-clockwise from NE, lower triangle before upper, as the FEM rows.
  const int last_i = px ? nx - 1 : nx;
  const int last_j = py ? ny - 1 : ny;
  // The sum over the (up to 6) triangles of one triangulation around a node, wrapping across
  // periodic sides: sx, sy per unit h/2.
  auto sums = [&](auto diagonal, const kernels::CellsBeside& x, const kernels::CellsBeside& y,
                  double& sx, double& sy) {
    constexpr kernels::Diagonal kD = decltype(diagonal)::value;
    kernels::ForEachTriangleAround<kernels::SquareOrder::kCounterClockwise, kD>(
        x, y, [&](const kernels::TriangleAround& t) {
          const double gx = t.gx, gy = t.gy;
          const MeanStress m = Mean(polymer_modulus, a11, a12, a22, t.k0, t.k1, t.k2);
          sx += gx * m.t11 + gy * m.t12;
          sy += gx * m.t12 + gy * m.t22;
        });
  };
  using SwNe = std::integral_constant<kernels::Diagonal, kernels::Diagonal::kSwNe>;
  using NwSe = std::integral_constant<kernels::Diagonal, kernels::Diagonal::kNwSe>;
  auto any_node = [&](int i, int j) {
    const kernels::CellsBeside x = kernels::OwnCells(i, nx, px);
    const kernels::CellsBeside y = kernels::RowOffsets(grid, kernels::OwnCells(j, ny, py));
    double sx = 0.0, sy = 0.0;
    sums(SwNe{}, x, y, sx, sy);
    double weight = half_h;
    if (both) {
      sums(NwSe{}, x, y, sx, sy);
      weight = 0.5 * half_h;
    }
    const std::size_t k = grid.Index(i, j);
    fx[k] -= weight * sx;
    fy[k] -= weight * sy;
  };
  // Nodes with all 6 triangles inside (1 <= i, j <= n - 1): the same sums collected per neighbour.
  // Each triangle gives (1/3) grad phi_i to each of its vertices; summed over the triangles that
  // share an edge with the node, the unit-gradient weights of the neighbours are, on the SW-NE
  // triangles,
  //   x: E -2, NE -1, N +1, W +2, SW +1, S -1;   y: E +1, NE -1, N -2, W -1, SW +1, S +2,
  // on the NW-SE triangles (the mirror image)
  //   x: E -2, SE -1, S +1, W +2, NW +1, N -1;   y: E -1, NW -1, N -2, W +1, SE +1, S +2,
  // and the node's own weights (and with them the -I of tau_p) sum to zero. Their mean:
  //   x: E -2, W +2, NE and SE -1/2, NW and SW +1/2;  y: N -2, S +2, NE and NW -1/2, SE and SW
  //   +1/2.
  const long row = nx + 1;
  auto dx = [row](const double* a, long k) {
    return -2.0 * a[k + 1] - a[k + row + 1] + a[k + row] + 2.0 * a[k - 1] + a[k - row - 1] -
           a[k - row];
  };
  auto dy = [row](const double* a, long k) {
    return a[k + 1] - a[k + row + 1] - 2.0 * a[k + row] - a[k - 1] + a[k - row - 1] +
           2.0 * a[k - row];
  };
  auto mean_dx = [row](const double* a, long k) {
    return 2.0 * (a[k - 1] - a[k + 1]) +
           0.5 * (a[k + row - 1] + a[k - row - 1] - a[k + row + 1] - a[k - row + 1]);
  };
  auto mean_dy = [row](const double* a, long k) {
    return 2.0 * (a[k - row] - a[k + row]) +
           0.5 * (a[k - row + 1] + a[k - row - 1] - a[k + row + 1] - a[k + row - 1]);
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
    if (both) {
      for (long i = 1; i < nx; ++i) {
        const long k = base + i;
        fx[k] -= scale * (mean_dx(a11, k) + mean_dy(a12, k));
        fy[k] -= scale * (mean_dx(a12, k) + mean_dy(a22, k));
      }
    } else {
      for (long i = 1; i < nx; ++i) {
        const long k = base + i;
        fx[k] -= scale * (dx(a11, k) + dy(a12, k));
        fy[k] -= scale * (dx(a12, k) + dy(a22, k));
      }
    }
    if (last_i == nx) any_node(nx, j);
  }
}

}  // namespace

void AddPolymerForce(const Grid& grid, const DomainParams& domain, double polymer_modulus,
                     const double* a11, const double* a12, const double* a22, double* fx,
                     double* fy) {
  AddMeshPolymerForce(grid, domain.PeriodicX(), domain.PeriodicY(),
                      domain.diagonals == MeshDiagonals::kBoth, polymer_modulus, a11, a12, a22, fx,
                      fy);
}

}  // namespace dlmfd
