// The Stokes step (33) with the rigid-body constraint in it (splitting.constraint = "viscous",
// particles/viscous_constraint.h): after the coupled solve the velocity is rigid at every
// multiplier point to the tolerance (checked with a separate coupling operator E) and
// divergence-free to the Uzawa tolerance; the hydrodynamic force of the whole step, (33) and (37)
// together, satisfies the momentum identity of method notes 2, 1.6; a fixed disk in a liquid at
// rest stays at rest. Small grids, a non-rigid start.
#include "dlmfd/particles/viscous_constraint.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/fluid/stokes_solver.h"
#include "dlmfd/particles/particle_step.h"
#include "dlmfd/particles/rigid_body_constraint.h"

namespace dlmfd {
namespace {

Params Box(double dt) {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(1.0, 1.0);
  p.domain.h = 1.0 / 32;
  for (auto& side : p.domain.sides) side.type = SideType::kWall;
  p.particle_mesh.h = p.domain.h * 96.0 / 70.0;
  p.fluid.density = 1.0;
  p.fluid.viscosity = 0.1;
  p.time.dt = dt;
  p.splitting.alpha = 1.0;
  p.splitting.beta = 0.0;
  p.splitting.constraint = ConstraintCoupling::kViscous;
  p.solvers.stokes_tolerance = 1e-8;
  p.solvers.multiplier_tolerance = 1e-6;
  return p;
}

ParticleParams Disk(Vec2 centre, double density, Vec2 velocity, double omega, Motion motion) {
  ParticleParams d;
  d.center = centre;
  d.diameter = 0.3;
  d.density = density;
  d.velocity = velocity;
  d.angular_velocity = omega;
  d.motion = motion;
  return d;
}

// A non-rigid start: a smooth solenoidal swirl, zero on the walls.
void SolenoidalSwirl(const Grid& g, std::vector<double>& u, std::vector<double>& v) {
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const double x = kPi * g.X(i), y = kPi * g.Y(j);
      u[g.Index(i, j)] = std::sin(x) * std::sin(x) * std::sin(2 * y);
      v[g.Index(i, j)] = -std::sin(2 * x) * std::sin(y) * std::sin(y);
    }
  }
}

struct CoupledRun {
  Params params;
  Grid grid;
  BoundaryData data;
  StokesSolver stokes;
  ParticleStep step;
  std::vector<ParticleState> particles;
  std::vector<double> u, v, p;
  StepReport report;

  explicit CoupledRun(const Params& prm)
      : params(prm),
        grid(prm.domain.VelocityGrid()),
        data(grid, prm.domain),
        stokes(grid, prm.domain, prm.fluid, prm.splitting.alpha, prm.solvers, data),
        step(prm, grid),
        particles(ParticleStep::InitialStates(prm)),
        u(grid.NodeCount(), 0.0),
        v(grid.NodeCount(), 0.0),
        p(grid.Coarse().NodeCount(), 0.0) {}
};

TEST(ViscousConstraint, StokesStepIsRigidAtTheMultiplierPointsAndDivergenceFree) {
  Params params = Box(1e-2);  // nu dt / h^2 = 1.0
  params.particles.push_back(Disk(Vec2(0.37, 0.52), 1.5, Vec2(0.2, -0.1), 0.7, Motion::kFree));
  params.particles.push_back(Disk(Vec2(0.71, 0.43), 1.0, Vec2::Zero(), 0.0, Motion::kFixed));
  CoupledRun run(params);
  ASSERT_TRUE(run.step.CouplesStokes());
  SolenoidalSwirl(run.grid, run.u, run.v);
  const ViscousConstraint::Outcome out =
      run.step.CoupleStokes(params.time.dt, params.time.dt, run.stokes, nullptr, nullptr,
                            run.particles, run.u.data(), run.v.data(), run.p.data());
  EXPECT_GT(out.iterations, 0);
  EXPECT_EQ(run.particles[1].velocity.norm(), 0.0);  // fixed stays fixed
  EXPECT_NE(run.particles[0].velocity, Vec2(0.2, -0.1));

  // E u = U + omega r_perp at every point, by a separate E.
  RigidBodyConstraint check(params, run.grid);
  check.Locate(0.0, params.time.dt, run.particles);
  const MultiplierPoints& points = check.points();
  double speed = 0.0;
  for (std::size_t k = 0; k < run.u.size(); ++k)
    speed = std::max(speed, std::hypot(run.u[k], run.v[k]));
  for (std::size_t q = 0; q < points.ParticleCount(); ++q) {
    const ParticleState& disk = run.particles[q];
    speed = std::max(speed, disk.velocity.norm() + std::abs(disk.angular_velocity) * disk.radius);
  }
  double worst = 0.0;
  for (std::size_t q = 0; q < points.ParticleCount(); ++q) {
    const ParticleState& disk = run.particles[q];
    for (int k = 0; k < points.Count(q); ++k) {
      double eu, ev;
      check.coupling().Interpolate(points.Begin(q) + k, run.u.data(), run.v.data(), eu, ev);
      const Vec2 rigid =
          disk.velocity + disk.angular_velocity * RigidModes::Perp(points.Points(q)[k]);
      worst = std::max(worst, (Vec2(eu, ev) - rigid).norm());
    }
  }
  EXPECT_LE(worst, params.solvers.multiplier_tolerance * speed);
  EXPECT_LE(out.residual, params.solvers.multiplier_tolerance);
  // Divergence: each Stokes solve stops at 1e-8 of its own velocity; the combination is as small.
  EXPECT_LT(run.stokes.DivergenceNorm(run.u.data(), run.v.data()), 1e-6);
}

TEST(ViscousConstraint, HydrodynamicForceOfTheWholeStepSatisfiesTheMomentumIdentity) {
  Params params = Box(4e-3);
  params.gravity = Vec2(0.0, -981.0);
  params.particles.push_back(Disk(Vec2(0.37, 0.52), 1.5, Vec2(0.2, -0.1), 0.7, Motion::kFree));
  CoupledRun run(params);
  SolenoidalSwirl(run.grid, run.u, run.v);
  for (int n = 0; n < 3; ++n) {
    const ParticleState before = run.particles[0];
    const double dt = params.time.dt;
    run.step.CoupleStokes((n + 1) * dt, dt, run.stokes, nullptr, nullptr, run.particles,
                          run.u.data(), run.v.data(), run.p.data());
    run.step.Advance(n * dt, dt, run.particles, run.u.data(), run.v.data(), run.report);
    const ParticleState& after = run.particles[0];
    const double mass = after.density * kPi * after.radius * after.radius;
    const double inertia = mass * after.radius * after.radius / 2;
    const Vec2 collision = run.step.CollisionForceAverage()[0];
    const Vec2 expected =
        mass * (after.velocity - before.velocity) / dt - mass * params.gravity - collision;
    // An algebraic identity: equal up to the round-off of terms of size M g divided by dt.
    EXPECT_NEAR((after.force - expected).norm(), 0.0, 1e-11 * mass * params.gravity.norm());
    EXPECT_NEAR(after.torque, inertia * (after.angular_velocity - before.angular_velocity) / dt,
                1e-11 * (std::abs(after.torque) + inertia / dt));
    EXPECT_GT(std::abs(after.torque), 0.0);
  }
}

TEST(ViscousConstraint, FixedDiskInALiquidAtRestStaysAtRest) {
  Params params = Box(1e-2);
  params.particles.push_back(Disk(Vec2(0.5, 0.5), 1.0, Vec2::Zero(), 0.0, Motion::kFixed));
  CoupledRun run(params);
  for (int n = 0; n < 5; ++n) {
    const ViscousConstraint::Outcome out =
        run.step.CoupleStokes((n + 1) * 1e-2, 1e-2, run.stokes, nullptr, nullptr, run.particles,
                              run.u.data(), run.v.data(), run.p.data());
    EXPECT_EQ(out.iterations, 0);
    run.step.Advance(n * 1e-2, 1e-2, run.particles, run.u.data(), run.v.data(), run.report);
  }
  EXPECT_EQ(*std::max_element(run.u.begin(), run.u.end()), 0.0);
  EXPECT_EQ(*std::min_element(run.v.begin(), run.v.end()), 0.0);
  EXPECT_EQ(run.particles[0].force.norm(), 0.0);
}

}  // namespace
}  // namespace dlmfd
