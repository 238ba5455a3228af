// Start-up of plane Poiseuille flow of an Oldroyd-B liquid through the whole Simulation, against
// the series of Waters & King (Rheol. Acta 9 (1970) 345-355), docs/sources/reference_data.md.
//
// Scene: cases/verification/waters_king.toml. Channel periodic in x, walls at y = 0 and y = 2H
// (H = 1), at rest with A = I, driven from t = 0 by the body force G = 3 (= -dp/dx). With rho = 1,
// eta = 1, lambda = 1: E = lambda eta / (rho H^2) = 1, beta = 1/9, Ubar = G H^2 / (3 eta) = 1 and
// T = t / lambda = t, so the centre-line velocity u(x, H, t) is U(0, T) of the series directly.
// Splitting alpha = 1, beta = 0: all the solvent viscosity is in (33), which makes the steady
// parabola an exact fixed point of the scheme (tests/unit/stokes_test.cc); with alpha < 1 the
// Marchuk-Yanenko steady state differs from it by O(dt). The polymer force of A^n enters (33) and
// step (35) follows with u^{n+2/4}; u = (u(y), 0) has N(u, u) = 0, so the advection scheme is idle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "dlmfd/core/simulation.h"
#include "dlmfd/reference/waters_king_series.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

constexpr double kBeta = 1.0 / 9.0;  // eta_s / eta
constexpr double kElasticity = 1.0;  // E = lambda eta / (rho H^2)
constexpr double kEndT = 6.0;

// U(0, T) / Ubar of the Waters-King series (engine/include/dlmfd/reference/waters_king_series.h).
double Centreline(double t) { return WatersKingVelocity(0.0, t, kBeta, kElasticity); }

// Extremum of Centreline on [lo, hi] by golden-section search (unimodal there); sign = +1 for a
// maximum, -1 for a minimum. Returns the abscissa.
double Extremum(double lo, double hi, double sign) {
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = lo, b = hi;
  for (int it = 0; it < 100; ++it) {
    const double c = b - r * (b - a), d = a + r * (b - a);
    if (sign * Centreline(c) > sign * Centreline(d)) {
      b = d;
    } else {
      a = c;
    }
  }
  return 0.5 * (a + b);
}

std::string Text(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

struct History {
  std::vector<double> t, u;  // centre-line velocity after each step
};

// Runs the scene with ny cells across the gap (nx = 4) and time step dt up to T = kEndT, with
// fluid.conformation = representation and fluid.stress_splitting = splitting.
History RunStartup(int ny, double dt, const std::string& representation = "standard",
                   const std::string& splitting = "explicit") {
  const double h = 2.0 / ny;
  const std::vector<SceneOverride> overrides = {
      {"domain.h", Text(h)},
      {"domain.size", "[" + Text(4 * h) + ", 2.0]"},
      {"time.dt", Text(dt)},
      {"time.end", Text(kEndT)},
      {"fluid.conformation", representation},
      {"fluid.stress_splitting", splitting},
      {"domain.diagonals", "\"sw_ne\""}};  // the study's mesh
  Params params = LoadSceneFile(DLMFD_SOURCE_DIR "/cases/verification/waters_king.toml", overrides);
  params.threads = 1;  // a 4 x ny grid: threads would only contend
  Simulation sim(params);
  const Grid& g = sim.grid();
  const std::size_t centre = g.Index(0, g.ny / 2);
  History hist;
  hist.t.reserve(static_cast<std::size_t>(sim.TotalSteps()));
  hist.u.reserve(static_cast<std::size_t>(sim.TotalSteps()));
  while (!sim.Done()) {
    sim.Step();
    hist.t.push_back(sim.state().time);
    hist.u.push_back(sim.state().u[centre]);
  }
  return hist;
}

double MaxError(const History& h) {
  double e = 0.0;
  for (std::size_t n = 0; n < h.t.size(); ++n)
    e = std::max(e, std::abs(h.u[n] - Centreline(h.t[n])));
  return e;
}

// The series against the README's table (5 decimals: rounding is at most 5e-6) and its extrema
// (2.5513 at T = 1.221, 1.2457 at T = 3.45: rounding 5e-5, 5e-4 and 5e-3).
TEST(WatersKingSeries, MatchesReferenceTable) {
  const double t[] = {0.5, 1, 1.5, 2, 3, 4, 5, 6, 8, 10};
  const double u[] = {1.48960, 2.46619, 2.45954, 2.05795, 1.32141,
                      1.31706, 1.52370, 1.55461, 1.48489, 1.50387};
  for (int k = 0; k < 10; ++k) EXPECT_NEAR(Centreline(t[k]), u[k], 1e-5) << "T = " << t[k];
  EXPECT_NEAR(Centreline(0.0), 0.0, 1e-6);
  EXPECT_NEAR(WatersKingVelocity(0.5, 40.0, kBeta, kElasticity), 1.5 * 0.75,
              1e-10);  // steady parabola
  const double t_max = Extremum(0.5, 2.5, 1.0), t_min = Extremum(2.5, 4.5, -1.0);
  EXPECT_NEAR(t_max, 1.221, 5e-4);
  EXPECT_NEAR(Centreline(t_max), 2.5513, 5e-5);
  EXPECT_NEAR(t_min, 3.45, 5e-3);
  EXPECT_NEAR(Centreline(t_min), 1.2457, 5e-5);
}

// Grid and time-step study for each fluid.stress_splitting (run with
// --gtest_also_run_disabled_tests; 5 minutes on one core): max over T in (0, 6] of
// |u_h(centre, t_n) - U(0, t_n)| per (ny, dt). Measured (Release build), explicit / devss:
//   ny \ dt   0.04               0.02               0.01               0.005              0.0025
//    16   3.33e-2/3.69e-2  2.81e-2/2.89e-2  2.66e-2/2.67e-2  2.58e-2/2.57e-2  2.54e-2/2.52e-2
//    32   1.96e-2/2.06e-2  1.29e-2/1.34e-2  9.19e-3/9.45e-3  7.27e-3/7.40e-3  6.80e-3/6.81e-3
//    64   blow-up/blow-up  9.04e-3/9.17e-3  5.31e-3/5.38e-3  3.36e-3/3.39e-3  2.36e-3/2.37e-3
//   128   blow-up/blow-up  2.13e-1/1.82e-1  4.32e-3/4.34e-3  2.36e-3/2.37e-3  1.36e-3/1.36e-3
// The polymer is elastic on the grid's scale here (El_h = lambda eta_p / (rho h^2) = 57 to 3640),
// so devss carries w = 1 / (1 + El_h) = 0.017 to 3e-4 of eta_p implicitly and follows the
// explicit scheme to 1-10 % of its error. Order in dt at ny = 128: 0.01 -> 0.005 -> 0.0025 gives
// ratios 1.83, 1.74 (first order, as the Marchuk-Yanenko splitting and the explicit polymer force
// of (33) are). Taking the dt part as e_t = 0.4 dt (the 1.0e-3 drop from 0.005 to 0.0025 at
// ny = 128), the h part at dt = 0.0025 is 2.44e-2, 5.8e-3, 1.36e-3, 0.35e-3 for ny = 16..128:
// ratios 4.2, 4.3, 3.9, second order in h. ny = 128 with dt = 0.02 (flow CFL 3.3) has a transient
// 2-D disturbance, and dt = 0.04 blows up: step (34) without viscosity (beta = 0) at a large CFL
// number (docs/evidence/stability.md).
TEST(WatersKingStartup, DISABLED_StressSplittingStudy) {
  for (const char* splitting : {"explicit", "devss"}) {
    for (int ny : {16, 32, 64, 128}) {
      for (double dt : {0.04, 0.02, 0.01, 0.005, 0.0025}) {
        try {
          const History h = RunStartup(ny, dt, "standard", splitting);
          std::printf("%s ny %4d  dt %.4f  max error %.3e\n", splitting, ny, dt, MaxError(h));
        } catch (const std::exception& e) {
          std::printf("%s ny %4d  dt %.4f  failed: %s\n", splitting, ny, dt, e.what());
        }
        std::fflush(stdout);
      }
    }
  }
}

// The test runs (ny, dt) = (32, 0.01) and (64, 0.005) under the default devss: 15 s of CPU on the
// loaded dev machine. Tolerances from the study above: the error model e = C_h h^2 + 0.4 dt
// predicts 1.4e-3 + 2.0e-3 = 3.4e-3 at (64, 0.005) (measured 3.39e-3; explicit 3.356e-3); the bound
// is that estimate plus 20%, 4e-3. Halving h and dt together divides e_h by 4 and e_t by 2, so the
// error ratio between the two runs lies in [2, 4] (measured 2.74); the test asks for at least 1.8,
// which a scheme of order below one would fail. The extrema of the discrete history are sampled
// every dt and lag by the first-order phase error (measured 3.7e-3 at the peak and 5.2e-3 at the
// dip, about one dt): their times must be within 2 dt, their values within the max-error bound.
TEST(WatersKingStartup, CentrelineVelocityFollowsSeries) {
  const History coarse = RunStartup(32, 0.01);
  const double dt = 0.005;
  const History h = RunStartup(64, dt);
  ASSERT_EQ(h.t.size(), 1200u);
  const double error = MaxError(h), error_coarse = MaxError(coarse);
  EXPECT_LE(error, 4e-3);
  EXPECT_GE(error_coarse / error, 1.8)
      << "errors " << error_coarse << " (32, 0.01), " << error << " (64, 0.005)";

  const auto peak = std::max_element(h.u.begin(), h.u.end());
  const std::size_t n_peak = static_cast<std::size_t>(peak - h.u.begin());
  const auto dip = std::min_element(h.u.begin() + static_cast<long>(n_peak), h.u.end());
  const std::size_t n_dip = static_cast<std::size_t>(dip - h.u.begin());
  const double t_max = Extremum(0.5, 2.5, 1.0), t_min = Extremum(2.5, 4.5, -1.0);
  EXPECT_NEAR(*peak, Centreline(t_max), 4e-3);
  EXPECT_NEAR(h.t[n_peak], t_max, 2 * dt);
  EXPECT_NEAR(*dip, Centreline(t_min), 4e-3);
  EXPECT_NEAR(h.t[n_dip], t_min, 2 * dt);
  // The overshoot itself, against the README's figures (their rounding is far below 4e-3).
  EXPECT_NEAR(*peak, 2.5513, 4e-3);
  EXPECT_NEAR(*dip, 1.2457, 4e-3);
}

// Waters-King in each representation (fluid.conformation = log, sqrt): u = (u(y), 0) carries no
// A across the flow (u . grad A = 0), so the advected variable never matters and the runs differ
// from the standard one only by the round-off of log/exp (or sqrt/square) at each node and step.
// The study's error at (32, 0.01) is 9.19e-3 (table above): each representation stays within it
// plus 20%, and within 1e-12 of the standard history (measured 1.8e-14 for log, 2.3e-14 for
// sqrt: the round-off of 600 steps).
TEST(WatersKingStartup, EachRepresentationFollowsSeries) {
  const History standard = RunStartup(32, 0.01);
  for (const char* representation : {"log", "sqrt"}) {
    const History h = RunStartup(32, 0.01, representation);
    ASSERT_EQ(h.u.size(), standard.u.size());
    double difference = 0.0;
    for (std::size_t n = 0; n < h.u.size(); ++n)
      difference = std::max(difference, std::abs(h.u[n] - standard.u[n]));
    std::printf("%s: max error %.3e, max difference from standard %.3e\n", representation,
                MaxError(h), difference);
    EXPECT_LE(MaxError(h), 1.1e-2) << representation;
    EXPECT_LE(difference, 1e-12) << representation;
  }
}

}  // namespace
}  // namespace dlmfd
