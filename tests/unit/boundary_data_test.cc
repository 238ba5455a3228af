// Dirichlet data at the corners (fluid/boundary_data.h): a corner of two Dirichlet sides takes from
// each side the component normal to it, so the data's P1 interpolant puts no flux through a wall
// whatever the other side carries (the driven cavity's lid does not leak), and a velocity side
// keeps its whole flux up to its corners. The quartic profile and the tanh ramp
// (fluid/boundary_profile.h) give the lid of Fattal & Kupferman (2005) at the nodes, at every time
// a step asks for, and leave steady data untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/simulation.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/fluid/boundary_profile.h"

namespace dlmfd {
namespace {

BoundarySide Wall() { return BoundarySide{}; }
BoundarySide Uniform(double ux, double uy) {
  BoundarySide s;
  s.type = SideType::kVelocity;
  s.value = Vec2(ux, uy);
  return s;
}
BoundarySide QuarticLid(double max, double ramp_time) {
  BoundarySide s;
  s.type = SideType::kVelocity;
  s.profile = Profile::kQuartic;
  s.max = Vec2(max, 0.0);
  s.ramp_time = ramp_time;
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

// Fattal & Kupferman (2005), section 4: u(x, t) = 8 [1 + tanh(8 (t - 1/2))] x^2 (1 - x)^2, v = 0.
double FattalKupfermanLid(double x, double t) {
  return 8.0 * (1.0 + std::tanh(8.0 * (t - 0.5))) * x * x * (1.0 - x) * (1.0 - x);
}

// The quartic lid with ramp_time 1/2 is their lid at every node and time. The two formulas differ
// only in the order of the floating-point operations: a few ulps of values <= 1.
TEST(BoundaryData, QuarticRampedLidIsFattalKupfermansLid) {
  const DomainParams d = Box(16, Wall(), Wall(), Wall(), QuarticLid(1.0, 0.5));
  const Grid g = d.VelocityGrid();
  BoundaryData data(g, d);
  EXPECT_EQ(data.MaxSpeed(), 1.0);  // the peak at mid-side, full ramp
  for (double t : {0.0, 0.1, 0.25, 0.5, 0.75, 1.0, 2.0, 8.0}) {
    data.SetTime(t);
    Data f{std::vector<double>(g.NodeCount(), 7.0), std::vector<double>(g.NodeCount(), 7.0)};
    data.Apply(f.u.data(), f.v.data());
    for (int i = 0; i <= g.nx; ++i) {
      const std::size_t id = g.Index(i, g.ny);
      EXPECT_NEAR(f.u[id], FattalKupfermanLid(g.X(i), t), 4e-16) << "t = " << t << " i = " << i;
      EXPECT_EQ(f.v[id], 0.0);
    }
    for (Side s : {Side::kLeft, Side::kRight, Side::kBottom, Side::kTop}) {
      EXPECT_NEAR(SideFlux(g, f, s), 0.0, 1e-15) << "t = " << t;
    }
    for (int j = 0; j < g.ny; ++j) {  // the walls stay at rest
      EXPECT_EQ(f.u[g.Index(0, j)], 0.0);
      EXPECT_EQ(f.u[g.Index(g.nx, j)], 0.0);
    }
  }
  // The ramp: half at t = T, 3.4e-4 at t = 0, within 3.4e-4 of 1 at t = 2T.
  const BoundarySide lid = QuarticLid(1.0, 0.5);
  EXPECT_DOUBLE_EQ(RampFactor(lid, 0.5), 0.5);
  EXPECT_NEAR(RampFactor(lid, 0.0), 0.5 * (1.0 - std::tanh(4.0)), 1e-17);
  EXPECT_NEAR(RampFactor(lid, 1.0), 0.5 * (1.0 + std::tanh(4.0)), 1e-16);
  EXPECT_EQ(RampFactor(QuarticLid(1.0, 0.0), 0.1), 1.0);
}

TEST(BoundaryData, SteadyDataAreTheSameBitForBitAtEveryTime) {
  const DomainParams d = Box(8, Uniform(0.3, -0.7), Wall(), Wall(), QuarticLid(2.0, 0.0));
  const Grid g = d.VelocityGrid();
  const Data before = Apply(g, d);
  BoundaryData data(g, d);
  for (double t : {0.0, 0.5, 3.0, 1e6}) {
    data.SetTime(t);
    Data f{std::vector<double>(g.NodeCount(), 0.0), std::vector<double>(g.NodeCount(), 0.0)};
    data.Apply(f.u.data(), f.v.data());
    EXPECT_EQ(f.u, before.u) << t;
    EXPECT_EQ(f.v, before.v) << t;
  }
  // The quartic profile itself: 16 s^2 (1 - s)^2 max, max at mid-side (the corners' u belongs to
  // the left and right sides).
  for (int i = 1; i < g.nx; ++i) {
    const double s = static_cast<double>(i) / g.nx;
    EXPECT_DOUBLE_EQ(before.u[g.Index(i, g.ny)], 2.0 * 16.0 * s * s * (1.0 - s) * (1.0 - s)) << i;
  }
  EXPECT_EQ(before.u[g.Index(g.nx / 2, g.ny)], 2.0);
}

// In a run, each step's data are those of its new time level t_{n+1} = (n + 1) dt (the Stokes
// step (33) and the advection (34) write them into u).
TEST(BoundaryData, SimulationStepsCarryTheDataOfTheirNewTimeLevel) {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain = Box(8, Wall(), Wall(), Wall(), QuarticLid(1.0, 0.5));
  p.fluid.density = 0.01;
  p.fluid.viscosity = 1.0;
  p.splitting.alpha = 1.0;
  p.splitting.beta = 0.0;
  p.time.dt = 0.05;
  p.time.end = 1.0;
  p.output.fields_every = 0.0;
  p.output.checkpoint_every = 0.0;
  p.threads = 1;
  Simulation sim(p);
  const Grid& g = sim.grid();
  for (int n = 0; n <= 12; ++n) {
    if (n > 0) sim.Step();
    const double t = sim.state().time;
    for (int i = 0; i <= g.nx; ++i) {
      EXPECT_NEAR(sim.state().u[g.Index(i, g.ny)], FattalKupfermanLid(g.X(i), t), 4e-16)
          << "step " << n << " i = " << i;
    }
  }
}

}  // namespace
}  // namespace dlmfd
