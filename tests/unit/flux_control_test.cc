// The flow rate held by the mean pressure gradient (domain.flow_rate, fluid/flux_control.h).
// Plane Poiseuille flow at a given rate in a channel periodic along y: the steady discrete profile
// is the parabola v = G x (W - x) / (2 eta) at the nodes (the P1 stiffness with lumped mass is
// the 3-point stencil, exact on parabolas), whose lumped-mass (trapezoid) rate is
//   Q_h = G (W^3 - h^2 W) / (12 eta),
// so the steady gradient is G = 12 eta Q / (W^3 - h^2 W); the rate is Q at every step to round-off
// (one scalar a step, exact by linearity). A body force along the channel with a zero rate is all
// taken by the gradient: G = -f and the liquid stays at rest. A settling disk's Stokes step holds a
// zero rate to round-off (the snapshots of the tendency correction show u^{n+1/4}). In a box
// periodic in both directions the rates along x and y are held at zero: the unit responses are the
// uniform fields (dt / rho) e_a, so the hold is a shift of the mean; a body force is taken whole
// along both axes, and under a settling disk the Stokes step's mean velocity is zero to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "../support/max_norms.h"
#include "../support/periodic_channel.h"
#include "../support/studied_numerics.h"
#include "dlmfd/core/simulation.h"

namespace dlmfd {
namespace {

class RateLog : public Observer {
 public:
  void OnStep(const FlowState&, const StepReport& report) override {
    gradient.push_back(report.Get("mean_pressure_gradient", NAN));
    rate.push_back(report.Get("flow_rate", NAN));
  }
  std::vector<double> gradient, rate;
};

// A channel W = 1 wide (walls left and right), periodic along y with period 0.5, at rest.
Params PeriodicChannel(double flow_rate) {
  Params p = testing::PeriodicChannel(flow_rate);
  p.fluid.density = 1.0;
  p.fluid.viscosity = 1.0;
  p.time.dt = 0.05;
  p.time.end = 100 * 0.05;
  p.output.fields_every = 0.0;
  p.output.particles_every = 0.0;
  p.output.checkpoint_every = 0.0;
  p.threads = 1;
  return p;
}

TEST(FluxControl, PoiseuilleFlowAtAGivenRate) {
  const double rate = 0.1, eta = 1.0, width = 1.0, h = 1.0 / 16;
  Simulation sim(PeriodicChannel(rate));
  RateLog log;
  sim.AddObserver(&log);
  sim.Run();
  ASSERT_EQ(log.rate.size(), 100u);
  for (double q : log.rate) EXPECT_NEAR(q, rate, 1e-14);
  const double gradient = 12.0 * eta * rate / (width * width * width - h * h * width);
  EXPECT_NEAR(log.gradient.back(), gradient, 1e-12 * gradient);
  const Grid& grid = sim.grid();
  std::vector<double> parabola(grid.NodeCount()), v = sim.state().v;
  for (int j = 0; j <= grid.ny; ++j) {
    for (int i = 0; i <= grid.nx; ++i) {
      const double x = grid.X(i);
      parabola[grid.Index(i, j)] = gradient * x * (width - x) / (2.0 * eta);
    }
  }
  EXPECT_LT(testing::MaxAbsDiff(v, parabola), 1e-12);
  EXPECT_LT(testing::MaxAbs(sim.state().u), 1e-14);
}

TEST(FluxControl, ZeroRateTakesTheBodyForce) {
  Params p = PeriodicChannel(0.0);
  p.fluid.body_force = Vec2(0.0, 3.0);
  p.time.end = 5 * p.time.dt;
  Simulation sim(p);
  RateLog log;
  sim.AddObserver(&log);
  sim.Run();
  for (std::size_t n = 0; n < log.rate.size(); ++n) {
    EXPECT_NEAR(log.gradient[n], -3.0, 1e-13) << "step " << n + 1;
    EXPECT_NEAR(log.rate[n], 0.0, 1e-15) << "step " << n + 1;
  }
  EXPECT_LT(testing::MaxAbs(sim.state().v), 1e-14);
}

// The settling disk of the two tests below: D = 0.2, rho_p / rho = 1.1 at `center`, in a liquid of
// eta = 0.05 under g = 981, with the constraint coupled by `coupling` and the tendency correction,
// 40 steps of 5e-4 with the fields written at every step.
void SettleADisk(ConstraintCoupling coupling, const Vec2& center, Params& p) {
  p.fluid.viscosity = 0.05;
  p.gravity = Vec2(0.0, -981.0);
  p.splitting = SplittingParams::DefaultWeights(coupling);
  testing::UseStudiedNumerics(p.splitting);
  p.splitting.steady_correction = SteadyCorrection::kTendency;
  p.time.dt = 5e-4;
  p.time.end = 40 * 5e-4;
  p.output.fields_every = 5e-4;
  ParticleParams disk;
  disk.center = center;
  disk.diameter = 0.2;
  disk.density = 1.1;
  p.particles.push_back(disk);
}

// The rate of u^{n+1/4}, the Stokes step's velocity that the tendency correction's snapshots show:
// the lumped mass is h^2 at the interior nodes, and the walls' nodes have v = 0. With the round-off
// scale sum |v| h^2 / L beside it.
class StokesRate : public Observer {
 public:
  explicit StokesRate(const Grid& grid)
      : grid_(grid) {}
  void OnSnapshot(const FlowState& state) override {
    double q = 0.0, scale = 0.0;
    for (int j = 0; j < grid_.ny; ++j) {  // the row ny repeats the row 0
      for (int i = 1; i < grid_.nx; ++i) {
        const double v = state.v[grid_.Index(i, j)];
        q += v * grid_.h * grid_.h;
        scale += std::abs(v) * grid_.h * grid_.h;
      }
    }
    rate.push_back(q / grid_.Height());
    round_off.push_back(scale / grid_.Height());
  }
  Grid grid_;
  std::vector<double> rate, round_off;
};

// A disk D = 0.2, rho_p / rho = 1.1, falls in a channel 1 wide, periodic along y with period 2, at
// zero rate (cases/periodic/disk_periodic_zero_flux.toml on h = 1/32), under each coupling of the
// constraint: the rate of the Stokes step's velocity is zero to round-off at every step; the
// gradient then balances the suspension's weight, at least phi (rho_p - rho) |g| = 1.541 (the
// walls' shear adds to it while the liquid beside the disk climbs).
TEST(FluxControl, SettlingDiskAtZeroRate) {
  for (ConstraintCoupling coupling : {ConstraintCoupling::kIncremental, ConstraintCoupling::kPaper,
                                      ConstraintCoupling::kViscous}) {
    Params p = PeriodicChannel(0.0);
    p.domain.size = Vec2(1.0, 2.0);
    p.domain.h = 1.0 / 32;
    SettleADisk(coupling, Vec2(0.5, 1.0), p);
    Simulation sim(p);
    RateLog log;
    StokesRate stokes(sim.grid());
    sim.AddObserver(&log);
    sim.AddObserver(&stokes);
    sim.Run();
    const int c = static_cast<int>(coupling);
    ASSERT_EQ(stokes.rate.size(), 40u) << "coupling " << c;  // every step
    for (std::size_t n = 0; n < stokes.rate.size(); ++n) {
      EXPECT_LE(std::abs(stokes.rate[n]), 1e-13 * stokes.round_off[n])
          << "coupling " << c << ", step " << n + 1;
    }
    const double weight = 0.25 * M_PI * 0.04 * 0.1 * 981.0 / 2.0;
    EXPECT_GT(log.gradient.back(), weight) << "coupling " << c;
    std::printf("coupling %d: G = %.6g, end-of-step rate %.3g, Stokes rate %.3g (scale %.3g)\n", c,
                log.gradient.back(), log.rate.back(), stokes.rate.back(), stokes.round_off.back());
  }
}

// The mean velocity of u^{n+1/4} along x and y over the distinct nodes of a box periodic in both
// directions (equal lumped masses h^2), with the round-off scale mean |u| + |v| beside it.
class StokesMean : public Observer {
 public:
  explicit StokesMean(const Grid& grid)
      : grid_(grid) {}
  void OnSnapshot(const FlowState& state) override {
    double mu = 0.0, mv = 0.0, scale = 0.0;
    for (int j = 0; j < grid_.ny; ++j) {  // the row ny and column nx repeat row and column 0
      for (int i = 0; i < grid_.nx; ++i) {
        const std::size_t k = grid_.Index(i, j);
        mu += state.u[k];
        mv += state.v[k];
        scale += std::abs(state.u[k]) + std::abs(state.v[k]);
      }
    }
    const double count = static_cast<double>(grid_.nx) * grid_.ny;
    mean_u.push_back(mu / count);
    mean_v.push_back(mv / count);
    round_off.push_back(scale / count);
  }
  Grid grid_;
  std::vector<double> mean_u, mean_v, round_off;
};

class BoxRateLog : public Observer {
 public:
  void OnStep(const FlowState&, const StepReport& report) override {
    gradient.emplace_back(report.Get("mean_pressure_gradient_x", NAN),
                          report.Get("mean_pressure_gradient_y", NAN));
    rate.emplace_back(report.Get("flow_rate_x", NAN), report.Get("flow_rate_y", NAN));
  }
  std::vector<Vec2> gradient, rate;
};

Params PeriodicBox() {
  Params p = PeriodicChannel(0.0);
  p.domain.size = Vec2(1.0, 1.0);
  p.domain.h = 1.0 / 32;
  p.domain.sides[static_cast<int>(Side::kLeft)].type = SideType::kPeriodic;
  p.domain.sides[static_cast<int>(Side::kRight)].type = SideType::kPeriodic;
  return p;
}

TEST(FluxControl, BoxTakesTheBodyForceAlongBothAxes) {
  Params p = PeriodicBox();
  p.fluid.body_force = Vec2(2.0, -3.0);
  p.time.end = 5 * p.time.dt;
  Simulation sim(p);
  BoxRateLog log;
  sim.AddObserver(&log);
  sim.Run();
  ASSERT_EQ(log.rate.size(), 5u);
  for (std::size_t n = 0; n < log.rate.size(); ++n) {
    EXPECT_NEAR(log.gradient[n].x(), -2.0, 1e-13) << "step " << n + 1;
    EXPECT_NEAR(log.gradient[n].y(), 3.0, 1e-13) << "step " << n + 1;
    EXPECT_NEAR(log.rate[n].norm(), 0.0, 1e-15) << "step " << n + 1;
  }
  EXPECT_LT(testing::MaxAbs(sim.state().u), 1e-14);
  EXPECT_LT(testing::MaxAbs(sim.state().v), 1e-14);
}

// A disk D = 0.2, rho_p / rho = 1.1 (eta = 0.05, as above) settles in a unit box periodic in both
// directions under each coupling: the Stokes step's mean velocity is zero to round-off along x and
// y at every step, and the gradient along y carries the disk's excess weight.
TEST(FluxControl, BoxHoldsAZeroMeanUnderASettlingDisk) {
  for (ConstraintCoupling coupling : {ConstraintCoupling::kIncremental, ConstraintCoupling::kPaper,
                                      ConstraintCoupling::kViscous}) {
    Params p = PeriodicBox();
    SettleADisk(coupling, Vec2(0.5, 0.5), p);
    Simulation sim(p);
    BoxRateLog log;
    StokesMean stokes(sim.grid());
    sim.AddObserver(&log);
    sim.AddObserver(&stokes);
    sim.Run();
    const int c = static_cast<int>(coupling);
    ASSERT_EQ(stokes.mean_u.size(), 40u) << "coupling " << c;  // every step
    for (std::size_t n = 0; n < stokes.mean_u.size(); ++n) {
      EXPECT_LE(std::abs(stokes.mean_u[n]), 1e-13 * stokes.round_off[n])
          << "coupling " << c << ", step " << n + 1;
      EXPECT_LE(std::abs(stokes.mean_v[n]), 1e-13 * stokes.round_off[n])
          << "coupling " << c << ", step " << n + 1;
    }
    EXPECT_GT(log.gradient.back().y(), 0.0) << "coupling " << c;
    std::printf(
        "coupling %d: G = (%.3g, %.6g) (weight / area %.6g), end-of-step rates (%.3g, %.3g)\n", c,
        log.gradient.back().x(), log.gradient.back().y(), 0.25 * M_PI * 0.04 * 0.1 * 981.0,
        log.rate.back().x(), log.rate.back().y());
  }
}

}  // namespace
}  // namespace dlmfd
