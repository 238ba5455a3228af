// A fixed disk in a uniformly accelerated periodic liquid feels the pressure-gradient plus
// added-mass force of potential theory, with an error that shrinks at first order in h (method
// notes 2, 1.6).
//
// Scene: the unit box, periodic on all sides, rho = 1, eta = 1e-6, the liquid at rest and driven by
// the body force a = (1, 0) from t = 0; a fixed disk D = 0.25 at the centre. Theory (Maxwell /
// Rayleigh for a dilute square array, error O(phi^4) = 6e-6): F_x = rho Vp a (1 + (1 - phi)/(1 +
// phi)) with phi = pi R^2 = 0.0491, i.e. F_x / (rho Vp a) = 1.906419. Inviscid limit, short time:
// dt = 1e-5 and at most 300 steps, so the liquid moves a t^2/2 <= 5e-6 (far below h) and the
// boundary layer sqrt(eta t) <= 6e-5 stays below h / 100 on every grid. The split scheme needs a
// number of steps (not a time: the per-step values do not depend on dt, checked at dt = 1e-3 and
// 4e-3) to build the potential flow around the disk; the force is read when it has settled: a
// change below 1e-3 over 20 steps (a tail below 5e-3, under 3% of the smallest grid-to-grid
// difference). Grids h = 1/24, 1/48, 1/96 with h_p = h and R = 3, 6, 12 h_p, so that the multiplier
// mesh is the same in units of h on every grid (with R / h_p not an integer the ring spacing R /
// ceil(R / h_p) jumps from grid to grid, and the force with it). Convergence study (Release build,
// this file): F_x / (rho Vp a) = 2.8050, 2.3648, 2.1379 after 116, 137 and 68 steps
// (2.8055, 2.3650, 2.1396 after 140 steps: the settling tail is below 5e-3), errors 0.899, 0.458,
// 0.231: observed order 0.956, extrapolated 1.896. Asserted: monotone decrease, observed order in
// [0.8, 1.2] (first order; a 5e-3 tail moves p by 0.03), and the extrapolated limit within 0.05 of
// the theory (the tail times the 1/(2^p - 1) ~ 1 amplification of the extrapolation, plus an O(h^2)
// remainder of the size of the 0.01 seen here). Not covered here, found in the study: with the
// paper's h_p / h = 96/70 the inviscid force converges to a lower value (R = 8/7 h_p(1/24), h =
// 1/24 ... 1/144: 2.801, 2.243, 2.005, 1.913, 1.825 against 1.921): between multiplier nodes that
// are sparser than the fluid nodes the potential flow leaks through the disk at no cost (no
// viscosity resists it, and the 2h pressure mesh does not forbid it). At h = 1/96 the force
// is 1.913, 2.185 and 2.276 for h_p / h = 1.37, 1 and 0.75.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/simulation.h"

namespace dlmfd {
namespace {

constexpr double kDiameter = 0.25;
constexpr int kMaxSteps = 300;
constexpr int kSettleWindow = 20;
constexpr double kSettled = 1e-3;  // change of F_x / (rho Vp a) over kSettleWindow steps

struct AddedMass {
  double force_ratio = 0.0;  // F_x / (rho Vp a)
  int steps = 0;
};

AddedMass SettledForce(int cells) {
  Params params;
  testing::UseStudiedNumerics(params);
  params.domain.size = Vec2(1.0, 1.0);
  params.domain.h = 1.0 / cells;
  for (auto& side : params.domain.sides) side.type = SideType::kPeriodic;
  params.fluid.density = 1.0;
  params.fluid.viscosity = 1e-6;
  params.fluid.body_force = Vec2(1.0, 0.0);
  params.splitting.advection = AdvectionScheme::kWave;
  params.time.dt = 1e-5;
  params.time.end = kMaxSteps * params.time.dt;
  params.particle_mesh.kind = ParticleMeshKind::kRing;  // the mesh this study measured
  // h_p = h, a hair above so that ceil(R / h_p) is R / h_p despite round-off.
  params.particle_mesh.h = params.domain.h * (1.0 + 1e-9);
  params.threads = 1;
  ParticleParams disk;
  disk.center = Vec2(0.5, 0.5);
  disk.diameter = kDiameter;
  disk.motion = Motion::kFixed;
  params.particles.push_back(disk);
  Simulation sim(params);
  const double scale =
      params.fluid.density * kPi * kDiameter * kDiameter / 4 * params.fluid.body_force.x();
  std::vector<double> history;
  AddedMass result;
  for (int n = 1; n <= kMaxSteps; ++n) {
    sim.Step();
    history.push_back(sim.state().particles[0].force.x() / scale);
    result.force_ratio = history.back();
    result.steps = n;
    if (n > kSettleWindow && std::abs(history.back() - history[n - 1 - kSettleWindow]) < kSettled)
      break;
  }
  return result;
}

TEST(ParticleAddedMass, FixedDiskInAnAcceleratedLiquidConvergesToPotentialTheory) {
  const double phi = kPi * kDiameter * kDiameter / 4;
  const double theory = 1.0 + (1.0 - phi) / (1.0 + phi);
  const std::vector<int> cells = {24, 48, 96};
  std::vector<double> force;
  std::printf("   h      F_x/(rho Vp a)   error    steps   (theory %.6f)\n", theory);
  for (int n : cells) {
    const AddedMass r = SettledForce(n);
    force.push_back(r.force_ratio);
    std::printf("  1/%-3d   %.6f       %+.4f   %d\n", n, r.force_ratio, r.force_ratio - theory,
                r.steps);
    EXPECT_LT(r.steps, kMaxSteps) << "the force did not settle on h = 1/" << n;
  }
  EXPECT_GT(force[0], force[1]);
  EXPECT_GT(force[1], force[2]);
  const double p = std::log2((force[0] - force[1]) / (force[1] - force[2]));
  const double limit = force[2] - (force[1] - force[2]) / (std::pow(2.0, p) - 1.0);
  std::printf("observed order %.3f, extrapolated %.4f\n", p, limit);
  EXPECT_GE(p, 0.8);
  EXPECT_LE(p, 1.2);
  EXPECT_NEAR(limit, theory, 0.05);
}

}  // namespace
}  // namespace dlmfd
