// Jeffery's orbit, the small version (issue 37, point 2; the study:
// docs/evidence/validation_particles.md, "Jeffery's orbit", bench/jeffery_orbit.sh): a neutrally
// buoyant ellipse r = a / b = 2 at the centre of a plane Couette flow
// (cases/shapes/jeffery_orbit.toml: a = 0.2, channel H = 2 with walls at -1 and +1 moving at -1 and
// +1, G = 1, periodic length 2, rho = 1, eta = 4, Re = 0.01) turns from broadside (theta = -pi/2)
// to aligned with the flow (theta = -pi) in a quarter of Jeffery's period, T / 4 = pi (r + 1/r) /
// (2 G) (Jeffery 1922; Bretherton 1962 for the elliptic cylinder), on the case's own grid, h = 1/32
// (b / h = 3.2), dt = 5e-4 (nu dt / h^2 = 2.048). Asserted within the study's bound (see
// kQuarterTolerance). The same case with cut cells at dt = 5e-3 (kCutQuarter): its quarter period,
// and K made anew as the ellipse turns.
#include <gtest/gtest.h>

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

// The study (docs/evidence/validation_particles.md, "Jeffery's orbit"): the quarter period's error
// at h = 1/24, 1/32, 1/48 is -4.41, -0.23, -0.45 % and the period's -4.35, -0.45, -0.50 %: from h =
// 1/32 on the grid moves them by 0.2 % at most, well inside the 1 %, which is the bound.
// The later study over sub-grid positions ("Over grids and sub-grid positions") found the quarter
// period at h = 1/32 between -1.96 and +0.60 % as the centre moves within a cell, and +1.6 % at h =
// 1/64 half a cell off: this check holds at the case's position, not at every position. Those are
// the turned interior lattice's; with the layers of interior points (since 2026-12-07) the quarter
// period is -0.44 % at the case's position (this check), between -2.40 and -0.44 % over three
// positions at h = 1/32 and -1.02 % at h = 1/48.
constexpr double kQuarterTolerance = 0.01;

// Counts the steps whose free bodies made K (cut cells' report column rigid_modes_made), and keeps
// the last angle.
class KCount : public Observer {
 public:
  void OnStep(const FlowState& state, const StepReport& report) override {
    for (const auto& [name, value] : report.columns) {
      if (name == "rigid_modes_made" && value > 0.0) ++made;
    }
    angle = state.particles[0].angle;
  }
  int made = 0;
  double angle = 0.0;
};

// The quarter period's relative error (the time from theta = -pi/2 to -pi against pi (r + 1/r) /
// (2 G)) of the case with `overrides`, run to t = 12 at most; `k` counts the steps that made K.
double QuarterError(const std::vector<SceneOverride>& overrides, KCount* k = nullptr) {
  const double ratio = 2.0, shear = 1.0;
  const double quarter = kPi * (ratio + 1.0 / ratio) / (2.0 * shear);
  std::vector<SceneOverride> all = {ParseOverride("time.end=12.0")};
  all.insert(all.end(), overrides.begin(), overrides.end());
  Params params =
      LoadSceneFile(std::string(DLMFD_SOURCE_DIR) + "/cases/shapes/jeffery_orbit.toml", all);
  params.threads = 1;
  Simulation sim(params);
  if (k != nullptr) sim.AddObserver(k);
  double broadside = -1.0, aligned = -1.0;
  double t0 = 0.0, theta0 = 0.0;
  while (aligned < 0.0 && !sim.Done()) {
    sim.Step();
    const double t1 = sim.state().time, theta1 = sim.state().particles[0].angle;
    // Linear interpolation of the crossings of -pi/2 (first) and then -pi.
    const double target = broadside < 0.0 ? -0.5 * kPi : -kPi;
    if (theta0 > target && theta1 <= target) {
      const double at = t0 + (theta0 - target) / (theta0 - theta1) * (t1 - t0);
      (broadside < 0.0 ? broadside : aligned) = at;
    }
    t0 = t1;
    theta0 = theta1;
  }
  EXPECT_GT(aligned, 0.0);
  const double error = (aligned - broadside) / quarter - 1.0;
  std::printf(
      "broadside at t = %.4f, aligned at t = %.4f: quarter period %.4f against %.4f "
      "(%+.3f %%)\n",
      broadside, aligned, aligned - broadside, quarter, 100.0 * error);
  return error;
}

TEST(EllipseJefferyOrbit, AQuarterTurnTakesAQuarterOfJefferysPeriod) {
  EXPECT_LT(std::abs(QuarterError({})), kQuarterTolerance);
}

// The same case cut (particle_mesh.kind = "cut_cell"; the scene's rules set splitting.beta = 0) at
// dt = 5e-3 (docs/evidence/cut_cell_boundary.md, "Moving ellipses"): the quarter period is +2.83 /
// +2.91 / +2.96 % with the centre on the node, h / 4 and h / 2 off it at h = 1/32, +2.82 and +2.66
// % on the node at h = 1/48 and 1/64 (at dt = 5e-4 and h = 1/32: +3.03 / +3.12 / +3.17 %). The
// slowing is the box's, not the grid's: in a box twice as large each way it is +1.18 %. Asserted:
// within kCutQuarterBand of the node's value, the largest distance of those five runs (0.17 %)
// rounded up; a cut that did not turn with the body, or a torque off by a disk's formula, is off by
// far more. And K, kept while a body moves less than particle_mesh.rigid_modes_refresh h, is made
// anew once the ellipse has turned that far at its bounding radius a: 1 + floor(|theta| a / h)
// times (a rule that looked at the centre only, a disk's, made it once).
constexpr double kCutQuarter = 0.0283, kCutQuarterBand = 0.003;

TEST(EllipseJefferyOrbit, CutCellsTurnItAsTheBoxSlowsIt) {
  KCount k;
  const double error = QuarterError(
      {ParseOverride("particle_mesh.kind=\"cut_cell\""), ParseOverride("time.dt=0.005")}, &k);
  EXPECT_NEAR(error, kCutQuarter, kCutQuarterBand);
  const double a = 0.2, h = 1.0 / 32.0;
  const int expected = static_cast<int>(std::floor(std::abs(k.angle) * a / h)) + 1;
  std::printf("K made %d times over a turn of %.4f (expected %d)\n", k.made, k.angle, expected);
  EXPECT_NEAR(k.made, expected, 1);
}

}  // namespace
}  // namespace dlmfd
