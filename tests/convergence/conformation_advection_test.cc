// Order of convergence of the advection in step (35): a smooth SPD field carried by u = (1, 1) in
// the doubly periodic unit box, relaxing with lambda = 1. The exact solution is A(x, t) = I + (A0(x
// - u t) - I) e^{-t/lambda}: with a uniform u, L = 0 and the advection and the pointwise relaxation
// commute, so the splitting adds no error and only the third-order advection (SSP-RK3 + third-order
// upwind-biased differences, error O(h^3 + dt^3)) remains.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/conformation/conformation_step.h"
#include "dlmfd/core/constants.h"

namespace dlmfd {
namespace {

constexpr double kTwoPi = 2.0 * kPi;

double A11(double x, double y) { return 2.0 + 0.5 * std::sin(kTwoPi * x) * std::cos(kTwoPi * y); }
double A12(double x, double y) { return 0.5 * std::cos(kTwoPi * (x + 2.0 * y)); }
double A22(double x, double y) { return 2.0 + 0.5 * std::sin(kTwoPi * (x - y) + 0.3); }
// lambda_min >= 1.5 - 0.5 = 1 > 0: SPD everywhere.

struct AdvectionRun {
  double error;
  double blended;
};

AdvectionRun AdvectOnGrid(int n, double courant, double end_time) {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(1.0, 1.0);
  p.domain.h = 1.0 / n;
  for (BoundarySide& s : p.domain.sides) s.type = SideType::kPeriodic;
  p.fluid.relaxation_time = 1.0;
  p.fluid.solvent_ratio = 0.5;
  p.conformation.max_courant = courant;
  const Grid grid{n, n, 1.0 / n, 0.0, 0.0};
  ConformationStep step(p, grid);

  const std::size_t count = grid.NodeCount();
  std::vector<double> u(count, 1.0), v(count, 1.0), a11(count), a12(count), a22(count);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const std::size_t k = grid.Index(i, j);
      a11[k] = A11(grid.X(i), grid.Y(j));
      a12[k] = A12(grid.X(i), grid.Y(j));
      a22[k] = A22(grid.X(i), grid.Y(j));
    }
  }
  // (|u| + |v|) dt / h = courant exactly, so one sub-step per step.
  const int steps = static_cast<int>(std::lround(end_time * 2.0 * n / courant));
  const double dt = end_time / steps;
  StepReport report;
  double blended = 0.0;
  for (int s = 0; s < steps; ++s) {
    step.Advance(s * dt, dt, u.data(), v.data(), nullptr, a11.data(), a12.data(), a22.data(),
                 report);
    blended += report.Get("blended_nodes");
    EXPECT_EQ(report.Get("conformation_substeps"), 1.0);
  }
  const double decay = std::exp(-end_time);
  double error = 0.0;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const std::size_t k = grid.Index(i, j);
      const double x = grid.X(i) - end_time, y = grid.Y(j) - end_time;
      error = std::max({error, std::abs(a11[k] - (1.0 + (A11(x, y) - 1.0) * decay)),
                        std::abs(a12[k] - A12(x, y) * decay),
                        std::abs(a22[k] - (1.0 + (A22(x, y) - 1.0) * decay))});
    }
  }
  return AdvectionRun{error, blended};
}

TEST(ConformationAdvection, ThirdOrderOnASmoothPeriodicField) {
  const double courant = 0.4, end_time = 0.5;
  std::printf("   N   max error   order   blended nodes\n");
  double previous = 0.0;
  std::vector<double> orders;
  for (int n : {16, 32, 64, 128}) {
    const AdvectionRun run = AdvectOnGrid(n, courant, end_time);
    if (previous > 0.0) {
      orders.push_back(std::log2(previous / run.error));
      std::printf("%4d   %.3e   %.2f    %.0f\n", n, run.error, orders.back(), run.blended);
    } else {
      std::printf("%4d   %.3e    --     %.0f\n", n, run.error, run.blended);
    }
    // A smooth field far from the SPD boundary: the blend must never act.
    EXPECT_EQ(run.blended, 0.0) << "n = " << n;
    previous = run.error;
  }
  // Expected order 3 (third order in space and time at fixed Courant number). The band allows the
  // pre-asymptotic coarse pair (16 -> 32); the finest pair must be within 0.2 of 3.
  for (double order : orders) EXPECT_GT(order, 2.6);
  EXPECT_NEAR(orders.back(), 3.0, 0.2);
}

}  // namespace
}  // namespace dlmfd
