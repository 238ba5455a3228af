// Lid-driven cavity, Newtonian, Re = 100 (unit square, lid u = 1, eta = 0.01, rho = 1), the scene
// cases/lid_driven_cavity.toml on 32 x 32 cells, run to steady state and compared on both
// centre-lines with Ghia, Ghia & Shin, J. Comput. Phys. 48 (1982) 387-411, tables I and II
// (copied below from the project's shared reference data, docs/sources/reference_data.md), the
// computed centre-line interpolated linearly to Ghia's points.
//
// Grid study (docs/evidence/validation.md, wave advection, dt = 0.01, t = 20, dlmfd-solve and
// cases/verification/cavity_ghia_errors.sh), since the corners of the lid take the walls' normal
// component (fluid/boundary_data.h; before, the lid leaked through the side walls and the
// deviation fell at first order: 0.0318 / 0.0157 / 0.0073):
//   cells   max|u - Ghia|   max|v - Ghia|   max|u - u_256| on x = 0.5   max|v - v_256| on y = 0.5
//     32       0.0048          0.0085            1.66e-3                    1.28e-3
//     64       0.0034          0.0087            3.46e-4                    2.34e-4
//    128       0.0033          0.0085            6.9e-5                     4.9e-5
// Against the engine's own 256-cell solution (at the 32-cell nodes, the same dt) the centre-lines
// converge at order 2.0-2.3; against Ghia the deviation stops at Ghia's own accuracy (v at
// x = 0.8594 is 0.0085 below the table on every grid; the peer's is 0.0091-0.0094).
// This test runs 32 cells with dt = 0.02 to t = 15 (750 steps) to stay within seconds, each scheme
// with the steady correction "taylor" (the default until 2026-12-05): 0.0062 / 0.0117 (wave; 0.0066
// / 0.0079 without the correction) and 0.0060 / 0.0116 (least squares, the default since
// 2026-12-03; 0.0128 / 0.0080 without it). Without the correction the first-order splitting error
// dominates at dt = 0.02 (at 64 cells u moves by 0.45 dt, least squares about twice as much), and
// the two schemes differ by 0.0067 in u; with it they agree to 3e-4. The correction brings the run
// closer to the dt -> 0 solution (64 cells, dt = 0.01 against 0.001: max|u - u_ref| 0.0021 against
// 0.0044, max|v - v_ref| 0.0028 against 0.0035) and further from Ghia's v, because the uncorrected
// scheme's streamline diffusion had cancelled part of Ghia's own offset at x = 0.8594 (the dt -> 0
// solution on 64 cells is 0.0096 from it; docs/evidence/validation.md, "The steady-state correction
// on the cavity"). The code is deterministic to round-off, so these values are what the test
// reproduces; asserted is the value plus 0.0005, a third of the 32-cell grid error against the
// 256-cell solution (1.7e-3 in u, 1.3e-3 in v): a regression worth a third of the grid error fails,
// and so would the leaky lid (0.0327 in this run). Time to steady state is not in the margin: from
// t = 15 to 20 the errors move by 1e-4.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

// Ghia, Ghia & Shin (1982), Re = 100: u on x = 0.5 (table I) and v on y = 0.5 (table II).
constexpr double kGhiaY[17] = {1.0000, 0.9766, 0.9688, 0.9609, 0.9531, 0.8516,
                               0.7344, 0.6172, 0.5000, 0.4531, 0.2813, 0.1719,
                               0.1016, 0.0703, 0.0625, 0.0547, 0.0000};
constexpr double kGhiaU[17] = {1.00000,  0.84123,  0.78871,  0.73722,  0.68717,  0.23151,
                               0.00332,  -0.13641, -0.20581, -0.21090, -0.15662, -0.10150,
                               -0.06434, -0.04775, -0.04192, -0.03717, 0.0};
constexpr double kGhiaX[17] = {1.0000, 0.9688, 0.9609, 0.9531, 0.9453, 0.9063,
                               0.8594, 0.8047, 0.5000, 0.2344, 0.2266, 0.1563,
                               0.0938, 0.0781, 0.0703, 0.0625, 0.0000};
constexpr double kGhiaV[17] = {0.0,      -0.05906, -0.07391, -0.08864, -0.10313, -0.16914,
                               -0.22445, -0.24533, 0.05454,  0.17527,  0.17507,  0.16077,
                               0.12317,  0.10890,  0.10091,  0.09233,  0.0};

struct CentreLineErrors {
  double u = 0.0, v = 0.0, u_min = 0.0;
};

// Linear interpolation of node values f(k) = values[start + k * stride], k = 0..n, at s in [0, 1].
double Interpolate(const std::vector<double>& values, std::size_t start, std::size_t stride, int n,
                   double s) {
  const int k = std::min(static_cast<int>(std::floor(s * n)), n - 1);
  const double w = s * n - k;
  return (1.0 - w) * values[start + k * stride] + w * values[start + (k + 1) * stride];
}

CentreLineErrors RunCavity(const std::string& advection) {
  const std::vector<SceneOverride> overrides = {
      {"domain.h", "0.03125"},
      {"time.dt", "0.02"},
      {"time.end", "15.0"},
      {"splitting.advection", advection},
      {"domain.diagonals", "\"sw_ne\""},  // the mesh of the study
      // the correction of the study (the default until 2026-12-05; the tendency correction, the
      // default since, leaves the end-of-step velocity read here O(dt) from the steady solution,
      // which its snapshots replace by the Stokes step's: docs/evidence/validation.md, "Against
      // accurate references, with the tendency correction")
      {"splitting.steady_correction", "\"taylor\""},
      {"output.fields_every", "0"},
      {"output.checkpoint_every", "0"}};
  const Params params =
      LoadSceneFile(std::string(DLMFD_SOURCE_DIR) + "/cases/lid_driven_cavity.toml", overrides);
  Simulation sim(params);
  const long steps = sim.TotalSteps();
  for (long n = 0; n < steps; ++n) sim.Step();
  const Grid& g = sim.grid();
  const FlowState& s = sim.state();
  const int c = g.nx / 2;
  CentreLineErrors e;
  e.u_min = 1.0;
  for (int j = 0; j <= g.ny; ++j) e.u_min = std::min(e.u_min, s.u[g.Index(c, j)]);
  for (int k = 0; k < 17; ++k) {
    const double u = Interpolate(s.u, g.Index(c, 0), std::size_t(g.nx + 1), g.ny, kGhiaY[k]);
    const double v = Interpolate(s.v, g.Index(0, c), 1, g.nx, kGhiaX[k]);
    e.u = std::max(e.u, std::abs(u - kGhiaU[k]));
    e.v = std::max(e.v, std::abs(v - kGhiaV[k]));
  }
  std::printf(
      "cavity Re = 100, 32 cells, %s: max|u - Ghia| = %.5f, max|v - Ghia| = %.5f, min u = %.5f\n",
      advection.c_str(), e.u, e.v, e.u_min);
  return e;
}

constexpr double kMargin = 0.0005;  // see the header

TEST(LidDrivenCavity, CentreLinesAgreeWithGhiaWithinTheGridStudyWave) {
  const CentreLineErrors e = RunCavity("wave");
  EXPECT_LE(e.u, 0.00618 + kMargin);
  EXPECT_LE(e.v, 0.01165 + kMargin);
  EXPECT_LT(e.u_min, 0.0);  // the primary vortex turns the centre-line flow back
}

TEST(LidDrivenCavity, CentreLinesAgreeWithGhiaWithinTheGridStudyLeastSquares) {
  const CentreLineErrors e = RunCavity("least_squares");
  EXPECT_LE(e.u, 0.00595 + kMargin);
  EXPECT_LE(e.v, 0.01160 + kMargin);
  EXPECT_LT(e.u_min, 0.0);
}

}  // namespace
}  // namespace dlmfd
