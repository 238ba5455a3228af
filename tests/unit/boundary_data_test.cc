// Dirichlet data at the corners (fluid/boundary_data.h): a corner of two Dirichlet sides takes from
// each side the component normal to it, so the data's P1 interpolant puts no flux through a wall
// whatever the other side carries (the driven cavity's lid does not leak), and a velocity side
// keeps its whole flux up to its corners.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dlmfd/core/params.h"
#include "dlmfd/fluid/boundary_data.h"

namespace dlmfd {
namespace {

BoundarySide Wall() { return BoundarySide{}; }
BoundarySide Uniform(double ux, double uy) {
  BoundarySide s;
  s.type = SideType::kVelocity;
  s.value = Vec2(ux, uy);
  return s;
}
BoundarySide Outflow() {
  BoundarySide s;
  s.type = SideType::kOutflow;
  return s;
}

DomainParams Box(int cells, BoundarySide left, BoundarySide right, BoundarySide bottom,
                 BoundarySide top) {
  DomainParams d;
  d.size = Vec2(1.0, 1.0);
  d.h = 1.0 / cells;
  d.sides[int(Side::kLeft)] = left;
  d.sides[int(Side::kRight)] = right;
  d.sides[int(Side::kBottom)] = bottom;
  d.sides[int(Side::kTop)] = top;
  return d;
}

struct Data {
  std::vector<double> u, v;
};

Data Apply(const Grid& g, const DomainParams& d) {
  Data out{std::vector<double>(g.NodeCount(), 0.0), std::vector<double>(g.NodeCount(), 0.0)};
  BoundaryData(g, d).Apply(out.u.data(), out.v.data());
  return out;
}

// Outward flux int u_h . n ds of the P1 interpolant through one side (trapezoid rule: exact for
// P1).
double SideFlux(const Grid& g, const Data& f, Side s) {
  const bool vertical = (s == Side::kLeft || s == Side::kRight);
  const int count = vertical ? g.ny : g.nx;
  const double sign = (s == Side::kLeft || s == Side::kBottom) ? -1.0 : 1.0;
  double flux = 0.0;
  for (int k = 0; k <= count; ++k) {
    const int i = vertical ? (s == Side::kLeft ? 0 : g.nx) : k;
    const int j = vertical ? k : (s == Side::kBottom ? 0 : g.ny);
    const double normal = vertical ? f.u[g.Index(i, j)] : f.v[g.Index(i, j)];
    flux += (k == 0 || k == count ? 0.5 : 1.0) * g.h * sign * normal;
  }
  return flux;
}

TEST(BoundaryData, CavityLidCornersTakeTheWallsNormalComponent) {
  const DomainParams d = Box(8, Wall(), Wall(), Wall(), Uniform(1.0, 0.0));
  const Grid g = d.VelocityGrid();
  const Data f = Apply(g, d);
  for (int i : {0, g.nx}) {
    EXPECT_EQ(f.u[g.Index(i, g.ny)], 0.0) << "corner i = " << i;  // the wall's normal component
    EXPECT_EQ(f.v[g.Index(i, g.ny)], 0.0) << "corner i = " << i;  // the lid's normal component
  }
  for (int i = 1; i < g.nx; ++i) EXPECT_EQ(f.u[g.Index(i, g.ny)], 1.0) << i;
  for (Side s : {Side::kLeft, Side::kRight, Side::kBottom}) EXPECT_EQ(SideFlux(g, f, s), 0.0);
}

TEST(BoundaryData, NoFluxThroughWallsAndWholeFluxThroughVelocitySides) {
  // Oblique uniform data on one side, walls or further velocity sides elsewhere.
  const std::vector<DomainParams> cases = {
      Box(8, Uniform(0.3, -0.7), Wall(), Wall(), Wall()),
      Box(8, Wall(), Wall(), Uniform(0.4, 1.0), Outflow()),
      Box(8, Uniform(1.0, 0.5), Uniform(1.0, -0.25), Wall(), Wall()),
      Box(8, Wall(), Uniform(-0.6, 0.2), Uniform(0.1, 0.8), Wall())};
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const DomainParams& d = cases[c];
    const Grid g = d.VelocityGrid();
    const Data f = Apply(g, d);
    for (Side s : {Side::kLeft, Side::kRight, Side::kBottom, Side::kTop}) {
      const BoundarySide& side = d.side(s);
      if (side.type == SideType::kWall) {
        EXPECT_NEAR(SideFlux(g, f, s), 0.0, 1e-15) << "case " << c << " side " << int(s);
      } else if (side.type == SideType::kVelocity) {
        // A uniform side of length 1 with normal velocity value.n: flux value.n exactly.
        const bool vertical = (s == Side::kLeft || s == Side::kRight);
        const double sign = (s == Side::kLeft || s == Side::kBottom) ? -1.0 : 1.0;
        const double normal = vertical ? side.value.x() : side.value.y();
        EXPECT_NEAR(SideFlux(g, f, s), sign * normal, 1e-14) << "case " << c << " side " << int(s);
      }
    }
  }
}

}  // namespace
}  // namespace dlmfd
