// OldroydBPolymer, the conformation module's coupling to the time loop: it exists only for a
// viscoelastic liquid, its modulus is eta_p / lambda, A^0 follows the same inflow rule as every
// step (also at a corner of two velocity sides), its force on (33) is the polymer force of A, and
// step (35) puts A = I at the nodes inside the particles, across periodic sides.
#include "dlmfd/conformation/oldroyd_b_polymer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/conformation/inflow_state.h"
#include "dlmfd/conformation/polymer_force.h"
#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

BoundarySide PolymerSide(SideType type, Profile profile = Profile::kUniform,
                         Vec2 max = Vec2::Zero()) {
  BoundarySide s;
  s.type = type;
  s.profile = profile;
  s.max = max;
  return s;
}

Params Box(int n, SideType type, double lambda) {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(1.0, 1.0);
  p.domain.h = 1.0 / n;
  for (auto& side : p.domain.sides) side = PolymerSide(type);
  p.fluid.viscosity = 1.2;
  p.fluid.solvent_ratio = 0.25;
  p.fluid.relaxation_time = lambda;
  return p;
}

Grid GridOf(int n) { return Grid{n, n, 1.0 / n, 0.0, 0.0}; }

FlowState RestState(const Grid& g) {
  FlowState s;
  s.u.assign(g.NodeCount(), 0.0);
  s.v.assign(g.NodeCount(), 0.0);
  s.p.assign(g.Coarse().NodeCount(), 0.0);
  return s;
}

TEST(OldroydBPolymer, ANewtonianLiquidHasNone) {
  const Grid g = GridOf(4);
  Params p = Box(4, SideType::kWall, 0.0);
  EXPECT_THROW(OldroydBPolymer(p, g), InvalidParameter);
  p.fluid.relaxation_time = 1.0;
  p.fluid.solvent_ratio = 1.0;
  EXPECT_THROW(OldroydBPolymer(p, g), InvalidParameter);
}

TEST(OldroydBPolymer, ModulusAndForceOnTheMomentumEquation) {
  const int n = 8;
  const Grid g = GridOf(n);
  const Params p = Box(n, SideType::kWall, 0.6);
  OldroydBPolymer polymer(p, g);
  EXPECT_EQ(polymer.modulus(), p.fluid.PolymerViscosity() / p.fluid.relaxation_time);
  FlowState s = RestState(g);
  polymer.SetInitialState(s);
  // A = I: no stress, no force.
  NodeForce f = polymer.MomentumForce(s);
  for (std::size_t k = 0; k < g.NodeCount(); ++k) {
    ASSERT_EQ(f.x[k], 0.0);
    ASSERT_EQ(f.y[k], 0.0);
  }
  // Any A: the polymer force with the modulus, bit for bit (the arrays are refilled, not added to).
  for (std::size_t k = 0; k < g.NodeCount(); ++k) {
    s.a11[k] = 1.5 + std::sin(0.3 * k);
    s.a12[k] = 0.2 * std::cos(0.7 * k);
    s.a22[k] = 1.2 + 0.1 * std::sin(1.1 * k);
  }
  std::vector<double> fx(g.NodeCount(), 0.0), fy(g.NodeCount(), 0.0);
  AddPolymerForce(g, p.domain, polymer.modulus(), s.a11.data(), s.a12.data(), s.a22.data(),
                  fx.data(), fy.data());
  polymer.MomentumForce(s);
  f = polymer.MomentumForce(s);
  for (std::size_t k = 0; k < g.NodeCount(); ++k) {
    ASSERT_EQ(f.x[k], fx[k]) << k;
    ASSERT_EQ(f.y[k], fy[k]) << k;
  }
}

// Left side: poiseuille inflow (sheared, so A_L is not I); bottom side: a uniform velocity side
// out of which the liquid leaves; u = (1, -1) everywhere. The corner (0, 0) lies on both: the
// liquid enters through the left side there, so it takes the left side's A_L, at t = 0 and after a
// step alike.
TEST(OldroydBPolymer, InitialStateFollowsTheInflowRuleOfEveryStep) {
  const int n = 8;
  const double lambda = 0.5;
  const Grid g = GridOf(n);
  Params p = Box(n, SideType::kWall, lambda);
  p.domain.sides[int(Side::kLeft)] =
      PolymerSide(SideType::kVelocity, Profile::kPoiseuille, Vec2(1.0, 0.0));
  p.domain.sides[int(Side::kRight)] = PolymerSide(SideType::kOutflow);
  p.domain.sides[int(Side::kBottom)] = PolymerSide(SideType::kVelocity);
  OldroydBPolymer polymer(p, g);
  FlowState s = RestState(g);
  for (std::size_t k = 0; k < g.NodeCount(); ++k) {
    s.u[k] = 1.0;
    s.v[k] = -1.0;
  }
  polymer.SetInitialState(s);
  auto expect_inflow = [&](const FlowState& state, const char* when) {
    for (int j = 0; j <= n; ++j) {
      const std::size_t k = g.Index(0, j);
      const SymTensor a = InflowConformation(g, p.domain, Side::kLeft, j, lambda);
      ASSERT_EQ(state.a11[k], a.a11) << when << " j = " << j;
      ASSERT_EQ(state.a12[k], a.a12) << when << " j = " << j;
      ASSERT_EQ(state.a22[k], a.a22) << when << " j = " << j;
    }
  };
  expect_inflow(s, "initial");
  EXPECT_GT(std::abs(s.a12[g.Index(0, 0)]), 0.1);  // the corner is sheared, not I
  for (int i = 1; i <= n; ++i) EXPECT_EQ(s.a12[g.Index(i, 0)], 0.0) << i;  // bottom: outflowing
  StepReport report;
  polymer.Update(0.01, s, report);
  expect_inflow(s, "after a step");
}

TEST(OldroydBPolymer, IdentityInsideParticlesAcrossPeriodicSides) {
  const int n = 16;
  const double lambda = 1.0, dt = 0.01;
  const Grid g = GridOf(n);
  Params p = Box(n, SideType::kPeriodic, lambda);
  ParticleParams disk;
  disk.center = Vec2(0.02, 0.98);  // near the corner: the disk wraps across both periodic pairs
  disk.diameter = 0.3;
  p.particles.push_back(disk);
  OldroydBPolymer polymer(p, g);
  FlowState s = RestState(g);
  polymer.SetInitialState(s);
  for (std::size_t k = 0; k < g.NodeCount(); ++k) s.a11[k] = s.a22[k] = 3.0;
  ParticleState q;
  q.position = disk.center;
  q.radius = 0.5 * disk.diameter;
  s.particles.push_back(q);
  StepReport report;
  polymer.Update(dt, s, report);
  int inside = 0;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      // Minimum-image distance to the centre.
      double dx = std::abs(g.X(i) - q.position.x()), dy = std::abs(g.Y(j) - q.position.y());
      dx = std::min(dx, 1.0 - dx);
      dy = std::min(dy, 1.0 - dy);
      const std::size_t k = g.Index(i, j);
      if (dx * dx + dy * dy < q.radius * q.radius) {
        ++inside;
        EXPECT_EQ(s.a11[k], 1.0) << i << ", " << j;
        EXPECT_EQ(s.a22[k], 1.0) << i << ", " << j;
      } else {
        EXPECT_NEAR(s.a11[k], 1.0 + 2.0 * std::exp(-dt / lambda), 1e-14) << i << ", " << j;
      }
    }
  }
  EXPECT_GT(inside, 8);
}

}  // namespace
}  // namespace dlmfd
