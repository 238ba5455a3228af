// Positive definiteness in a strong planar extensional flow (method notes 2, section 2.3): the
// stagnation-point flow u = e R diag(1, -1) R^T x, R a rotation by 30 degrees (so the outgoing axis
// is not a grid line), on [-1, 1]^2, h = 1/48, A = I on the inflow parts of the boundary, A0 = I,
// lambda = 1, lambda e = 2 (> 1/2: A grows without bound near the outgoing axis), e dt = 0.006, t
// <= 3.
//
// Construction A (ConformationStep) must keep A SPD at every step; a naive scheme (the same
// third-order upwind-biased advection without the SPD blend, and explicit stretching and
// relaxation, all in one SSP-RK3, written out below as the comparison) must lose positive
// definiteness on the same problem. The prototype of the notes saw the naive scheme fail at t
// = 2.37 with lambda_min ~ -6e4, a spatial failure near the outgoing axis that a smaller dt does
// not cure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/conformation/conformation_step.h"
#include "dlmfd/conformation/sym_tensor.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

constexpr int kExtensionCells = 96;  // h = 1/48 on [-1, 1]
constexpr double kLambda = 1.0;
constexpr double kRate = 2.0;     // lambda e = 2
constexpr double kDt = 0.003;     // e dt = 0.006
constexpr double kEndTime = 3.0;  // past the naive scheme's failure (t = 2.37 in the notes)

struct Flow {
  Grid grid{kExtensionCells, kExtensionCells, 2.0 / kExtensionCells, -1.0, -1.0};
  Mat2 l;  // the uniform velocity gradient
  std::vector<double> u, v;
  Flow() {
    const double c = std::cos(kPi / 6.0), s = std::sin(kPi / 6.0);
    l = Mat2{kRate * (c * c - s * s), 2.0 * kRate * c * s, 2.0 * kRate * c * s,
             kRate * (s * s - c * c)};
    u.resize(grid.NodeCount());
    v.resize(grid.NodeCount());
    for (int j = 0; j <= kExtensionCells; ++j) {
      for (int i = 0; i <= kExtensionCells; ++i) {
        const double x = grid.X(i), y = grid.Y(j);
        u[grid.Index(i, j)] = l.m11 * x + l.m12 * y;
        v[grid.Index(i, j)] = l.m21 * x + l.m22 * y;
      }
    }
  }
};

// The naive comparison scheme: dA/dt = -u . grad A + L A + A L^T - (A - I)/lambda, one SSP-RK3 step
// per dt, third-order upwind-biased differences, ghosts by constant extrapolation, A = I where
// u . n < 0 on the boundary. Returns the smallest lambda_min seen and the first time it was <= 0.
struct NaiveResult {
  double min_eig = 1e300;
  double failure_time = -1.0;
};

NaiveResult RunNaive(const Flow& flow) {
  const Grid& g = flow.grid;
  const int n = kExtensionCells, pad = n + 5;
  auto P = [&](int i, int j) { return std::size_t(j + 2) * pad + std::size_t(i + 2); };
  std::vector<double> a[3], s1[3], s2[3];
  for (int c = 0; c < 3; ++c) {
    a[c].assign(std::size_t(pad) * pad, c == 1 ? 0.0 : 1.0);
    s1[c] = a[c];
    s2[c] = a[c];
  }
  auto boundary_fix = [&](std::vector<double>* f) {
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        if (i != 0 && i != n && j != 0 && j != n) continue;
        const double nx = i == 0 ? -1.0 : (i == n ? 1.0 : 0.0),
                     ny = j == 0 ? -1.0 : (j == n ? 1.0 : 0.0);
        const std::size_t k = g.Index(i, j);
        if (flow.u[k] * nx + flow.v[k] * ny < 0.0) {
          f[0][P(i, j)] = 1.0;
          f[1][P(i, j)] = 0.0;
          f[2][P(i, j)] = 1.0;
        }
      }
    }
    for (int c = 0; c < 3; ++c) {
      for (int j = 0; j <= n; ++j) {
        f[c][P(-1, j)] = f[c][P(-2, j)] = f[c][P(0, j)];
        f[c][P(n + 1, j)] = f[c][P(n + 2, j)] = f[c][P(n, j)];
      }
      for (int i = -2; i <= n + 2; ++i) {
        f[c][P(i, -1)] = f[c][P(i, -2)] = f[c][P(i, 0)];
        f[c][P(i, n + 1)] = f[c][P(i, n + 2)] = f[c][P(i, n)];
      }
    }
  };
  const Mat2& l = flow.l;
  const double c6 = 1.0 / (6.0 * g.h);
  // out = wb * base + wi * (in + dt R(in))
  auto stage = [&](double wb, std::vector<double>* base, double wi, std::vector<double>* in,
                   std::vector<double>* out) {
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const std::size_t k = g.Index(i, j), p = P(i, j);
        const double uk = flow.u[k], vk = flow.v[k];
        double adv[3];
        for (int c = 0; c < 3; ++c) {
          const double* q = in[c].data() + p;
          const std::ptrdiff_t sy = pad;
          const double dx = uk >= 0 ? q[-2] - 6 * q[-1] + 3 * q[0] + 2 * q[1]
                                    : -2 * q[-1] - 3 * q[0] + 6 * q[1] - q[2];
          const double dy = vk >= 0 ? q[-2 * sy] - 6 * q[-sy] + 3 * q[0] + 2 * q[sy]
                                    : -2 * q[-sy] - 3 * q[0] + 6 * q[sy] - q[2 * sy];
          adv[c] = -c6 * (uk * dx + vk * dy);
        }
        const double a11 = in[0][p], a12 = in[1][p], a22 = in[2][p];
        const double r11 = adv[0] + 2.0 * (l.m11 * a11 + l.m12 * a12) - (a11 - 1.0) / kLambda;
        const double r12 =
            adv[1] + l.m11 * a12 + l.m12 * a22 + a11 * l.m21 + a12 * l.m22 - a12 / kLambda;
        const double r22 = adv[2] + 2.0 * (l.m21 * a12 + l.m22 * a22) - (a22 - 1.0) / kLambda;
        out[0][p] = wb * base[0][p] + wi * (a11 + kDt * r11);
        out[1][p] = wb * base[1][p] + wi * (a12 + kDt * r12);
        out[2][p] = wb * base[2][p] + wi * (a22 + kDt * r22);
      }
    }
    boundary_fix(out);
  };
  NaiveResult result;
  const int steps = static_cast<int>(std::lround(kEndTime / kDt));
  for (int s = 1; s <= steps; ++s) {
    stage(0.0, a, 1.0, a, s1);
    stage(0.75, a, 0.25, s1, s2);
    stage(1.0 / 3.0, a, 2.0 / 3.0, s2, a);  // reads a[p] before writing it: pointwise safe
    double lo = 1e300;
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const SymTensor t{a[0][P(i, j)], a[1][P(i, j)], a[2][P(i, j)]};
        lo = IsFinite(t) ? std::min(lo, MinEigenvalue(t)) : -1e300;
      }
    }
    result.min_eig = std::min(result.min_eig, lo);
    if (!(lo > 0.0)) {
      result.failure_time = s * kDt;
      break;
    }
  }
  return result;
}

Params ExtensionParams() {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(2.0, 2.0);
  p.domain.h = 2.0 / kExtensionCells;
  for (BoundarySide& s : p.domain.sides) {
    s.type = SideType::kVelocity;  // uniform profile: A_L = I where the flow enters
    s.profile = Profile::kUniform;
  }
  p.fluid.relaxation_time = kLambda;
  p.fluid.solvent_ratio = 0.5;
  return p;
}

TEST(ConformationExtension, ConstructionAStaysPositiveDefiniteWhereTheNaiveSchemeFails) {
  const Flow flow;
  const Params params = ExtensionParams();
  ConformationStep step(params, flow.grid);
  const std::size_t count = flow.grid.NodeCount();
  std::vector<double> a11(count, 1.0), a12(count, 0.0), a22(count, 1.0);
  StepReport report;
  double min_eig = 1e300, max_trace = 0.0, blended = 0.0;
  const int steps = static_cast<int>(std::lround(kEndTime / kDt));
  for (int s = 0; s < steps; ++s) {
    // Throws ConformationNotPositiveDefinite if A ever loses positive definiteness.
    step.Advance(s * kDt, kDt, flow.u.data(), flow.v.data(), nullptr, a11.data(), a12.data(),
                 a22.data(), report);
    min_eig = std::min(min_eig, report.Get("min_eig_A"));
    max_trace = std::max(max_trace, report.Get("max_trA"));
    blended += report.Get("blended_nodes");
  }
  std::printf(
      "construction A: min lambda_min %.3e, max trA %.3e, blended node updates %.0f, elastic "
      "Courant %.4f\n",
      min_eig, max_trace, blended, report.Get("elastic_courant"));
  EXPECT_GT(min_eig, 0.0);

  const NaiveResult naive = RunNaive(flow);
  std::printf("naive scheme: min lambda_min %.3e, lost positive definiteness at t = %.3f\n",
              naive.min_eig, naive.failure_time);
  EXPECT_LE(naive.min_eig, 0.0);
  EXPECT_GT(naive.failure_time, 0.0);
}

TEST(ConformationExtension, WithoutTheBlendTheExactPointwiseUpdateAloneDoesNotSaveA) {
  // The comparison option of ConformationStep: the same step without the SPD blend. The pointwise
  // update is still exact and SPD-preserving, so a failure here comes from the unlimited advection.
  const Flow flow;
  ConformationStep step(ExtensionParams(), flow.grid);
  step.DisableBlendForComparison();
  const std::size_t count = flow.grid.NodeCount();
  std::vector<double> a11(count, 1.0), a12(count, 0.0), a22(count, 1.0);
  StepReport report;
  const int steps = static_cast<int>(std::lround(kEndTime / kDt));
  bool lost_positive_definiteness = false;
  try {
    for (int s = 0; s < steps; ++s) {
      step.Advance(s * kDt, kDt, flow.u.data(), flow.v.data(), nullptr, a11.data(), a12.data(),
                   a22.data(), report);
    }
  } catch (const ConformationNotPositiveDefinite& e) {
    std::printf("blend disabled: %s\n", e.what());
    lost_positive_definiteness = true;
  }
  EXPECT_TRUE(lost_positive_definiteness);
}

}  // namespace
}  // namespace dlmfd
