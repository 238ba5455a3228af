// The polymer force on the fluid part of a cut mesh; see particles/cut_cell_polymer_force.h.
#include "dlmfd/particles/cut_cell_polymer_force.h"

#include <array>
#include <cstddef>

namespace dlmfd {
namespace {

struct Stress {
  double t11, t12, t22;
};

// tau_p = modulus (S - I) at the point of barycentric weights w of the triangle's nodes.
Stress StressAt(double modulus, const std::array<int, 3>& nodes, const std::array<double, 3>& w,
                const double* s11, const double* s12, const double* s22) {
  Stress s{0.0, 0.0, 0.0};
  for (int k = 0; k < 3; ++k) {
    const auto n = static_cast<std::size_t>(nodes[k]);
    s.t11 += w[k] * (s11[n] - 1.0);
    s.t12 += w[k] * s12[n];
    s.t22 += w[k] * (s22[n] - 1.0);
  }
  return Stress{modulus * s.t11, modulus * s.t12, modulus * s.t22};
}

}  // namespace

void AddCutCellPolymerCorrection(const std::vector<const CutCellGeometry*>& geometries,
                                 double modulus, const double* s11, const double* s12,
                                 const double* s22, double* fx, double* fy) {
  if (geometries.empty()) return;
  const double weight = 1.0 / static_cast<double>(geometries.size());
  const Grid& grid = geometries.front()->grid();
  const int row = grid.NodesX();
  const CutPeriodicity periodic = geometries.front()->periodic();
  // A repeated last column or row of a periodic side adds into the first.
  auto fold = [&](int node) {
    int i = node % row, j = node / row;
    if (periodic.x && i == grid.nx) i = 0;
    if (periodic.y && j == grid.ny) j = 0;
    return grid.Index(i, j);
  };
  // f_i += sign * area * grad phi_i : tau over the triangle's nodes.
  auto add = [&](const std::array<int, 3>& nodes, const std::array<Vec2, 3>& grads, double area,
                 const Stress& t, double sign) {
    const double a = sign * weight * area;
    for (int k = 0; k < 3; ++k) {
      const std::size_t n = fold(nodes[k]);
      fx[n] += a * (grads[k].x() * t.t11 + grads[k].y() * t.t12);
      fy[n] += a * (grads[k].x() * t.t12 + grads[k].y() * t.t22);
    }
  };
  const double whole = 0.5 * grid.h * grid.h;
  const std::array<double, 3> mean{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0};
  for (const CutCellGeometry* geo : geometries) {
    // The whole-mesh force holds -|T| grad phi_i : mean tau for every triangle: out with the
    // solid ones' and the cut ones' (the cut ones come back over their fluid polygons below).
    for (int t = 0; t < geo->TriangleCount(); ++t) {
      if (geo->State(t) == ElementState::kFluid) continue;
      const std::array<int, 3> nodes = geo->TriangleNodes(t);
      add(nodes, geo->TriangleGradients(t), whole, StressAt(modulus, nodes, mean, s11, s12, s22),
          +1.0);
    }
    for (const CutTriangle& c : geo->cut_triangles()) {
      Vec2 centre = Vec2::Zero();
      for (int k = 0; k < 3; ++k) {
        const int n = c.nodes[k];
        centre += Vec2(grid.X(n % row), grid.Y(n / row)) / 3.0;
      }
      std::array<double, 3> w{};
      for (int k = 0; k < 3; ++k) w[k] = 1.0 / 3.0 + c.grads[k].dot(c.centroid - centre);
      add(c.nodes, c.grads, c.area, StressAt(modulus, c.nodes, w, s11, s12, s22), -1.0);
    }
  }
}

}  // namespace dlmfd
