// A free disk cut out of the mesh (particles/cut_cell_free_bodies.h; issue 33 point 2) settles
// onto the bottom wall and comes to rest where the paper's wall force (15) carries its weight, with
// no overlap and no blow-up. docs/evidence/cut_cell_boundary.md, "A free body", "A free disk
// settling onto a wall".
//
// Scene: cases/verification/faxen_disk_w1.toml (D = 0.2, eta = 0.1, walls all round) made 2 high,
// the disk released 0.03 above the floor (gap 1.5 h at D/h = 10), rho_f = 0.01, rho_p = 0.02,
// dt = 0.01 (Faxen's creeping scene of cut_cell_free_disk_test.cc), to t = 1. The wall force of
// particles/collision_forces.h, F = (1/eps_w) 2 (R + g) (rho - 2 g)^2 for a gap g < rho / 2
// (rho = 1.5 h, eps_w = 1e-5), balances the weight less buoyancy W = (rho_p - rho_f) pi R^2 |g|
// at one gap g*, 0.0131549 at D/h = 10 (0.658 h; 0.0055899 = 0.559 h at D/h = 20).
// Study (Release, one thread; smallest gap, gap at the end):
// - D/h = 10: the disk enters the force's range at t = 0.37 and overshoots once to 0.0125742
//   (0.956 g*; the collision force is explicit and comes once a step, its spring's period about
//   1.3 dt), rebounds and is at rest at g* within 1e-7 from t = 0.8 (|v| 1.6e-7 at t = 1, 5e-15
//   at t = 2), the lateral velocity and rotation at round-off (6e-16, 1.4e-14).
// - D/h = 20 (from the same height, to t = 8): no overshoot, at rest at 0.0055899 (g* to 1e-9)
//   from t = 1.6; over the last cell of the approach (gap below 1.4 h) the disk falls faster
//   (-0.0108 at gap 1.6 h, -0.0221 at 1.0 h): the liquid left under it lies within one cell,
//   and the film's lubrication is no longer resolved.
// Asserted at D/h = 10: the smallest gap above 0.9 g* (no overlap, measured 0.956 g*), the gap at
// t = 1 equal to g* within 1e-5 of it (measured 2e-6, the rest at round-off being 1e-7 away at
// t = 1 by the damped rebound), and the lateral velocity and rotation below 1e-10. Since the first
// solve's motion comes from Newton's law (particles/cut_cell_free_bodies.h, Predict): smallest gap
// 0.0128444 (0.976 g*), the gap at t = 1 g* to 2.9e-12 (|v| 2.7e-11); the linear extrapolation
// 2 V^n - V^{n-1} fails here (0.867 g*, still bouncing at t = 1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "dlmfd/core/constants.h"
#include "dlmfd/core/observer.h"
#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

struct WallContact {
  double smallest_gap = 1.0, end_gap = 0.0, end_speed = 0.0, lateral = 0.0;
  double rest = 0.0;  // g*
  int k_made = 0;     // steps that made K (report column rigid_modes_made)
};

class KMadeCount : public Observer {
 public:
  void OnStep(const FlowState& /*state*/, const StepReport& report) override {
    for (const auto& [name, value] : report.columns)
      if (name == "rigid_modes_made" && value > 0.0) ++made;
  }
  int made = 0;
};

// The gap g at which the wall force (15) equals the weight less buoyancy (bisection: the force
// falls monotonically over 0 <= g <= rho / 2).
double EquilibriumGap(const Params& params) {
  const ParticleParams& disk = params.particles[0];
  const double radius = disk.Radius(), range = params.collisions.range * params.domain.h;
  const double weight =
      (disk.density - params.fluid.density) * kPi * radius * radius * params.gravity.norm();
  double lo = 0.0, hi = 0.5 * range;
  for (int k = 0; k < 200; ++k) {
    const double g = 0.5 * (lo + hi);
    const double force = 2.0 * (radius + g) * (range - 2.0 * g) * (range - 2.0 * g) /
                         params.collisions.wall_stiffness;
    (force > weight ? lo : hi) = g;
  }
  return 0.5 * (lo + hi);
}

// Released with its centre at `height`, to t = `end`; K kept at the default
// particle_mesh.rigid_modes_refresh.
WallContact SettleOntoTheFloor(const std::string& h, const std::string& height = "0.13",
                               const std::string& end = "1.0") {
  const std::vector<SceneOverride> overrides = {{"domain.h", h},
                                                {"domain.size", "[1.0, 2.0]"},
                                                {"particles.0.center", "[0.5, " + height + "]"},
                                                {"fluid.density", "0.01"},
                                                {"particles.0.density", "0.02"},
                                                {"time.dt", "0.01"},
                                                {"time.end", end},
                                                {"output.particles_every", "0"},
                                                {"output.fields_every", "0"},
                                                {"particle_mesh.kind", "\"cut_cell\""}};
  Params params = LoadSceneFile(
      std::string(DLMFD_SOURCE_DIR) + "/cases/verification/faxen_disk_w1.toml", overrides);
  params.threads = 1;
  WallContact w;
  w.rest = EquilibriumGap(params);
  Simulation sim(params);
  KMadeCount count;
  sim.AddObserver(&count);
  const long steps = sim.TotalSteps();
  for (long n = 0; n < steps; ++n) {
    sim.Step();
    const ParticleState& disk = sim.state().particles[0];
    w.smallest_gap = std::min(w.smallest_gap, disk.position.y() - disk.radius);
    w.lateral = std::max({w.lateral, std::abs(disk.velocity.x()), std::abs(disk.angular_velocity)});
  }
  const ParticleState& disk = sim.state().particles[0];
  w.end_gap = disk.position.y() - disk.radius;
  w.end_speed = disk.velocity.norm();
  w.k_made = count.made;
  return w;
}

TEST(CutCellWallContact, FreeDiskComesToRestWhereTheWallForceCarriesItsWeight) {
  const WallContact w = SettleOntoTheFloor("0.02");
  const double rest = w.rest;
  std::printf(
      "g* = %.7f; smallest gap %.7f (%.3f g*), at t = 1 %.7f (%+.1e g*), |v| %.1e, lateral "
      "%.1e\n",
      rest, w.smallest_gap, w.smallest_gap / rest, w.end_gap, w.end_gap / rest - 1.0, w.end_speed,
      w.lateral);
  EXPECT_GT(w.smallest_gap, 0.9 * rest);
  EXPECT_NEAR(w.end_gap / rest, 1.0, 1e-5);
  EXPECT_LT(w.lateral, 1e-10);
}

// The approach over many cells with K kept over steps (particle_mesh.rigid_modes_refresh, the
// default 1): released with its centre at 0.43 (gap 15.8 h at D/h = 10), the disk nears the wall
// while the liquid's resistance grows (K made anew once it has moved a cell: 16 times in 400
// steps), enters the force's range at t = 3.15 and is at rest at g* from t = 3.5. Measured
// (docs/evidence/cut_cell_boundary.md, "K kept over 2 or 4 cells"):
// smallest gap 0.996 g* (K every step 1.000, K kept 2 cells 0.992), the gap at t = 4 g* to
// round-off. With K kept 4 cells the update goes unstable near the wall (the kept K too far
// below the film's resistance): the disk is thrown up at gap 1.5 h (t = 2.64) and the run fails at
// t = 5.1, the disk reaching the floor; this test then fails on the gap at t = 4. Asserted: K
// made 4 to 39 times (kept, and made anew over the approach; 2 cells: 8), the smallest gap above
// 0.9 g*, the gap at t = 4 g* within 1e-5, the lateral motion below 1e-10 (measured 1.0e-13).
TEST(CutCellWallContact, FreeDiskFallingManyCellsComesToRestWithKKept) {
  const WallContact w = SettleOntoTheFloor("0.02", "0.43", "4.0");
  const double rest = w.rest;
  std::printf("K made %d times; smallest gap %.7f (%.3f g*), at t = 4 %+.1e g*, |v| %.1e\n",
              w.k_made, w.smallest_gap, w.smallest_gap / rest, w.end_gap / rest - 1.0, w.end_speed);
  EXPECT_GE(w.k_made, 4);
  EXPECT_LT(w.k_made, 40);
  EXPECT_GT(w.smallest_gap, 0.9 * rest);
  EXPECT_NEAR(w.end_gap / rest, 1.0, 1e-5);
  EXPECT_LT(w.lateral, 1e-10);
}

}  // namespace
}  // namespace dlmfd
