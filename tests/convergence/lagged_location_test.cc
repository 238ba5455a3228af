// Where the default (incremental) coupling spreads the lagged multiplier: on the multiplier points
// at X^n + dt U^n, where (37) will hold the particle (issue 13 point 2;
// particles/lagged_multiplier.h, "Where"; docs/stability.md, "The coupling of the constraint",
// failure 2). Spread at X^n, the lag trailed a fast particle by U dt, and paper 5.1a's disk (Re
// about 200, U dt / h about 0.9 at dt = 1e-3 on h = 1/96) failed in four of the paper's six 5.1a
// files under the default, at t = 0.055-0.085, on the least-squares advection's iteration cap
// while its Courant number ran away.
//
// Study (2026-12-03, Release, the six files with `--set 'splitting.constraint="incremental"' --set
// splitting.alpha=1 --set splitting.beta=0 --set time.end=0.5`): all six complete, U over
// [0.25, 0.45] = 10.06 / 10.07 (h = 1/96, dt = 1e-3, Newtonian / Oldroyd-B), 10.31 / 10.42 (dt =
// 4e-4), 10.32 / 10.41 (h = 1/128, h_p = 1/120, dt = 4e-4), max trA 42 / 47 / 56; the paper's
// coupling 9.68 / 9.70, 10.00 / 10.15, 10.09 / 10.12, max trA 42.5. With the lag at X^n the
// Newtonian file at dt = 1e-3 failed at t = 0.078 (and on h = 1/48 at dt = 2e-3, 3e-3 at t = 0.106,
// 0.066).
// This test: that file to t = 0.1 (100 steps) under both couplings. v(0.1) = -8.6385 (default) and
// -8.4099 (paper), 2.7 % apart; asserted within 5 %: the two couplings differ by 3.7-6.2 % in U on
// the 5.1a files (docs/validation.md, "The paper's cases under the default coupling"), and by
// 4 % here over [0.25, 0.45].
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

// The fall speed -v at t = 0.1 of the Newtonian 5.1a disk (h = 1/96, dt = 1e-3), under the
// default coupling (alpha = 1, beta = 0) or under the paper's (alpha = beta = 1/2).
double FallSpeed(bool default_coupling) {
  std::vector<SceneOverride> overrides = {{"time.end", "0.1"},
                                          {"output.fields_every", "0"},
                                          {"output.particles_every", "0"},
                                          {"output.checkpoint_every", "0"}};
  overrides.push_back({"splitting.constraint", default_coupling ? "\"incremental\"" : "\"paper\""});
  overrides.push_back({"splitting.alpha", default_coupling ? "1" : "0.5"});
  overrides.push_back({"splitting.beta", default_coupling ? "0" : "0.5"});
  Params params = LoadSceneFile(
      std::string(DLMFD_SOURCE_DIR) + "/cases/paper/5.1a_newtonian_disk_rho1.5_h96_dt1e-3.toml",
      overrides);
  params.threads = 1;
  Simulation sim(params);
  sim.Run();
  return -sim.state().particles[0].velocity.y();
}

TEST(LaggedLocation, FastDiskFollowsThePapersCoupling) {
  const double lagged = FallSpeed(true);
  const double paper = FallSpeed(false);
  std::printf("5.1a disk at t = 0.1: -v = %.4f (default coupling), %.4f (paper's)\n", lagged,
              paper);
  EXPECT_NEAR(lagged, paper, 0.05 * paper);
}

}  // namespace
}  // namespace dlmfd
