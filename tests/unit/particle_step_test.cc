// The particle step (36)-(38) as a whole: rest stays rest, translation is untouched, the force
// identity of method notes 2, 1.6, collisions keep disks apart, overlaps end the run with ids, time
// and gap. Synthetic velocity fields; the fluid changes only through (37) (no fluid solver).
#include "dlmfd/particles/particle_step.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

Params Scene(double size, double h, bool periodic,
             ParticleMeshKind kind = ParticleMeshKind::kRing) {
  Params params;
  testing::UseStudiedNumerics(params);
  params.particle_mesh.kind = kind;
  params.domain.size = Vec2(size, size);
  params.domain.h = h;
  for (auto& side : params.domain.sides)
    side.type = periodic ? SideType::kPeriodic : SideType::kWall;
  params.particle_mesh.h = h * 96.0 / 70.0;  // the paper's ratio h_p / h
  params.time.dt = 4e-4;
  return params;
}

ParticleParams Disk(Vec2 centre, double density, Vec2 velocity = Vec2::Zero()) {
  ParticleParams p;
  p.center = centre;
  p.diameter = 0.2;
  p.density = density;
  p.velocity = velocity;
  return p;
}

Grid GridOf(const Params& p) {
  const int n = static_cast<int>(std::lround(p.domain.size.x() / p.domain.h));
  return Grid{n, n, p.domain.h, 0.0, 0.0};
}

struct SceneRun {
  Params params;
  Grid grid;
  ParticleStep step;
  std::vector<ParticleState> particles;
  std::vector<double> u, v;
  StepReport report;
  long n = 0;

  explicit SceneRun(const Params& p)
      : params(p),
        grid(GridOf(p)),
        step(p, grid),
        particles(ParticleStep::InitialStates(p)),
        u(grid.NodeCount(), 0.0),
        v(grid.NodeCount(), 0.0) {}
  void Advance() {
    step.Advance(n * params.time.dt, params.time.dt, particles, u.data(), v.data(), report);
    ++n;
  }
  // A non-rigid liquid: a smooth field on the interior nodes, zero on the walls.
  void NonRigidField() {
    for (int j = 1; j < grid.ny; ++j) {
      for (int i = 1; i < grid.nx; ++i) {
        const double x = grid.X(i), y = grid.Y(j);
        u[grid.Index(i, j)] = std::sin(2 * kPi * x) * std::sin(2 * kPi * y);
        v[grid.Index(i, j)] = std::cos(3 * x) * std::sin(2 * kPi * y);
      }
    }
  }
};

// Two disks 0.02 apart, inside each other's collision range, under gravity in a unit box of walls
// (h = 1/48): the first of density first_density moving right, the second of 1.5 up and left.
Params DisksInContact(double first_density, ParticleMeshKind kind) {
  Params params = Scene(1.0, 1.0 / 48, false, kind);
  params.gravity = Vec2(0.0, -981.0);
  params.particles.push_back(Disk(Vec2(0.4, 0.45), first_density, Vec2(0.2, 0.0)));
  params.particles.push_back(Disk(Vec2(0.4 + 0.2 + 0.02, 0.47), 1.5, Vec2(-0.1, 0.1)));
  return params;
}

// The properties that hold for both multiplier point sets: the ring mesh and the collocation points
// (quadratic at the boundary points).
class ParticleStepOnEachMesh : public ::testing::TestWithParam<ParticleMeshKind> {};

INSTANTIATE_TEST_SUITE_P(Meshes, ParticleStepOnEachMesh,
                         ::testing::Values(ParticleMeshKind::kRing, ParticleMeshKind::kCollocation),
                         [](const ::testing::TestParamInfo<ParticleMeshKind>& mesh) {
                           return mesh.param == ParticleMeshKind::kRing ? "ring" : "collocation";
                         });

TEST_P(ParticleStepOnEachMesh, DiskAtRestInLiquidAtRestStaysAtRest) {
  Params params = Scene(1.0, 1.0 / 48, false, GetParam());
  params.particles.push_back(Disk(Vec2(0.5137, 0.4871), 1.01));
  SceneRun run(params);
  for (int k = 0; k < 50; ++k) run.Advance();
  const ParticleState& p = run.particles[0];
  EXPECT_EQ(p.velocity.norm(), 0.0);
  EXPECT_EQ(p.angular_velocity, 0.0);
  EXPECT_EQ((p.position - Vec2(0.5137, 0.4871)).norm(), 0.0);
  EXPECT_EQ(p.force.norm(), 0.0);
  EXPECT_EQ(*std::max_element(run.u.begin(), run.u.end()), 0.0);
  EXPECT_EQ(*std::min_element(run.v.begin(), run.v.end()), 0.0);
}

TEST_P(ParticleStepOnEachMesh, UniformTranslationOfFluidAndDiskIsLeftUnchanged) {
  Params params =
      Scene(1.0, 1.0 / 48, true, GetParam());  // periodic: the uniform field is admissible
  const Vec2 velocity(0.3, -0.1);
  params.particles.push_back(Disk(Vec2(0.5137, 0.4871), 1.5, velocity));
  SceneRun run(params);
  std::fill(run.u.begin(), run.u.end(), velocity.x());
  std::fill(run.v.begin(), run.v.end(), velocity.y());
  const int steps = 2000;  // 0.8 time units: the disk crosses the periodic sides
  for (int k = 0; k < steps; ++k) run.Advance();
  const ParticleState& p = run.particles[0];
  EXPECT_NEAR((p.velocity - velocity).norm(), 0.0, 1e-14);
  EXPECT_NEAR(p.angular_velocity, 0.0, 1e-12);
  for (std::size_t q = 0; q < run.u.size(); ++q) {
    ASSERT_NEAR(run.u[q], velocity.x(), 1e-14);
    ASSERT_NEAR(run.v[q], velocity.y(), 1e-14);
  }
  Vec2 expected = Vec2(0.5137, 0.4871) + steps * 4e-4 * velocity;
  expected -= expected.array().floor().matrix();  // wrapped into [0, 1)^2
  EXPECT_NEAR((p.position - expected).norm(), 0.0, 1e-12);
}

TEST_P(ParticleStepOnEachMesh, HydrodynamicForceSatisfiesTheMomentumIdentity) {
  // Two disks inside each other's collision range, under gravity, in a non-rigid liquid.
  const Params params = DisksInContact(1.01, GetParam());
  SceneRun run(params);
  run.NonRigidField();
  for (int k = 0; k < 3; ++k) {
    std::vector<ParticleState> before = run.particles;
    run.Advance();
    const double dt = params.time.dt;
    for (std::size_t p = 0; p < 2; ++p) {
      const ParticleState& a = before[p];
      const ParticleState& b = run.particles[p];
      const double mass = b.density * kPi * b.radius * b.radius;
      const double inertia = mass * b.radius * b.radius / 2;
      const Vec2 collision = run.step.CollisionForceAverage()[p];
      const Vec2 expected =
          mass * (b.velocity - a.velocity) / dt - mass * params.gravity - collision;
      const double scale = mass * params.gravity.norm() + collision.norm();
      std::printf("step %d particle %zu: F_h = (%.6e, %.6e), F' = (%.3e, %.3e), T_h = %.3e\n", k, p,
                  b.force.x(), b.force.y(), collision.x(), collision.y(), b.torque);
      EXPECT_GT(collision.norm(), 0.0);
      // An algebraic identity: equal up to the round-off of O(1e4) terms divided by dt.
      EXPECT_NEAR((b.force - expected).norm(), 0.0, 1e-12 * scale);
      EXPECT_NEAR(b.torque, inertia * (b.angular_velocity - a.angular_velocity) / dt,
                  1e-12 * std::abs(b.torque) + 1e-15);
    }
  }
}

TEST_P(ParticleStepOnEachMesh, NeutrallyBuoyantDiskFloatsWithAUniformFlowUnderGravity) {
  // rho_d = rho_L: gravity is balanced by buoyancy, the disk is carried by the flow, and the
  // hydrodynamic force is the buoyancy -rho_L Vp g = -M g.
  Params params = Scene(1.0, 1.0 / 48, true, GetParam());
  params.gravity = Vec2(0.0, -981.0);
  const Vec2 velocity(0.3, -0.1);
  params.particles.push_back(Disk(Vec2(0.5137, 0.4871), 1.0, velocity));
  SceneRun run(params);
  std::fill(run.u.begin(), run.u.end(), velocity.x());
  std::fill(run.v.begin(), run.v.end(), velocity.y());
  const int steps = 500;
  for (int k = 0; k < steps; ++k) run.Advance();
  const ParticleState& p = run.particles[0];
  const double mass = kPi * 0.01;
  EXPECT_NEAR((p.velocity - velocity).norm(), 0.0, 1e-13);
  EXPECT_NEAR(p.angular_velocity, 0.0, 1e-12);
  for (std::size_t q = 0; q < run.u.size(); ++q) {
    ASSERT_NEAR(run.u[q], velocity.x(), 1e-14);
    ASSERT_NEAR(run.v[q], velocity.y(), 1e-14);
  }
  // |F_h + M g| is round-off of M (U^{n+1} - U^n)/dt: 1e-16 velocity over dt = 4e-4, times M.
  EXPECT_NEAR((p.force + mass * params.gravity).norm(), 0.0, 1e-10);
  const Vec2 expected = Vec2(0.5137, 0.4871) + steps * 4e-4 * velocity;
  EXPECT_NEAR((p.position - expected).norm(), 0.0, 1e-12);
}

TEST_P(ParticleStepOnEachMesh, NeutrallyBuoyantDiskSatisfiesTheMomentumIdentityInContact) {
  // A neutral disk (its collision force goes to the fluid through (37)) next to a heavy one.
  const Params params = DisksInContact(1.0, GetParam());
  SceneRun run(params);
  run.NonRigidField();
  for (int k = 0; k < 3; ++k) {
    std::vector<ParticleState> before = run.particles;
    run.Advance();
    const double dt = params.time.dt;
    const Vec2 collision = run.step.CollisionForceAverage()[0];
    EXPECT_GT(collision.norm(), 0.0);
    // The neutral disk hands F' to the fluid: sum nu = F'_avg exactly.
    EXPECT_NEAR((run.step.constraint().NodalForceSum(0) - collision).norm(), 0.0,
                1e-12 * collision.norm());
    for (std::size_t p = 0; p < 2; ++p) {
      const ParticleState& a = before[p];
      const ParticleState& b = run.particles[p];
      const double mass = b.density * kPi * b.radius * b.radius;
      const Vec2 f = run.step.CollisionForceAverage()[p];
      const Vec2 expected = mass * (b.velocity - a.velocity) / dt - mass * params.gravity - f;
      const double scale = mass * params.gravity.norm() + f.norm() + mass * b.velocity.norm() / dt;
      EXPECT_NEAR((b.force - expected).norm(), 0.0, 1e-12 * scale);
    }
  }
}

TEST_P(ParticleStepOnEachMesh, FixedDiskFeelsMinusTheNodalForceSum) {
  Params params = Scene(1.0, 1.0 / 48, false, GetParam());
  params.particles.push_back(Disk(Vec2(0.5137, 0.4871), 1.5));
  params.particles[0].motion = Motion::kFixed;
  SceneRun run(params);
  for (int j = 1; j < run.grid.ny; ++j) {
    for (int i = 1; i < run.grid.nx; ++i) run.u[run.grid.Index(i, j)] = 1.0;  // liquid moving in +x
  }
  run.Advance();
  const ParticleState& p = run.particles[0];
  EXPECT_EQ(p.velocity.norm(), 0.0);
  EXPECT_EQ((p.position - Vec2(0.5137, 0.4871)).norm(), 0.0);
  EXPECT_EQ((p.force + run.step.constraint().NodalForceSum(0)).norm(), 0.0);
  EXPECT_GT(p.force.x(), 0.0);  // the liquid stopped by the disk pushes it in +x
}

// Paper parameters: h = 1/96, rho = 1.5 h, eps_p = 2e-5, eps_w = 1e-5, K = 10, dt = 4e-4, D = 0.2.
// Without a fluid solver the liquid is inviscid and at rest: a moving disk hands momentum to the
// fluid nodes it covers, so the disks start 2 h apart (just outside the range) to meet at speed.
double MinGapOfRun(const Params& params, int steps, const char* label) {
  SceneRun run(params);
  double min_gap = 1.0;
  int contacts = 0;
  for (int k = 0; k < steps; ++k) {
    run.Advance();  // throws ParticlesOverlap on contact
    min_gap = std::min(min_gap, run.report.Get("particle_min_gap"));
    contacts = std::max(contacts, static_cast<int>(run.report.Get("collision_contacts")));
  }
  std::printf("%s: min gap %.4f h over %d steps\n", label, min_gap / params.domain.h, steps);
  EXPECT_GT(contacts, 0);  // the repulsion acted
  return min_gap;
}

TEST_P(ParticleStepOnEachMesh, TwoDisksPushedTogetherNeverTouch) {
  const double h = 1.0 / 96;
  // At rho_d = 1.01 and speed 0.5 the disks stop before the range (momentum goes to the liquid).
  const std::pair<double, double> cases[] = {{1.01, 2.0}, {1.5, 0.5}, {1.5, 2.0}};
  for (const auto& [density, speed] : cases) {
    {
      Params params = Scene(1.0, h, false, GetParam());
      params.particles.push_back(Disk(Vec2(0.4 - h, 0.5), density, Vec2(speed, 0.0)));
      params.particles.push_back(Disk(Vec2(0.6 + h, 0.5), density, Vec2(-speed, 0.0)));
      char label[96];
      std::snprintf(label, sizeof label, "pair, rho_d = %.2f, approach speed 2 x %.1f", density,
                    speed);
      const double gap = MinGapOfRun(params, 400, label);
      EXPECT_GT(gap, 0.0);
      EXPECT_LT(gap, 1.5 * h);
    }
  }
}

TEST_P(ParticleStepOnEachMesh, DisksStackedUnderGravityNeverTouch) {
  // A sustained push: the lower disk settles on the bottom wall and the upper one on it. Only
  // rho_d = 1.01 (the paper's pairs): without viscous drag a rho_d = 1.5 disk reaches the wall at
  // about 5 cm/s, where the notes (1.7) predict, and the engine reports, an overlap.
  const double h = 1.0 / 96;
  for (double density : {1.01}) {
    Params params = Scene(1.0, h, false, GetParam());
    params.gravity = Vec2(0.0, -981.0);
    params.particles.push_back(Disk(Vec2(0.5, 0.1 + 3 * h), density));
    params.particles.push_back(Disk(Vec2(0.5, 0.3 + 6 * h), density));
    char label[64];
    std::snprintf(label, sizeof label, "stack under gravity, rho_d = %.2f", density);
    const double gap = MinGapOfRun(params, 1500, label);
    EXPECT_GT(gap, 0.0);
    EXPECT_LT(gap, 1.5 * h);
  }
}

TEST_P(ParticleStepOnEachMesh, DiskPushedAtAWallNeverTouches) {
  const double h = 1.0 / 96;
  // rho_d = 1.01 stops before the range from these speeds; the stack test pushes it onto the wall.
  for (double density : {1.5}) {
    for (double speed : {0.5, 2.0}) {
      Params params = Scene(1.0, h, false, GetParam());
      params.particles.push_back(Disk(Vec2(0.5, 0.1 + 2 * h), density, Vec2(0.0, -speed)));
      char label[96];
      std::snprintf(label, sizeof label, "wall, rho_d = %.2f, approach speed %.1f", density, speed);
      const double gap = MinGapOfRun(params, 400, label);
      EXPECT_GT(gap, 0.0);
      EXPECT_LT(gap, 1.5 * h);
    }
  }
}

TEST(ParticleStep, OverlapDuringARunThrowsWithIdsTimeAndGap) {
  Params params = Scene(1.0, 1.0 / 48, false);
  params.particles.push_back(Disk(Vec2(0.385, 0.5), 1.5, Vec2(100.0, 0.0)));
  params.particles.push_back(Disk(Vec2(0.615, 0.5), 1.5, Vec2(-100.0, 0.0)));
  SceneRun run(params);
  run.particles[0].id = 3;
  run.particles[1].id = 7;
  try {
    for (int k = 0; k < 10; ++k) run.Advance();
    FAIL() << "no overlap detected";
  } catch (const ParticlesOverlap& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    EXPECT_NE(what.find("particles 3 and 7 overlap at t = 0.0004 (gap = -"), std::string::npos)
        << what;
  }
}

TEST(ParticleStep, OverlapWithAWallThrows) {
  Params params = Scene(1.0, 1.0 / 48, false);
  params.particles.push_back(Disk(Vec2(0.5, 0.13), 1.5, Vec2(0.0, -200.0)));
  SceneRun run(params);
  try {
    run.Advance();
    FAIL() << "no overlap detected";
  } catch (const ParticlesOverlap& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    EXPECT_NE(what.find("particle 0 "), std::string::npos) << what;
    EXPECT_NE(what.find("bottom side at t = 0.0004"), std::string::npos) << what;
  }
}

TEST(ParticleStep, InitialStatesRejectOverlapAndCrossing) {
  Params params = Scene(1.0, 1.0 / 48, false);
  params.particles.push_back(Disk(Vec2(0.5, 0.5), 1.5));
  params.particles.push_back(Disk(Vec2(0.69, 0.5), 1.5));
  try {
    ParticleStep::InitialStates(params);
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "particles.1.center");
  }
  params.particles[1].center = Vec2(0.5, 0.95);
  try {
    ParticleStep::InitialStates(params);
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "particles.1.center");
    EXPECT_NE(std::string(e.what()).find("top"), std::string::npos);
  }
  params.particles[1].center = Vec2(0.5, 0.75);
  const auto states = ParticleStep::InitialStates(params);
  ASSERT_EQ(states.size(), 2u);
  EXPECT_EQ(states[1].id, 1);
  EXPECT_EQ(states[1].radius, 0.1);
  // R = 0.1, h_p = 1/35: 4 rings (round(2 pi k 3.5 / 4) = 5, 11, 16, 22) plus the centre.
  EXPECT_EQ(states[1].multiplier.size(), 2u * 55u);
}

}  // namespace
}  // namespace dlmfd
