// The steady Stokes drag of a fixed disk in a channel: at first order in h with the paper's
// coupling of the constraint (issue 3), and independent of the diffusion number with the default,
// splitting.constraint = "incremental" (issue 13 point 2; particles/lagged_multiplier.h).
//
// Scene: periodic in x (period 1), walls at y = 0 and y = 1, the liquid driven by the body force
// f = (1, 0) (a mean pressure gradient), rho = eta = 1, a fixed disk D = 0.25 at the centre;
// Re = rho U D / eta ~ 0.03 with U ~ f H^2 / (8 eta). The run starts from the disk-free Poiseuille
// profile and ends at t = 0.6 H^2 rho / eta, when the slowest Stokes mode has decayed by
// exp(-0.6 pi^2) = 3e-3 of a start that is already close: the drag then changes by 2e-6 or less per
// 10 steps (asserted below at 1e-5, which is 1e-3 of the smallest grid-to-grid difference).
// Grids: h = 1/16, 1/24, 1/32 (and 1/48 in the study) with h_p / h = 96/70 (the paper's ratio)
// and the diffusion number eta dt / (rho h^2) = 2 held fixed. The steady state of the split scheme
// depends on dt: the Stokes step smears the DLM correction over sqrt(eta dt / rho) ~ h, which is
// then an O(h) effect, like the DLM thickening of the disk (R_eff ~ R + 0.6 h, method notes 1.6).
// Convergence study (Release build, this file): F_x = 0.392413, 0.448766, 0.477131, 0.505697;
// observed orders 0.981 (16-24-32) and 0.979 (24-32-48), extrapolated limits 0.5641 and 0.5643.
// At eta dt / (rho h^2) = 1 the grids 1/16 and 1/32 give 0.458894, 0.510299, whose first-order
// extrapolation 0.5617 is within 0.5% of those: the limit does not depend on the diffusion number.
// Hence the asserts: monotone convergence (F_x increases with every refinement) and an observed
// order in [0.8, 1.2] (first order, the DLM/FD expectation; the margin is far above what the 2e-6
// steady-state noise can do to differences of 3e-2, and below what a half-order method would give).
// Those studies, and the first-order tests, are of the paper's coupling (splitting.constraint =
// "paper", alpha = beta = 1/2), whose steady state depends on dt.
//
// The default coupling (study 2026-12-02, DISABLED_IncrementalCouplingStudy below, Release):
// eta dt / (rho h^2) = 2, 0.5 at h = 1/24: ring 0.558323, 0.558376; collocation 0.543326,
// 0.543326 (the paper's: ring 0.448762, 0.521527; collocation 0.392136, 0.493384); at 8 the runs
// are not steady by t = 0.6 (the lag of the multiplier decays over about 1 + 8 steps a mode) and
// lie 0.3 % lower. Grids 1/16 ... 1/64 at 2: ring 0.564030, 0.558323, 0.554639, 0.551927,
// 0.550179 (from above, the diffuse boundary's larger effective disk, with the irregular orders
// of the ring mesh's h_p / h = 96 / 70 against the grid); collocation 0.539002, 0.543326,
// 0.539845, 0.543464, 0.546345 (within 1.5 % of each other, not monotone). The two point sets
// close in on one limit of about 0.547-0.548, 3 % below the paper coupling's extrapolated 0.564:
// that extrapolation carried its dt error (O(h) along a ladder of fixed diffusion number).
// Asserted: at h = 1/24, the drags at diffusion numbers 2 and 0.5 agree within 3e-4 (three times
// the ring's 9.5e-5; the paper's differ by 14 % and 21 %).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/simulation.h"

namespace dlmfd {
namespace {

constexpr double kDiffusionNumber = 2.0;  // eta dt / (rho h^2)
constexpr double kEndTime = 0.6;

struct Drag {
  double force = 0.0;        // F_x on the disk at the end
  double last_change = 0.0;  // |F_x(end) - F_x(end - 10 dt)|
};

Drag SteadyDrag(int cells, ParticleMeshKind kind, ConstraintCoupling coupling,
                double diffusion_number = kDiffusionNumber) {
  Params params;
  testing::UseStudiedNumerics(params);
  params.splitting = SplittingParams::DefaultWeights(coupling);
  testing::UseStudiedNumerics(params.splitting);
  params.particle_mesh.kind = kind;
  params.domain.size = Vec2(1.0, 1.0);
  params.domain.h = 1.0 / cells;
  params.domain.sides[0].type = params.domain.sides[1].type = SideType::kPeriodic;
  params.fluid.density = 1.0;
  params.fluid.viscosity = 1.0;
  params.fluid.body_force = Vec2(1.0, 0.0);
  params.splitting.advection = AdvectionScheme::kWave;
  params.time.dt = diffusion_number * params.domain.h * params.domain.h;
  params.time.end = kEndTime;
  params.particle_mesh.h = params.domain.h * 96.0 / 70.0;
  params.threads = 1;
  ParticleParams disk;
  disk.center = Vec2(0.5, 0.5);
  disk.diameter = 0.25;
  disk.motion = Motion::kFixed;
  params.particles.push_back(disk);
  Simulation sim(params);
  // The disk-free Poiseuille profile u = f y (H - y) / (2 eta).
  FlowState& state = sim.mutable_state();
  const Grid& grid = sim.grid();
  for (int j = 0; j <= grid.ny; ++j) {
    for (int i = 0; i <= grid.nx; ++i)
      state.u[grid.Index(i, j)] = 0.5 * grid.Y(j) * (1.0 - grid.Y(j));
  }
  Drag drag;
  const long steps = sim.TotalSteps();
  double earlier = 0.0;
  for (long n = 0; n < steps; ++n) {
    sim.Step();
    if (n == steps - 11) earlier = sim.state().particles[0].force.x();
  }
  drag.force = sim.state().particles[0].force.x();
  drag.last_change = std::abs(drag.force - earlier);
  return drag;
}

// The order p with (h1^p - h2^p) / (h2^p - h3^p) = d12 / d23, by bisection on [0.05, 5].
double ObservedOrder(double h1, double h2, double h3, double d12, double d23) {
  auto mismatch = [&](double p) {
    return (std::pow(h1, p) - std::pow(h2, p)) / (std::pow(h2, p) - std::pow(h3, p)) - d12 / d23;
  };
  double lo = 0.05, hi = 5.0;
  if (mismatch(lo) * mismatch(hi) > 0.0) return std::nan("");
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (mismatch(lo) * mismatch(mid) <= 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// Monotone convergence at an observed order in [0.8, 1.2] on these grids, each run steady to
// steady_bound (the drag change over its last 10 steps).
void CheckFirstOrder(const std::vector<int>& cells, ParticleMeshKind kind, double steady_bound,
                     const char* label) {
  std::vector<double> h, force;
  for (int n : cells) {
    const Drag drag = SteadyDrag(n, kind, ConstraintCoupling::kPaper);
    h.push_back(1.0 / n);
    force.push_back(drag.force);
    std::printf("%s: h = 1/%-3d F_x = %.6f  (change over the last 10 steps %.1e)\n", label, n,
                drag.force, drag.last_change);
    EXPECT_LT(drag.last_change, steady_bound);
  }
  for (std::size_t k = 1; k < force.size(); ++k) {
    EXPECT_GT(force[k], force[k - 1]) << "refinement " << k;
  }
  for (std::size_t k = 2; k < force.size(); ++k) {
    const double p = ObservedOrder(h[k - 2], h[k - 1], h[k], force[k - 1] - force[k - 2],
                                   force[k] - force[k - 1]);
    const double limit =
        force[k] + (force[k] - force[k - 1]) / (std::pow(h[k - 1] / h[k], p) - 1.0);
    std::printf("%s: grids 1/%d, 1/%d, 1/%d: observed order %.3f, extrapolated F_x %.5f\n", label,
                cells[k - 2], cells[k - 1], cells[k], p, limit);
    EXPECT_GE(p, 0.8);
    EXPECT_LE(p, 1.2);
  }
}

TEST(ParticleDrag, SteadyDragDoesNotDependOnTheDiffusionNumberWithTheDefaultCoupling) {
  for (ParticleMeshKind kind : {ParticleMeshKind::kRing, ParticleMeshKind::kCollocation}) {
    const double coarse = SteadyDrag(24, kind, ConstraintCoupling::kIncremental, 2.0).force;
    const double fine = SteadyDrag(24, kind, ConstraintCoupling::kIncremental, 0.5).force;
    std::printf("%s: F_x = %.6f (eta dt / (rho h^2) = 2), %.6f (0.5)\n",
                kind == ParticleMeshKind::kRing ? "ring" : "collocation", coarse, fine);
    EXPECT_NEAR(coarse, fine, 3e-4 * fine);
  }
}

TEST(ParticleDrag, FixedDiskInAChannelConvergesAtFirstOrder) {
  // 1/48 (in the study) costs 3x the three together.
  CheckFirstOrder({16, 24, 32}, ParticleMeshKind::kRing, 1e-5, "ring");
}

// The collocation points (quadratic boundary interpolation, spacing 2 h) at the same diffusion
// number 2. Study (Release, this scene): F_x = 0.294388, 0.392136, 0.436654, 0.481829, 0.506085 on
// h = 1/16, 1/24, 1/32, 1/48, 1/64 (R / h = 2 to 8); observed orders 1.2 (16-24-32, R / h <= 4:
// not yet asymptotic), 0.97 (24-32-48) and 0.9 (32-48-64). The same first order as the ring mesh
// here: at eta dt / (rho h^2) = 2 the drag is limited by the split of the constraint (37) from the
// viscous step (33) (particle-coupling.md section 2), not by where the points sit; at 0.25 the
// grids 1/24 ... 1/48 give 0.516, 0.521, 0.532 (ring 0.538, 0.541, 0.544), a different limit. Hence
// the same bounds as the ring mesh on the grids past R / h = 2, and steadiness to 1e-3 of the
// smallest grid-to-grid difference (0.045), as for the ring: 4.5e-5 (measured 1.0e-5 on 1/48).
TEST(ParticleDrag, FixedDiskInAChannelConvergesAtFirstOrderWithCollocationPoints) {
  CheckFirstOrder({24, 32, 48}, ParticleMeshKind::kCollocation, 4.5e-5, "collocation");
}

// The grid study of the default coupling (splitting.constraint = "incremental"), run by hand:
//   build/tests/convergence_tests --gtest_also_run_disabled_tests
//   --gtest_filter='ParticleDrag*Study*'
TEST(ParticleDrag, DISABLED_IncrementalCouplingStudy) {
  for (ParticleMeshKind kind : {ParticleMeshKind::kRing, ParticleMeshKind::kCollocation}) {
    for (double number : {8.0, 2.0, 0.5}) {
      for (ConstraintCoupling coupling :
           {ConstraintCoupling::kIncremental, ConstraintCoupling::kPaper}) {
        const Drag drag = SteadyDrag(24, kind, coupling, number);
        std::printf("%s, %s: h = 1/24, eta dt / (rho h^2) = %.1f: F_x = %.6f (last change %.1e)\n",
                    kind == ParticleMeshKind::kRing ? "ring" : "collocation",
                    coupling == ConstraintCoupling::kPaper ? "paper" : "incremental", number,
                    drag.force, drag.last_change);
      }
    }
    for (int n : {16, 24, 32, 48, 64}) {
      const Drag drag = SteadyDrag(n, kind, ConstraintCoupling::kIncremental);
      std::printf("%s: h = 1/%-3d F_x = %.6f  (change over the last 10 steps %.1e)\n",
                  kind == ParticleMeshKind::kRing ? "ring" : "collocation", n, drag.force,
                  drag.last_change);
    }
  }
}

}  // namespace
}  // namespace dlmfd
