// Stability of the wave-like scheme of step (34) (engine/src/fluid/advection_wave.cc), measured on
// the engine and asserted against a von Neumann analysis of the same discrete operators.
//
// Theory. For a constant flow V in a doubly periodic box every operator is circulant, so a Fourier
// mode exp(i(theta_x i + theta_y j)) is an eigenvector. With the lumped mass M = h^2:
//   M^-1 C   -> i sigma |V| / h, sigma = (V/|V|) . g(theta), g the symbol of the integrated
//   gradient
//               G (method notes 1, section 1) divided by h^2, which is real;
//   M^-1 K_V -> kappa |V|^2 / h^2, kappa = (|g1|^2 + |g2|^2) / 2, g1, g2 the difference quotients
//   of
//               the mode along V on the two triangles of a square (W_T = |T| V V^T for constant V).
// With c = tau |V| / h and y = c^2 kappa, one call (start-up, then Q - 1 centred sub-steps) maps
// the mode's amplitude 1 to
//   u^1 = 1 - i c sigma - y / 2,  u^{q+1} = (2 - y) u^q - u^{q-1},  G = u^Q,
// and, writing cos phi = 1 - y / 2, G = cos(Q phi) - i c sigma sin(Q phi) / sin(phi). Hence |G| <=
// 1 for every mode iff y <= 4 (the leapfrog limit of K_V alone) and
//   sigma^2 <= kappa (1 - c^2 kappa / 4)   (the restarted Taylor start must not add energy),
// a condition independent of Q. Because C (vertex quadrature of N(V, .)) is not C^T M^-1
// C-compatible with K_V, the second condition binds before the leapfrog limit except across the
// diagonals:
//   along x or y: c* = sqrt(2/3) = 0.816 (modes with theta_y = -theta_x / 2; leapfrog alone gives
//   1); along y = x:  c* = 2/sqrt(3) = 1.155 (leapfrog alone gives sqrt(2)); along y = -x: c* =
//   1/sqrt(2) = 0.707 (the checkerboard, leapfrog limit of K_V);
// and 1/sqrt(2) is the minimum over all directions (at 135 degrees). The method notes' 1.02-1.04
// came from power iteration on M^-1 K_V alone for nearly vertical fields, which misses both the
// start-up condition and the direction dependence; solvers.wave_max_courant = 0.5 keeps a margin of
// 0.7 below the worst direction for flows that are not uniform.
//
// Measurement. Power iteration on the engine's own map: u = U + eps x, one AdvectionWave::Solve
// (diffusion off), x <- (u - U) / eps, renormalised. The linearised map is circulant, hence normal,
// so every ratio |G x| / |x| is at most the spectral radius rho, and the ratios approach rho from
// below as the iteration converges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/core/params.h"
#include "dlmfd/fluid/advection_wave.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/fluid/node_set.h"
#include "dlmfd/mesh/boundary_topology.h"

namespace dlmfd {
namespace {

using Complex = std::complex<double>;
constexpr int kWaveCells = 32;  // periodic box of 32 x 32 cells
constexpr int kSubstepCounts[] = {1,
                                  2};  // Q = 1 is the engine's minimum; the theory holds for any Q

// Spectral radius of one call of the scheme over the modes of the kWaveCells-periodic grid (theory
// above).
double TheoreticalRadius(Vec2 direction, double courant, int substeps) {
  const Vec2 d = direction.normalized();
  const Complex i1(0.0, 1.0);
  double rho = 0.0;
  for (int a = 0; a < kWaveCells; ++a) {
    for (int b = 0; b < kWaveCells; ++b) {
      const Complex ex = std::exp(i1 * (2.0 * kPi * a / kWaveCells)),
                    ey = std::exp(i1 * (2.0 * kPi * b / kWaveCells));
      const Complex gx =
          (2.0 * (ex - 1.0 / ex) + (1.0 / ey - 1.0 / (ex * ey)) + (ex * ey - ey)) / 6.0;
      const Complex gy =
          (2.0 * (ey - 1.0 / ey) + (ex * ey - ex) + (1.0 / ex - 1.0 / (ex * ey))) / 6.0;
      const double sigma = (d.x() * gx + d.y() * gy).imag();
      const Complex g1 = d.x() * (ex - 1.0) + d.y() * ex * (ey - 1.0);
      const Complex g2 = d.x() * ey * (ex - 1.0) + d.y() * (ey - 1.0);
      const double y = courant * courant * 0.5 * (std::norm(g1) + std::norm(g2));
      Complex u0 = 1.0, u1 = 1.0 - i1 * courant * sigma - 0.5 * y;
      for (int q = 1; q < substeps; ++q) {
        const Complex u2 = (2.0 - y) * u1 - u0;
        u0 = u1;
        u1 = u2;
      }
      rho = std::max(rho, std::abs(u1));
    }
  }
  return rho;
}

// Largest Courant number with TheoreticalRadius <= 1 (bisection to 1e-6).
double TheoreticalLimit(Vec2 direction, int substeps) {
  double lo = 0.1, hi = 2.0;
  while (hi - lo > 1e-6) {
    const double mid = 0.5 * (lo + hi);
    (TheoreticalRadius(direction, mid, substeps) <= 1.0 + 1e-12 ? lo : hi) = mid;
  }
  return lo;
}

// Power iteration on the engine's linearised per-call map; returns the last ratio |G x| / |x|.
double MeasuredRadius(Vec2 flow, double courant, int iterations, int substeps) {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(1.0, 1.0);
  p.domain.h = 1.0 / kWaveCells;
  for (BoundarySide& s : p.domain.sides) s.type = SideType::kPeriodic;
  p.fluid.viscosity = 0.02;
  p.fluid.solvent_ratio = 1.0;
  p.solvers.wave_max_courant = courant * 1.01;  // exactly `substeps` sub-steps of Courant `courant`
  p.time.dt = substeps * courant * p.domain.h / flow.norm();
  const Grid g{kWaveCells, kWaveCells, p.domain.h, 0.0, 0.0};
  BoundaryData data(g, p.domain);
  AdvectionWave wave(g, p.domain, p.fluid, 0.0, SteadyCorrection::kNone, p.solvers, data);
  NodeSet nodes(g, BoundaryTopology::ForVelocity(p.domain));
  const std::size_t n = g.NodeCount();
  std::vector<double> xu(n), xv(n), u(n), v(n);
  unsigned state = 2024u;
  for (std::size_t k = 0; k < n; ++k) {
    state = state * 1664525u + 1013904223u;
    xu[k] = static_cast<double>(state >> 8) / 16777216.0 - 0.5;
    state = state * 1664525u + 1013904223u;
    xv[k] = static_cast<double>(state >> 8) / 16777216.0 - 0.5;
  }
  nodes.SyncPeriodic(xu.data());
  nodes.SyncPeriodic(xv.data());
  auto norm = [&] { return std::sqrt(nodes.Dot2(xu.data(), xu.data(), xv.data(), xv.data())); };
  // eps keeps the quadratic part (eps^2 relative to eps) far below the ratios' resolution.
  const double eps = 1e-7;
  double ratio = 0.0, before = norm();
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t k = 0; k < n; ++k) {
      u[k] = flow.x() + eps * xu[k] / before;
      v[k] = flow.y() + eps * xv[k] / before;
    }
    const AdvectionReport r = wave.Solve(p.time.dt, u.data(), v.data());
    EXPECT_EQ(r.iterations, substeps);
    for (std::size_t k = 0; k < n; ++k) {
      xu[k] = (u[k] - flow.x()) / eps;
      xv[k] = (v[k] - flow.y()) / eps;
    }
    const double after = norm();
    ratio = after;  // |G x| for |x| = 1
    before = after;
  }
  return ratio;
}

struct Direction {
  const char* name;
  Vec2 flow;
  double analytic_limit;  // from the continuous-theta analysis in the header
};

const Direction kDirections[] = {{"x", Vec2(1.0, 0.0), std::sqrt(2.0 / 3.0)},
                                 {"y", Vec2(0.0, 0.8), std::sqrt(2.0 / 3.0)},
                                 {"y=x", Vec2(0.6, 0.6), 2.0 / std::sqrt(3.0)},
                                 {"y=-x", Vec2(0.6, -0.6), 1.0 / std::sqrt(2.0)}};

// The discrete theory on the 32-periodic grid agrees with the continuous analysis (the grid's
// modes only sample theta, so its limit is at least the continuous one and close to it).
TEST(AdvectionWaveStability, TheoryOnTheGridMatchesTheAnalysis) {
  for (const int q : kSubstepCounts) {
    for (const Direction& d : kDirections) {
      const double limit = TheoreticalLimit(d.flow, q);
      std::printf("Q = %d, flow along %-5s theoretical limit %.4f (continuous theta: %.4f)\n", q,
                  d.name, limit, d.analytic_limit);
      EXPECT_GE(limit, d.analytic_limit - 1e-5) << d.name << ", Q = " << q;
      EXPECT_LE(limit, d.analytic_limit * 1.01)
          << d.name << ", Q = " << q;  // 32 modes resolve theta to 2 pi/32
    }
  }
}

// The engine's amplification: never above the theoretical radius (normal map), equal to it once the
// power iteration has converged, and so stable at 0.97 c* and unstable at 1.05 c* in every
// direction.
TEST(AdvectionWaveStability, MeasuredLimitMatchesTheoryInEveryDirection) {
  for (const int q : kSubstepCounts) {
    for (const Direction& d : kDirections) {
      const double limit = TheoreticalLimit(d.flow, q);
      for (const double factor : {0.97, 1.05}) {
        const double c = factor * limit;
        const double theory = TheoreticalRadius(d.flow, c, q);
        const double measured = MeasuredRadius(d.flow, c, 300, q);
        std::printf("Q = %d, flow along %-5s Courant %.4f: radius measured %.6f, theory %.6f\n", q,
                    d.name, c, measured, theory);
        // Round-off of (u - U) / eps with eps = 1e-7 and |U| ~ 1 is about 1e-16 / 1e-7 = 1e-9 per
        // node.
        EXPECT_LE(measured, theory + 1e-6) << d.name << ", Q = " << q;
        if (factor < 1.0) {
          EXPECT_LE(measured, 1.0 + 1e-6) << d.name << ", Q = " << q;
        } else {
          // Above the limit the iteration converges slowly where neighbouring grid modes have radii
          // close to the largest (measured after 300 calls with Q = 2: 58-83 % of the theoretical
          // excess along x, y and y = x, 99.99 % along y = -x); a quarter of the excess still
          // separates it from <= 1.
          EXPECT_GE(measured - 1.0, 0.25 * (theory - 1.0)) << d.name << ", Q = " << q;
          EXPECT_GT(theory, 1.0 + 1e-3) << d.name << ", Q = " << q;
        }
      }
    }
  }
}

// The default sub-step rule keeps every direction stable: wave_max_courant is below the worst
// direction's limit 1/sqrt(2).
TEST(AdvectionWaveStability, DefaultMaxCourantIsBelowTheWorstDirection) {
  const SolverParams defaults;
  EXPECT_LT(defaults.wave_max_courant, 1.0 / std::sqrt(2.0));
  for (const Direction& d : kDirections) {
    for (const int q : kSubstepCounts) {
      EXPECT_LE(MeasuredRadius(d.flow, defaults.wave_max_courant, 100, q), 1.0 + 1e-6)
          << d.name << ", Q = " << q;
    }
  }
}

}  // namespace
}  // namespace dlmfd
