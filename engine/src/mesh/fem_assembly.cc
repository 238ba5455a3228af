// Assembled reference matrices from element integrals, written independently of the stencil
// kernels: a loop over the triangles of the mesh, P1 basis gradients from vertex coordinates, and
// exact integrals (|T|/12 (1 + delta_ij) for the mass, |T| grad phi_i . grad phi_j for the
// stiffness, |T|/3 d phi_j for the P1-P1 gradient). For the divergence the pressure basis is
// evaluated at the vertices of each h-triangle through barycentric coordinates in the 2h-triangle
// that contains it (exact: q_Q is linear there). Periodic duplicates are folded into the first
// node. The forms that domain.diagonals = "both" averages (G, B) are assembled on either
// triangulation (the squares' SW-NE or NW-SE diagonals) from their own triangles, independently of
// the mirror image through which the stencil code evaluates the NW-SE forms.
#include <array>
#include <cmath>
#include <vector>

#include "dlmfd/mesh/fem_operators.h"

namespace dlmfd {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

struct Triangle {
  std::array<int, 3> dof;  // folded node indices
  std::array<double, 3> x, y;
  double area = 0.0;
  std::array<double, 3> dx, dy;  // gradients of the three P1 basis functions
};

// Node index with the periodic duplicate folded into the first line.
int FoldedIndex(const Grid& grid, const BoundaryTopology& topo, int i, int j) {
  if (topo.x.low == EndKind::kPeriodic && i == grid.nx) i = 0;
  if (topo.y.low == EndKind::kPeriodic && j == grid.ny) j = 0;
  return static_cast<int>(grid.Index(i, j));
}

Triangle MakeTriangle(const Grid& grid, const BoundaryTopology& topo,
                      const std::array<std::array<int, 2>, 3>& corners) {
  Triangle t;
  for (int k = 0; k < 3; ++k) {
    t.dof[k] = FoldedIndex(grid, topo, corners[k][0], corners[k][1]);
    t.x[k] = grid.X(corners[k][0]);
    t.y[k] = grid.Y(corners[k][1]);
  }
  const double twice_area =
      (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.x[2] - t.x[0]) * (t.y[1] - t.y[0]);
  t.area = 0.5 * std::abs(twice_area);
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    t.dx[k] = (t.y[k1] - t.y[k2]) / twice_area;
    t.dy[k] = (t.x[k2] - t.x[k1]) / twice_area;
  }
  return t;
}

// The two triangles of the square (i, j) of a grid: below and above its SW-NE diagonal, or (NW-SE)
// below-left and above-right of the other.
std::array<Triangle, 2> SquareTriangles(const Grid& grid, const BoundaryTopology& topo, int i,
                                        int j, bool nw_se) {
  if (nw_se) {
    return {MakeTriangle(grid, topo, {{{i, j}, {i + 1, j}, {i, j + 1}}}),
            MakeTriangle(grid, topo, {{{i + 1, j}, {i + 1, j + 1}, {i, j + 1}}})};
  }
  return {MakeTriangle(grid, topo, {{{i, j}, {i + 1, j}, {i + 1, j + 1}}}),
          MakeTriangle(grid, topo, {{{i, j}, {i + 1, j + 1}, {i, j + 1}}})};
}

// The triangles of every h-square of a grid.
std::vector<Triangle> Triangles(const Grid& grid, const BoundaryTopology& topo,
                                bool nw_se = false) {
  std::vector<Triangle> out;
  out.reserve(std::size_t(2) * grid.nx * grid.ny);
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      for (const Triangle& t : SquareTriangles(grid, topo, i, j, nw_se)) out.push_back(t);
    }
  }
  return out;
}

// The mean of a form assembled on both triangulations (MeshDiagonals::kBoth), or the SW-NE one's.
template <typename Form>
Eigen::SparseMatrix<double> OnDiagonals(MeshDiagonals diagonals, Form&& form) {
  if (diagonals == MeshDiagonals::kSwNe) return form(false);
  return 0.5 * (form(false) + form(true));
}

Eigen::SparseMatrix<double> FromTriplets(std::size_t rows, std::size_t cols,
                                         const Triplets& entries) {
  Eigen::SparseMatrix<double> m(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  m.setFromTriplets(entries.begin(), entries.end());
  return m;
}

// Barycentric coordinates of (px, py) in triangle t.
std::array<double, 3> Barycentric(const Triangle& t, double px, double py) {
  std::array<double, 3> l;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    l[k] = t.dx[k] * (px - t.x[k1]) + t.dy[k] * (py - t.y[k1]);
  }
  return l;
}

// B_c(Q, j) = int q_Q d_c phi_j, c = 0 (x) or 1 (y).
Eigen::SparseMatrix<double> AssembleDivergence(const Grid& grid,
                                               const BoundaryTopology& pressure_topo, int component,
                                               bool nw_se) {
  const Grid coarse = grid.Coarse();
  Triplets entries;
  for (const Triangle& t : Triangles(grid, pressure_topo, nw_se)) {
    const double cx = (t.x[0] + t.x[1] + t.x[2]) / 3.0, cy = (t.y[0] + t.y[1] + t.y[2]) / 3.0;
    const int ci = static_cast<int>(std::floor((cx - coarse.x0) / coarse.h));
    const int cj = static_cast<int>(std::floor((cy - coarse.y0) / coarse.h));
    // The 2h-triangle that holds t: the first of the 2h-square's two below its diagonal.
    const double sx = (cx - coarse.X(ci)) / coarse.h, sy = (cy - coarse.Y(cj)) / coarse.h;
    const bool first = nw_se ? sx + sy < 1.0 : sx > sy;
    const Triangle coarse_t = SquareTriangles(coarse, pressure_topo, ci, cj, nw_se)[first ? 0 : 1];
    std::array<double, 3> q_sum{0.0, 0.0, 0.0};  // sum over the fine vertices of each q_Q
    for (int v = 0; v < 3; ++v) {
      const std::array<double, 3> l = Barycentric(coarse_t, t.x[v], t.y[v]);
      for (int k = 0; k < 3; ++k) q_sum[k] += l[k];
    }
    for (int k = 0; k < 3; ++k) {
      for (int m = 0; m < 3; ++m) {
        const double grad = component == 0 ? t.dx[m] : t.dy[m];
        entries.emplace_back(coarse_t.dof[k], t.dof[m], t.area / 3.0 * q_sum[k] * grad);
      }
    }
  }
  return FromTriplets(coarse.NodeCount(), grid.NodeCount(), entries);
}

// G_c(i, j) = int phi_i d_c phi_j, c = 0 (x) or 1 (y).
Eigen::SparseMatrix<double> AssembleGradient(const Grid& grid, const BoundaryTopology& topo,
                                             int component, bool nw_se) {
  Triplets entries;
  for (const Triangle& t : Triangles(grid, topo, nw_se)) {
    for (int k = 0; k < 3; ++k) {
      for (int m = 0; m < 3; ++m) {
        entries.emplace_back(t.dof[k], t.dof[m],
                             t.area / 3.0 * (component == 0 ? t.dx[m] : t.dy[m]));
      }
    }
  }
  return FromTriplets(grid.NodeCount(), grid.NodeCount(), entries);
}

}  // namespace

Eigen::SparseMatrix<double> AssembleConsistentMass(const Grid& grid, const BoundaryTopology& topo) {
  Triplets entries;
  for (const Triangle& t : Triangles(grid, topo)) {
    for (int k = 0; k < 3; ++k) {
      for (int m = 0; m < 3; ++m)
        entries.emplace_back(t.dof[k], t.dof[m], t.area / 12.0 * (k == m ? 2.0 : 1.0));
    }
  }
  return FromTriplets(grid.NodeCount(), grid.NodeCount(), entries);
}

Eigen::SparseMatrix<double> AssembleStiffness(const Grid& grid, const BoundaryTopology& topo) {
  Triplets entries;
  for (const Triangle& t : Triangles(grid, topo)) {
    for (int k = 0; k < 3; ++k) {
      for (int m = 0; m < 3; ++m) {
        entries.emplace_back(t.dof[k], t.dof[m], t.area * (t.dx[k] * t.dx[m] + t.dy[k] * t.dy[m]));
      }
    }
  }
  return FromTriplets(grid.NodeCount(), grid.NodeCount(), entries);
}

Eigen::SparseMatrix<double> AssembleGradientX(const Grid& grid, const BoundaryTopology& topo,
                                              MeshDiagonals diagonals) {
  return OnDiagonals(diagonals, [&](bool nw_se) { return AssembleGradient(grid, topo, 0, nw_se); });
}

Eigen::SparseMatrix<double> AssembleGradientY(const Grid& grid, const BoundaryTopology& topo,
                                              MeshDiagonals diagonals) {
  return OnDiagonals(diagonals, [&](bool nw_se) { return AssembleGradient(grid, topo, 1, nw_se); });
}

Eigen::SparseMatrix<double> AssembleDivergenceX(const Grid& grid,
                                                const BoundaryTopology& pressure_topo,
                                                MeshDiagonals diagonals) {
  return OnDiagonals(diagonals,
                     [&](bool nw_se) { return AssembleDivergence(grid, pressure_topo, 0, nw_se); });
}

Eigen::SparseMatrix<double> AssembleDivergenceY(const Grid& grid,
                                                const BoundaryTopology& pressure_topo,
                                                MeshDiagonals diagonals) {
  return OnDiagonals(diagonals,
                     [&](bool nw_se) { return AssembleDivergence(grid, pressure_topo, 1, nw_se); });
}

}  // namespace dlmfd
