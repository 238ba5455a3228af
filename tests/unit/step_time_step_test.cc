// dt reaches every step per call (issue 39 point 2): the steps that build an operator of dt (the
// Stokes step's fast solver, reference floor and flux responses; the advection schemes' implicit
// diffusion; the cut-cell saddle point) build it for the first call's dt and rebuild it when a call
// brings another. A step called with dt_1 and then with dt_2 gives, bit for bit, what a fresh step
// called with dt_2 gives: nothing of dt_1 is left in it.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "../support/cut_cell_creeping.h"
#include "../support/periodic_channel.h"
#include "../support/studied_numerics.h"
#include "dlmfd/core/state.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/fluid/stokes_solver.h"
#include "dlmfd/fluid/velocity_advection.h"
#include "dlmfd/particles/cut_cell_step.h"

namespace dlmfd {
namespace {

constexpr double kFirstDt = 0.01;
constexpr double kSecondDt = 0.004;

// A smooth field that is not a steady solution: every step has work to do.
void Swirl(const Grid& g, std::vector<double>& u, std::vector<double>& v) {
  u.assign(g.NodeCount(), 0.0);
  v.assign(g.NodeCount(), 0.0);
  for (int j = 1; j < g.ny; ++j) {
    for (int i = 1; i < g.nx; ++i) {
      const double x = g.X(i), y = g.Y(j);
      u[g.Index(i, j)] = 0.3 * std::sin(3.0 * x + 0.2) * std::cos(2.0 * y);
      v[g.Index(i, j)] = 0.2 * std::cos(x - 0.5) * std::sin(4.0 * y + 0.1);
    }
  }
}

// A channel periodic along y at a held flow rate, with a polymer: the Stokes step's unit responses
// and its reference floor depend on dt.
Params FluxChannel() {
  Params p = testing::PeriodicChannel(0.05);
  p.fluid.viscosity = 0.1;
  p.fluid.relaxation_time = 0.1;
  p.fluid.solvent_ratio = 0.5;
  p.fluid.body_force = Vec2(0.0, 0.4);
  p.threads = 1;
  return p;
}

struct StokesOutcome {
  std::vector<double> u, v, p;
  StokesReport report;
  Vec2 force = Vec2::Zero();  // F_h of the cut-cell step's body
};

StokesOutcome StokesStep(StokesSolver& stokes, const Grid& g, double dt) {
  StokesOutcome o;
  Swirl(g, o.u, o.v);
  o.p.assign(g.Coarse().NodeCount(), 0.0);
  o.report = stokes.Solve(dt, nullptr, nullptr, o.u.data(), o.v.data(), o.p.data());
  return o;
}

TEST(StepTimeStep, StokesStepRebuildsItsOperatorsWhenDtChanges) {
  const Params p = FluxChannel();
  const Grid g = p.domain.VelocityGrid();
  BoundaryData data(g, p.domain);
  StokesSolver changed(g, p.domain, p.fluid, 1.0, p.solvers, data);
  StokesSolver fresh(g, p.domain, p.fluid, 1.0, p.solvers, data);
  const StokesOutcome first = StokesStep(changed, g, kFirstDt);
  const StokesOutcome second = StokesStep(changed, g, kSecondDt);
  const StokesOutcome built = StokesStep(fresh, g, kSecondDt);
  EXPECT_GT(built.report.iterations, 0);
  EXPECT_NE(first.u, built.u);  // dt matters to this step
  EXPECT_EQ(second.u, built.u);
  EXPECT_EQ(second.v, built.v);
  EXPECT_EQ(second.p, built.p);
  EXPECT_EQ(second.report.iterations, built.report.iterations);
  EXPECT_EQ(second.report.reference, built.report.reference);
  EXPECT_EQ(second.report.mean_pressure_gradient, built.report.mean_pressure_gradient);
  std::vector<double> u, v;
  Swirl(g, u, v);
  EXPECT_EQ(changed.ResidualNorm(kFirstDt, u.data(), v.data()),
            fresh.ResidualNorm(kFirstDt, u.data(), v.data()));
}

// Both advection schemes with the implicit diffusion of (34) (beta > 0), whose fast solver is of
// rho/dt.
TEST(StepTimeStep, AdvectionRebuildsItsDiffusionWhenDtChanges) {
  for (AdvectionScheme scheme : {AdvectionScheme::kLeastSquares, AdvectionScheme::kWave}) {
    Params p;
    testing::UseStudiedNumerics(p);
    p.domain.size = Vec2(1.0, 1.0);
    p.domain.h = 1.0 / 16;
    p.fluid.viscosity = 0.05;
    p.splitting.alpha = 0.5;
    p.splitting.beta = 0.5;
    p.splitting.advection = scheme;
    p.solvers.advection_tolerance = 1e-8;
    p.threads = 1;
    const Grid g = p.domain.VelocityGrid();
    BoundaryData data(g, p.domain);
    const std::unique_ptr<VelocityAdvection> changed = MakeVelocityAdvection(g, p, data);
    const std::unique_ptr<VelocityAdvection> fresh = MakeVelocityAdvection(g, p, data);
    std::vector<double> u1, v1, u2, v2, u3, v3;
    Swirl(g, u1, v1);
    Swirl(g, u2, v2);
    Swirl(g, u3, v3);
    changed->Solve(kFirstDt, u1.data(), v1.data());
    changed->Solve(kSecondDt, u2.data(), v2.data());
    fresh->Solve(kSecondDt, u3.data(), v3.data());
    const int s = static_cast<int>(scheme);
    EXPECT_NE(u1, u3) << "scheme " << s;
    EXPECT_EQ(u2, u3) << "scheme " << s;
    EXPECT_EQ(v2, v3) << "scheme " << s;
  }
}

// The creeping fixed disk of the cut-cell studies at D/h = 10.
TEST(StepTimeStep, CutCellStepRebuildsItsSaddlePointWhenDtChanges) {
  Params p;
  p.domain = CutCreepingChannel(10.0);
  p.fluid.viscosity = 1.0;
  p.particle_mesh.kind = ParticleMeshKind::kCutCell;
  ParticleParams disk;
  disk.center = Vec2(0.2, 0.2);
  disk.diameter = 0.1;
  disk.motion = Motion::kFixed;
  p.particles.push_back(disk);
  p.threads = 1;
  const Grid g = p.domain.VelocityGrid();
  BoundaryData data(g, p.domain);
  CutCellStep changed(p, g), fresh(p, g);
  auto step = [&](CutCellStep& cut, double dt) {
    StokesOutcome o;
    Swirl(g, o.u, o.v);
    o.p.assign(g.Coarse().NodeCount(), 0.0);
    std::vector<ParticleState> particles = {ParticleState{}};
    particles[0].position = disk.center;
    StepReport report;
    cut.Solve(dt, data, particles, o.u.data(), o.v.data(), o.p.data(), report);
    o.force = particles[0].force;
    return o;
  };
  const StokesOutcome first = step(changed, kFirstDt);
  const StokesOutcome second = step(changed, kSecondDt);
  const StokesOutcome built = step(fresh, kSecondDt);
  EXPECT_NE(first.u, built.u);
  EXPECT_EQ(second.u, built.u);
  EXPECT_EQ(second.v, built.v);
  EXPECT_EQ(second.p, built.p);
  EXPECT_EQ(second.force, built.force);
}

}  // namespace
}  // namespace dlmfd
