// The time-step dependence of the drag on the test channel (tests/support/viscous_channel.h: a
// fixed disk D = 0.4 in a Poiseuille channel, rho = eta = 1, h = 1/16, drag at t = 0.5) under the
// three couplings of the rigid-body constraint (issue 13 point 2;
// docs/evidence/constraint_coupling.md, "Coupling the constraint with viscosity").
//
// dt-convergence study (2026-12-01, `dlmfd-solve` on the same scene, tolerances 1e-9; the commands
// are in docs/evidence/constraint_coupling.md): F_x at dt = 8, 4, 2, 1, 0.5 (e-3), nu dt / h^2
// = 2.05 ... 0.13:
//   viscous: 57.8554 / 57.8356 / 57.8256 / 57.8206 / 57.8181: steps 0.0199, 0.0100, 0.0050,
//            0.0025, first order with c = dF/d(dt) = 4.99, limit 57.8156;
//   paper:   14.417 / 22.807 / 32.236 / 40.926 / 47.566 (51.950 at 2.5e-4), still 10 % low at
//            the smallest step and converging toward the same limit, at about order 0.6.
// With the looser tolerances of the test (1e-6) the viscous drags move by < 1e-5.
//   incremental (the default, tolerances 1e-9): at t = 0.5 57.5176 / 57.7836 / 57.8220 / 57.8190
//            (dt = 8, 4, 2, 1 e-3: the lag of the multiplier in the start-up, 0.5 % at nu dt / h^2
//            = 2.05); at the steady state, t = 3: 57.82114 / 57.82831 / 57.82223 / 57.81897, all
//            within 0.0127 of the viscous coupling's limit 57.8156 (the paper's: 14.417 / 32.236
//            at 8e-3 / 2e-3, unchanged from t = 0.5).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../support/quiet_case.h"
#include "../support/studied_numerics.h"
#include "../support/viscous_channel.h"
#include "dlmfd/core/observer.h"
#include "dlmfd/core/simulation.h"
#include "dlmfd/particles/viscous_constraint.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

// The outer iterations of the viscous coupling, step by step (the step report's column).
struct IterationLog : Observer {
  std::vector<long> iterations;
  std::vector<double> stokes_tolerance;  // of the coupled Stokes solves, at the step's end
  std::vector<double> drag;              // F_x of the first particle
  void OnStep(const FlowState& state, const StepReport& report) override {
    iterations.push_back(static_cast<long>(report.Get("coupling_iterations", -1.0)));
    stokes_tolerance.push_back(report.Get("coupling_stokes_tolerance", -1.0));
    drag.push_back(state.particles.empty() ? 0.0 : state.particles[0].force.x());
  }
};

// The Schaefer-Turek disk (D = 0.1 at (0.2, 0.2), D/h = 20) in a 0.8 x 0.4 channel of creeping
// flow (eta = rho = 1, Poiseuille inflow of peak 0.3, dt = 0.05, nu dt / h^2 = 2000), collocation
// points, the viscous coupling, no output, one thread; `overrides` add keys (none of these).
Params CreepingDisk(std::vector<SceneOverride> overrides) {
  std::vector<SceneOverride> keys = {
      {"domain.size", "[0.8, 0.4]"},
      {"fluid.viscosity", "1.0"},
      {"particle_mesh.kind", "\"collocation\""},
      {"domain.diagonals", "\"sw_ne\""},  // the mesh of these studies
      {"splitting.constraint", "\"viscous\""},
      {"time.dt", "0.05"}};
  keys.insert(keys.end(), overrides.begin(), overrides.end());
  return testing::QuietCase("cases/verification/schaefer_turek_2d1.toml", keys);
}

double ChannelDrag(double dt, ConstraintCoupling coupling, double end = 0.5) {
  Params p = testing::ChannelWithFixedDisk(16, dt, 0.0, 1.0);
  p.time.end = end;
  p.splitting = SplittingParams::DefaultWeights(coupling);  // paper: alpha = beta = 1/2
  testing::UseStudiedNumerics(p.splitting);
  if (coupling == ConstraintCoupling::kViscous) {
    p.solvers.stokes_tolerance = 1e-6;
    p.solvers.multiplier_tolerance = 1e-6;
  }
  Simulation sim(p);
  sim.Run();
  return sim.state().particles[0].force.x();
}

// First order in dt with the measured constant: F(8e-3) - F(2e-3) = 4.99 x 6e-3 = 0.030; the test
// allows twice that (1e-3 of the drag), against the paper scheme's 17.8 over the same steps.
TEST(ViscousCoupling, ChannelDragDoesNotDependOnTheTimeStep) {
  const double coarse = ChannelDrag(8e-3, ConstraintCoupling::kViscous);
  const double fine = ChannelDrag(2e-3, ConstraintCoupling::kViscous);
  std::printf("viscous coupling: F_x = %.6f (dt = 8e-3), %.6f (dt = 2e-3)\n", coarse, fine);
  EXPECT_NEAR(coarse - fine, 0.030, 0.030);
  // Both within the first-order error of the dt -> 0 limit 57.8156 of the study (0.04 and 0.01).
  EXPECT_NEAR(coarse, 57.8156, 2 * 4.99 * 8e-3);
  EXPECT_NEAR(fine, 57.8156, 2 * 4.99 * 2e-3);
}

// The paper's scheme, selected, gives the numbers of main before the viscous coupling existed
// (the same binary path: bitwise equal there; 1e-7 allows the run-to-run round-off of
// FFTW_MEASURE plans through 1e-9 solver tolerances), and its drag still depends on dt.
TEST(ViscousCoupling, PaperSchemeKeepsItsNumbers) {
  const double coarse = ChannelDrag(8e-3, ConstraintCoupling::kPaper);
  const double fine = ChannelDrag(2e-3, ConstraintCoupling::kPaper);
  std::printf("paper coupling: F_x = %.9f (dt = 8e-3), %.9f (dt = 2e-3)\n", coarse, fine);
  EXPECT_NEAR(coarse, 14.417374732677532, 1e-7 * 14.4);
  EXPECT_NEAR(fine, 32.23637037856553, 1e-7 * 32.2);
}

// The default coupling at the steady state: the drag does not depend on the time step; the study
// above found all four steps within 0.0127 of the viscous limit, asserted with 0.02.
TEST(IncrementalCoupling, SteadyChannelDragDoesNotDependOnTheTimeStep) {
  const double coarse = ChannelDrag(8e-3, ConstraintCoupling::kIncremental, 3.0);
  const double fine = ChannelDrag(2e-3, ConstraintCoupling::kIncremental, 3.0);
  std::printf("incremental coupling, t = 3: F_x = %.6f (dt = 8e-3), %.6f (dt = 2e-3)\n", coarse,
              fine);
  EXPECT_NEAR(coarse, 57.8156, 0.02);
  EXPECT_NEAR(fine, 57.8156, 0.02);
}

// The viscous coupling with the collocation points (particles/viscous_constraint.h, warm start):
// Faxen's disk (cases/verification/faxen_disk_w1.toml) on h = 1/48, dt = 0.002. Warm-started from
// the last step's multiplier, the outer PCG needed 11, 16, 12, then 46-55 iterations and threw at
// step 10 ("did not converge ... rigid-motion mismatch"); started cold it takes 8-13 a step over
// 50 steps (9-16 on h = 1/96). 30 steps must complete.
TEST(ViscousCoupling, CollocationPointsConvergeEveryStep) {
  const Params params =
      LoadSceneFile(std::string(DLMFD_SOURCE_DIR) + "/cases/verification/faxen_disk_w1.toml",
                    {{"domain.h", "0.020833333333333332"},
                     {"particle_mesh.kind", "\"collocation\""},
                     {"domain.diagonals", "\"sw_ne\""},
                     {"splitting.constraint", "\"viscous\""},
                     {"time.dt", "0.002"},
                     {"time.end", "0.06"},
                     {"output.fields_every", "0"},
                     {"output.particles_every", "0"},
                     {"output.checkpoint_every", "0"}});
  Simulation sim(params);
  EXPECT_NO_THROW(sim.Run());
  EXPECT_EQ(sim.state().step, 30);
  EXPECT_LT(sim.state().particles[0].velocity.y(), 0.0);  // it falls
}

// The viscous coupling with the collocation points around a fixed disk: Schaefer-Turek 2D-1 as
// shipped (D/h = 20), dt = h. With the coupled Stokes solves at the default tolerance 1e-4 the
// outer PCG grew along the null space of S to a mismatch of 9e17 at step 1; they now stop at 1e-2
// of the multiplier tolerance (ViscousConstraint::kCollocationStokesShare) and every step converges
// (43, then 29 iterations started cold; 43, 42, 27, 25, 17 warm-started, since 2026-12-04). 5 steps
// must complete, the disk must feel the flow's drag (F_x > 0), and the flow at the points must be
// rigid (the disk's velocity stays 0).
TEST(ViscousCoupling, CollocationPointsAroundAFixedDiskConverge) {
  Params params =
      LoadSceneFile(std::string(DLMFD_SOURCE_DIR) + "/cases/verification/schaefer_turek_2d1.toml",
                    {{"particle_mesh.kind", "\"collocation\""},
                     {"domain.diagonals", "\"sw_ne\""},
                     {"splitting.constraint", "\"viscous\""},
                     {"time.end", "0.025"},
                     {"output.fields_every", "0"},
                     {"output.particles_every", "0"},
                     {"output.checkpoint_every", "0"}});
  params.threads = 1;
  Simulation sim(params);
  EXPECT_NO_THROW(sim.Run());
  EXPECT_EQ(sim.state().step, 5);
  EXPECT_GT(sim.state().particles[0].force.x(), 0.0);
  EXPECT_EQ(sim.state().particles[0].velocity.norm(), 0.0);
}

// The warm start of a fixed disk with collocation points (ViscousConstraint::WarmStarts): the
// creeping disk (CreepingDisk) to t = 0.25, once fixed (warm-started) and once prescribed at rest
// (the same physics, started cold every step). Measured 2026-12-04: 128, 14, 0,
// 0, 0 outer iterations against 128 every step; F_x at t = 0.25 6.5141381 against 6.5139424 (3.0e-5
// apart; at multiplier tolerance 1e-6 the two agree to 1e-7 at t = 0.2, 6.5139608 / 6.5139609).
// With the recycled directions (FixedDiskStartsFromItsRecycledDirections): 128, 13, 0, 0, 0 and
// 6.5140379 (1.5e-5 from the cold start).
// Both runs stop at a rigid-motion mismatch of at most tol V (tol = 1e-4, V the largest velocity,
// about the inflow's peak 0.3 and so the disk's velocity scale U), and a mismatch d on the disk
// changes its Stokes drag by about (F / U) d: so |F_warm - F_cold| <= 2 tol (V / U) F, 2e-4 F with
// V / U = 1. The settled flow's steps (3-5) must take at most one iteration each.
TEST(ViscousCoupling, FixedDiskWarmStartsWithCollocationPoints) {
  double drag[2];
  long settled_iterations[2];
  const char* motions[2] = {"fixed", "prescribed"};
  for (int m = 0; m < 2; ++m) {
    Simulation sim(CreepingDisk(
        {{"particles.0.motion", std::string("\"") + motions[m] + "\""}, {"time.end", "0.25"}}));
    IterationLog log;
    sim.AddObserver(&log);
    sim.Run();
    ASSERT_EQ(log.iterations.size(), 5u);
    settled_iterations[m] = log.iterations[2] + log.iterations[3] + log.iterations[4];
    drag[m] = sim.state().particles[0].force.x();
    std::printf("%s disk: outer iterations %ld %ld %ld %ld %ld, F_x = %.7f\n", motions[m],
                log.iterations[0], log.iterations[1], log.iterations[2], log.iterations[3],
                log.iterations[4], drag[m]);
  }
  EXPECT_LE(settled_iterations[0], 3);
  EXPECT_NEAR(drag[0], drag[1], 2e-4 * drag[1]);
}

// A stall of the outer PCG tightens the coupled Stokes solves and restarts (ViscousConstraint::
// kStallWindow): the creeping disk (CreepingDisk) at D/h = 40 (h = 0.0025), its centre 5h/4 off
// the nodes, one step. Measured 2026-12-04: without the rule the step failed (over 500
// iterations with the coupled solves at 1e-6, the default's effective value; so did h/4 and 7h/4,
// and 3h/4 on two threads stalled at a mismatch of 2.4e-4 > 3e-5 through 1000); with it the step
// converges in 319 iterations, tightened to 1e-8. The reference F_x = 6.612541 is the same step run
// with solvers.stokes_tolerance = 1e-8 from the start (`dlmfd-solve` on this scene, --threads 1:
// 233 iterations); the rule's run gave 6.612612 (1.1e-5 apart). Both stop at a mismatch of at most
// tol V, so the bound of the test above, 2e-4 F, holds between them. The tightening is for the
// step that stalled: the second step, warm-started, starts again from 1e-6 and does not stall
// (before 2026-12-05 the tolerance stayed tightened for the rest of the run). Its reference,
// F_x = 6.4930209, is the second step of the run at 1e-8 from the start (this test with
// solvers.stokes_tolerance = 1e-8: 18 iterations); the reset's gave 6.4929925 (4.4e-6 apart).
TEST(ViscousCoupling, StallTightensTheCoupledStokesSolvesForItsStep) {
  Simulation sim(CreepingDisk(
      {{"domain.h", "0.0025"}, {"particles.0.center", "[0.203125, 0.2]"}, {"time.end", "0.1"}}));
  IterationLog log;
  sim.AddObserver(&log);
  ASSERT_NO_THROW(sim.Run());
  ASSERT_EQ(log.iterations.size(), 2u);
  std::printf("stall: %ld outer iterations, coupled Stokes tolerance %g, F_x = %.7f\n",
              log.iterations[0], log.stokes_tolerance[0], log.drag[0]);
  std::printf("next step: %ld outer iterations, coupled Stokes tolerance %g, F_x = %.7f\n",
              log.iterations[1], log.stokes_tolerance[1], log.drag[1]);
  EXPECT_NEAR(log.stokes_tolerance[0], 1e-8, 1e-12);  // one tightening from 1e-6
  EXPECT_NEAR(log.drag[0], 6.612541, 2e-4 * 6.612541);
  EXPECT_NEAR(log.stokes_tolerance[1], 1e-6, 1e-10);  // the step's own, untightened
  EXPECT_NEAR(log.drag[1], 6.4930209, 2e-4 * 6.4930209);
}

// The recycled directions (particles/recycled_directions.h): around a fixed disk S is the same
// operator at every step, so each step starts from the Galerkin correction in the span of the last
// directions. The confined cylinder (cases/verification/confined_cylinder_oldroyd_b.toml:
// Oldroyd-B, Wi = 0.6, the Stokes limit) at R/h = 8 with collocation points, 60 steps. Measured
// 2026-12-04
// (`dlmfd-solve` on this scene): 8.56 outer iterations a step over steps 11-60 before the change,
// 3.18 with it; K = 96.46655 against 96.46745 at t = 0.3 (9e-6 apart). The test asks for at most
// half the iterations of before, and the drag within the 2e-4 F that two runs stopping at a
// mismatch of tol V allow (FixedDiskWarmStartsWithCollocationPoints).
TEST(ViscousCoupling, FixedDiskStartsFromItsRecycledDirections) {
  const Params params = testing::QuietCase(
      "cases/verification/confined_cylinder_oldroyd_b.toml",
      {{"domain.h", "0.125"},
       {"time.end", "0.3"},
       {"particle_mesh.kind", "\"collocation\""},
       {"splitting.constraint", "\"viscous\""},
       {"domain.diagonals", "\"sw_ne\""},               // the scheme of the measurement
       {"splitting.advection", "\"least_squares\""}});  // (the defaults before issue 32)
  Simulation sim(params);
  IterationLog log;
  sim.AddObserver(&log);
  sim.Run();
  ASSERT_EQ(log.iterations.size(), 60u);
  double settled = 0.0;
  for (std::size_t k = 10; k < 60; ++k) settled += static_cast<double>(log.iterations[k]) / 50.0;
  const double drag = sim.state().particles[0].force.x();
  std::printf("recycled: %.2f outer iterations a step over steps 11-60, K = %.7f\n", settled, drag);
  EXPECT_LE(settled, 8.56 / 2.0);
  EXPECT_NEAR(drag, 96.46655, 2e-4 * 96.46655);
}

// When the coupled PCG gives up, its error names the keys that help
// (ViscousConstraint::RemedyText). With collocation points the coupled Stokes solves' tolerance
// comes first, with its value at the failure: a fixed disk 3h/4 off the nodes at D/h = 40 stalled
// above the target through 1000 iterations with it at 1e-6 (the default's effective value) and
// converged in 287 at 1e-8 (docs/evidence/particle_boundary.md, "The circle's sub-grid position");
// a stall now tightens it (ViscousCoupling.StallTightensTheCoupledStokesSolves), so the value named
// is the one reached. The ring mesh's advice is the multiplier keys only.
TEST(ViscousCoupling, NonConvergenceNamesTheKeysThatHelp) {
  for (const char* kind : {"collocation", "ring"}) {
    const Params params =
        LoadSceneFile(std::string(DLMFD_SOURCE_DIR) + "/cases/verification/schaefer_turek_2d1.toml",
                      {{"particle_mesh.kind", std::string("\"") + kind + "\""},
                       {"splitting.constraint", "\"viscous\""}});
    const std::string remedy = ViscousConstraint::RemedyText(
        params.particle_mesh.kind, ViscousConstraint::StokesSettings(params).stokes_tolerance);
    EXPECT_NE(remedy.find("solvers.multiplier_max_iterations"), std::string::npos) << remedy;
    const bool collocation = std::string(kind) == "collocation";
    EXPECT_EQ(remedy.find("lower solvers.stokes_tolerance") != std::string::npos, collocation)
        << remedy;
    // The effective tolerance: 1e-2 of the multiplier tolerance 1e-4 (solvers' defaults).
    if (collocation) {
      EXPECT_NE(remedy.find("now 1e-06"), std::string::npos) << remedy;
    }
  }
}

}  // namespace
}  // namespace dlmfd
