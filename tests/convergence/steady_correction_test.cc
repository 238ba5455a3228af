// The steady-state correction of the wave-like advection step (fluid/advection_wave.h,
// splitting.steady_correction): the fixed point of the Lie splitting of an implicit Stokes step and
// a Lax-Wendroff-type advection step solves the steady equations with an extra streamline
// diffusion (dt/2)(u.grad)^2 u, so a steady drag moves at first order with dt; with the Taylor
// term removed it does not.
//
// Study (docs/evidence/splitting.md, "The splitting's steady-state error"; the Schaefer-Turek scene
// cases/verification/schaefer_turek_2d1.toml as shipped, D/h = 20, Re 20, t = 5):
//   dt       1e-2     5e-3     2e-3     1e-3     1e-4
//   none     5.8087   5.7573   5.7253   5.7150   5.7088      (Cd; 1.75 % from 1e-2 to 1e-4)
//   taylor   5.7235   5.7042   5.7040   5.7043   5.7077      (0.34 %; at 1e-2 the correction is
//                                                            capped near the disk, theta < 1)
// At t = 2 (this test; the drag is within 0.2 % of its t = 5 value) the corrected runs at
// dt = 5e-3 and 2e-3 differ by 0.005 %, the uncorrected by 0.5 %. Asserted: the default (taylor)
// runs at dt = 5e-3 and 2.5e-3 within 0.05 % of each other, a tenth of what the Taylor term
// moves the uncorrected pair by (asserted above 0.2 %, so the test sees the term it removes).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

// Cd = 2 F_x / (rho U_mean^2 D) of the scene at t = 2, with the correction `correction` ("" for
// the scene's default).
double SchaeferTurekDragAtTwo(const std::string& dt, const std::string& correction) {
  std::vector<SceneOverride> overrides = {{"time.dt", dt},
                                          {"time.end", "2.0"},
                                          {"output.fields_every", "0"},
                                          {"output.particles_every", "0"},
                                          {"output.checkpoint_every", "0"},
                                          // the scheme this study measured (the defaults
                                          // before issue 32)
                                          {"particle_mesh.kind", "\"ring\""},
                                          {"domain.diagonals", "\"sw_ne\""}};
  if (!correction.empty()) overrides.push_back({"splitting.steady_correction", correction});
  const Params params = LoadSceneFile(
      std::string(DLMFD_SOURCE_DIR) + "/cases/verification/schaefer_turek_2d1.toml", overrides);
  Simulation sim(params);
  const long steps = sim.TotalSteps();
  for (long n = 0; n < steps; ++n) sim.Step();
  const double cd = 2.0 * sim.state().particles.at(0).force.x() / (0.2 * 0.2 * 0.1);
  std::printf("Schaefer-Turek D/h = 20, dt = %s, steady_correction %s: Cd(t = 2) = %.5f\n",
              dt.c_str(), correction.empty() ? "(default)" : correction.c_str(), cd);
  return cd;
}

TEST(SteadyCorrection, SteadyDragDoesNotDependOnTheTimeStepByDefault) {
  const double coarse = SchaeferTurekDragAtTwo("0.005", "");
  const double fine = SchaeferTurekDragAtTwo("0.0025", "");
  EXPECT_LE(std::abs(coarse / fine - 1.0), 5e-4);

  const double coarse_none = SchaeferTurekDragAtTwo("0.005", "\"none\"");
  const double fine_none = SchaeferTurekDragAtTwo("0.0025", "\"none\"");
  EXPECT_GE(coarse_none / fine_none - 1.0, 2e-3);  // the Taylor term's streamline diffusion
}

}  // namespace
}  // namespace dlmfd
