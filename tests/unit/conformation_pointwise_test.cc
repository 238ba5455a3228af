// The pointwise part of step (35): the closed-form exp(sL), the exponential integrator, and the
// steady Oldroyd-B states (pointwise_update.h, inflow_state.h).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dlmfd/conformation/inflow_state.h"
#include "dlmfd/conformation/pointwise_update.h"
#include "dlmfd/conformation/sym_tensor.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

// exp(M) by its Taylor series in long double (60 terms: truncation < 3^60/60! ~ 1e-53 for |M| <=
// 3).
Mat2 TaylorExponential(const Mat2& l, double s) {
  long double e[2][2] = {{1, 0}, {0, 1}}, term[2][2] = {{1, 0}, {0, 1}};
  const long double m[2][2] = {{l.m11 * s, l.m12 * s}, {l.m21 * s, l.m22 * s}};
  for (int n = 1; n < 60; ++n) {
    long double next[2][2];
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) next[r][c] = (term[r][0] * m[0][c] + term[r][1] * m[1][c]) / n;
    }
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) {
        term[r][c] = next[r][c];
        e[r][c] += next[r][c];
      }
    }
  }
  return Mat2{double(e[0][0]), double(e[0][1]), double(e[1][0]), double(e[1][1])};
}

// The ODE right side L A + A L^T - (A - I)/lambda.
SymTensor Rate(const SymTensor& a, const Mat2& l, double lambda) {
  return SymTensor{2.0 * (l.m11 * a.a11 + l.m12 * a.a12) - (a.a11 - 1.0) / lambda,
                   l.m11 * a.a12 + l.m12 * a.a22 + a.a11 * l.m21 + a.a12 * l.m22 - a.a12 / lambda,
                   2.0 * (l.m21 * a.a12 + l.m22 * a.a22) - (a.a22 - 1.0) / lambda};
}

SymTensor Axpy(const SymTensor& a, double s, const SymTensor& b) {
  return SymTensor{a.a11 + s * b.a11, a.a12 + s * b.a12, a.a22 + s * b.a22};
}

// Classical RK4 with n steps: error ~ (dt rate / n)^4, below 1e-14 relative for n = 4000 here.
SymTensor IntegrateRk4(SymTensor a, const Mat2& l, double dt, double lambda, int n) {
  const double k = dt / n;
  for (int step = 0; step < n; ++step) {
    const SymTensor k1 = Rate(a, l, lambda);
    const SymTensor k2 = Rate(Axpy(a, 0.5 * k, k1), l, lambda);
    const SymTensor k3 = Rate(Axpy(a, 0.5 * k, k2), l, lambda);
    const SymTensor k4 = Rate(Axpy(a, k, k3), l, lambda);
    a = SymTensor{a.a11 + k / 6 * (k1.a11 + 2 * k2.a11 + 2 * k3.a11 + k4.a11),
                  a.a12 + k / 6 * (k1.a12 + 2 * k2.a12 + 2 * k3.a12 + k4.a12),
                  a.a22 + k / 6 * (k1.a22 + 2 * k2.a22 + 2 * k3.a22 + k4.a22)};
  }
  return a;
}

double MaxDiff(const SymTensor& a, const SymTensor& b) {
  return std::max({std::abs(a.a11 - b.a11), std::abs(a.a12 - b.a12), std::abs(a.a22 - b.a22)});
}

Mat2 RotatedExtension(double rate, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  // R diag(rate, -rate) R^T
  return Mat2{rate * (c * c - s * s), 2.0 * rate * c * s, 2.0 * rate * c * s,
              rate * (s * s - c * c)};
}

const std::vector<Mat2> kGradients = {
    Mat2{0.0, 1.0, 0.0, 0.0},       // simple shear (q = 0)
    Mat2{0.7, 0.0, 0.0, -0.7},      // planar extension (q^2 > 0)
    Mat2{0.0, -1.3, 1.3, 0.0},      // rotation (q^2 < 0)
    Mat2{0.3, 0.9, -0.2, -0.1},     // general, with a trace
    Mat2{0.04, 0.02, 0.03, -0.05},  // x = q^2 s^2 just below the series switch 1e-2
    Mat2{0.06, 0.03, 0.03, -0.05},  // just above it
    RotatedExtension(1.5, kPi / 6.0),
};

TEST(MatrixExponential, EqualsTaylorSeriesToRoundOff) {
  for (const Mat2& l : kGradients) {
    for (double s : {1e-6, 0.01, 0.5, 1.0, 2.0}) {
      const Mat2 f = MatrixExponential(l, s), t = TaylorExponential(l, s);
      const double scale =
          std::max({std::abs(t.m11), std::abs(t.m12), std::abs(t.m21), std::abs(t.m22)});
      // Round-off: a few ulps of the cosh/sinh evaluation times the norm of F.
      EXPECT_NEAR(f.m11, t.m11, 1e-14 * scale) << "s = " << s;
      EXPECT_NEAR(f.m12, t.m12, 1e-14 * scale) << "s = " << s;
      EXPECT_NEAR(f.m21, t.m21, 1e-14 * scale) << "s = " << s;
      EXPECT_NEAR(f.m22, t.m22, 1e-14 * scale) << "s = " << s;
    }
  }
}

TEST(StretchAndRelax, MatchesFineRungeKutta) {
  const SymTensor a0{3.0, 1.0, 2.0};
  const double lambda = 0.8;
  for (const Mat2& l : kGradients) {
    for (double dt : {0.01, 0.1, 0.5}) {
      const SymTensor exact = IntegrateRk4(a0, l, dt, lambda, 4000);
      const SymTensor got = StretchAndRelax(a0, l, dt, lambda);
      // Composite 3-point Gauss with panel rate <= 0.125: relative error of the integral term
      // ~ 0.125^6 / 2016000 ~ 2e-12 (header analysis), times the polynomial factors seen on steady
      // shear (x10); RK4 with 4000 steps is exact to 1e-14 here.
      EXPECT_LT(MaxDiff(got, exact), 2e-11 * (1.0 + Trace(exact))) << "dt = " << dt;
    }
  }
}

TEST(ExponentialIntegrator, EqualsTheGeneralRuleToRoundOff) {
  // The one-panel fast path (semigroup products) and the general rule are the same quadrature.
  const SymTensor a0{3.0, 1.0, 2.0};
  const double lambda = 0.8;
  for (const Mat2& l : kGradients) {
    for (double dt : {1e-4, 0.01, 0.05, 0.5}) {
      const ExponentialIntegrator integrator(dt, lambda);
      const SymTensor fast = integrator.Apply(a0, l), general = StretchAndRelax(a0, l, dt, lambda);
      EXPECT_LT(MaxDiff(fast, general), 1e-14 * Trace(general)) << "dt = " << dt;
    }
  }
}

TEST(OnePanelRow, EqualsTheGeneralRuleWhereItApplies) {
  // The vectorised row kernel of ConformationStep against StretchAndRelax, node by node.
  const double lambda = 0.8;
  for (double dt : {1e-4, 4e-3, 0.02, 0.09}) {
    const ExponentialIntegrator integrator(dt, lambda);
    const OnePanelConstants constants = integrator.Constants();
    std::vector<double> a11, a12, a22, l11, l12, l21, l22;
    for (const Mat2& l : kGradients) {
      for (double scale : {0.0, 0.1, 1.0, 5.0}) {
        a11.push_back(3.0 + scale);
        a12.push_back(1.0 - 0.1 * scale);
        a22.push_back(2.0);
        l11.push_back(scale * l.m11);
        l12.push_back(scale * l.m12);
        l21.push_back(scale * l.m21);
        l22.push_back(scale * l.m22);
      }
    }
    const int count = static_cast<int>(a11.size());
    std::vector<double> o11(count), o12(count), o22(count);
    OnePanelRow(count, constants, a11.data(), a12.data(), a22.data(), l11.data(), l12.data(),
                l21.data(), l22.data(), o11.data(), o12.data(), o22.data());
    int applied = 0;
    for (int i = 0; i < count; ++i) {
      const Mat2 l{l11[i], l12[i], l21[i], l22[i]};
      if (!OnePanelApplies(constants, l)) continue;
      ++applied;
      const SymTensor general = StretchAndRelax(SymTensor{a11[i], a12[i], a22[i]}, l, dt, lambda);
      EXPECT_LT(MaxDiff(SymTensor{o11[i], o12[i], o22[i]}, general), 1e-14 * Trace(general))
          << "dt " << dt;
    }
    EXPECT_GT(applied, 0);
  }
}

TEST(StretchAndRelax, HomogeneousRelaxationIsExactToRoundOff) {
  // L = 0: A(t) = I + (A0 - I) e^{-t/lambda}; the rescaled weights make this exact (no quadrature
  // error), so after 37 steps only round-off remains (about steps * ulp).
  const double lambda = 0.7;
  for (double dt : {0.001, 0.05, 0.3, 2.0}) {
    SymTensor a{3.0, 1.0, 2.0};
    for (int n = 0; n < 37; ++n) a = StretchAndRelax(a, Mat2{}, dt, lambda);
    const double decay = std::exp(-37 * dt / lambda);
    const SymTensor exact{1.0 + 2.0 * decay, decay, 1.0 + decay};
    EXPECT_LT(MaxDiff(a, exact), 37 * 4e-16 * 3.0) << "dt = " << dt;
  }
}

TEST(StretchAndRelax, StaysPositiveDefiniteForAnyStep) {
  // SPD holds in exact arithmetic for any dt. In double precision a tensor with condition number
  // near 1/eps cannot be told from a singular one, so the test stays below cond(A(dt)) ~ 1e12:
  // cond(F A F^T) <= cond(F)^2 cond(A) <= e^{4 q dt} 2e3 <= 1e12 for q dt <= 5.
  const SymTensor nearly_singular{1.0, 0.999, 1.0};  // lambda_min = 1e-3, cond 2e3
  const double lambda = 1.0;
  for (const Mat2& l : kGradients) {
    const double q = std::sqrt(std::abs(std::pow(0.5 * (l.m11 - l.m22), 2) + l.m12 * l.m21));
    for (double scale : {1.0, 10.0, 50.0}) {
      const Mat2 strong{scale * l.m11, scale * l.m12, scale * l.m21, scale * l.m22};
      for (double dt : {1e-3, 0.1, 1.0, 5.0}) {
        if (scale * q * dt > 5.0 || scale * std::abs(l.m11 + l.m22) * dt > 5.0) continue;
        const SymTensor a = StretchAndRelax(nearly_singular, strong, dt, lambda);
        ASSERT_TRUE(IsFinite(a));
        EXPECT_GT(MinEigenvalue(a), 0.0) << "scale " << scale << " dt " << dt;
      }
    }
  }
}

TEST(StretchAndRelax, SteadyShearIsAFixedPointUpToQuadrature) {
  // The exact map has the steady shear state as a fixed point; ours only up to the quadrature error
  // of the integral term, O(w^7) per step for a panel of width w (3-point Gauss), accumulated over
  // ~lambda/dt steps: O(w^6) for one panel per step (dt <= 0.125 lambda). Measured with this test:
  // relative errors 2.2e-10, 3.4e-12, 5.6e-14 (lambda g = 0.5) and 1.1e-9, 1.7e-11, 2.6e-13
  // (lambda g = 10) at dt/lambda = 0.25, 0.125, 0.0625: a factor 64 per halving (order 6).
  // Asserted: at least 32 per halving, and below 5e-11 at the panel limit dt = 0.125 lambda.
  for (double wi : {0.5, 2.0, 10.0}) {
    const double lambda = 1.0, g = wi / lambda;
    const SymTensor exact = SimpleShearConformation(lambda, g);
    double previous = 0.0;
    for (double dt : {0.125, 0.0625, 0.03125}) {
      SymTensor a{};
      for (int n = 0; n < static_cast<int>(60.0 / dt); ++n)
        a = StretchAndRelax(a, Mat2{0, g, 0, 0}, dt, lambda);
      const double error = MaxDiff(a, exact) / Trace(exact);
      std::printf("lambda g = %5.1f  dt/lambda = %6.4f  relative error %.3e\n", wi, dt, error);
      EXPECT_LT(error, 5e-11);
      if (previous > 1e-12) {  // above the round-off floor (~1e-14)
        EXPECT_LT(error, previous / 32.0);
      }
      previous = error;
    }
  }
}

// lambda << dt (a sweep of lambda towards 0 at a fixed dt): one step forgets A^n (e^{-dt/lambda})
// and must land on the steady state of the frozen L, A - I = lambda (L + L^T) + 2 lambda^2 L L^T in
// shear, the lambda -> 0 limit that fluid.stress_splitting = devss relies on. Before the integral
// stopped at its decay (IntegralEnd), the 256 panels spread over dt were up to 40 lambda wide, and
// the error relative to lambda g was 5.8e-3 / 3.4 / 439 at dt / lambda = 1e3 / 1e4 / 1e6. With the
// tail cut at 50 e-foldings the 256 panels are 0.2 lambda wide, and the error is the quadrature's:
// measured 1.6e-10 / 1.6e-10 / 1.1e-9 / 1.6e-10 at dt / lambda = 50 / 1e3 / 1e4 / 1e6. Asserted:
// 1e-8 relative to lambda g, from a start far from the steady state.
TEST(StretchAndRelax, RelaxationMuchFasterThanTheStepLandsOnTheSteadyState) {
  const double dt = 2e-3, g = 3.0;
  for (double ratio : {50.0, 1e3, 1e4, 1e6}) {
    const double lambda = dt / ratio;
    const SymTensor exact = SimpleShearConformation(lambda, g);
    const SymTensor a = StretchAndRelax(SymTensor{4.0, 1.0, 2.0}, Mat2{0, g, 0, 0}, dt, lambda);
    const double error = MaxDiff(a, exact) / (lambda * g);
    std::printf("dt / lambda = %.0e: |A - A_steady| / (lambda g) = %.3e\n", ratio, error);
    EXPECT_LT(error, 1e-8) << "dt / lambda = " << ratio;
  }
}

TEST(SteadyConformation, SimpleShearMatchesReference) {
  for (double wi : {0.0, 0.5, 1.0, 3.0, 10.0}) {
    const SymTensor a = SteadyConformation(Mat2{0.0, wi, 0.0, 0.0}, 1.0);
    const SymTensor r = SimpleShearConformation(1.0, wi);
    EXPECT_NEAR(a.a11, 1.0 + 2.0 * wi * wi, 1e-13 * a.a11);
    EXPECT_NEAR(a.a12, wi, 1e-13 * a.a11);
    EXPECT_NEAR(a.a22, 1.0, 1e-13 * a.a11);
    EXPECT_LT(MaxDiff(a, r), 1e-13 * a.a11);
  }
}

TEST(SteadyConformation, SolvesTheSteadyEquationAndRejectsStrongExtension) {
  const double lambda = 1.0;
  for (const Mat2& l :
       {Mat2{0.2, 0.5, -0.1, -0.2}, RotatedExtension(0.3, 0.4), Mat2{0, -2, 2, 0}}) {
    const SymTensor a = SteadyConformation(l, lambda);
    const SymTensor r = Rate(a, l, lambda);
    EXPECT_LT(std::max({std::abs(r.a11), std::abs(r.a12), std::abs(r.a22)}), 1e-13 * Trace(a));
    EXPECT_GT(MinEigenvalue(a), 0.0);
  }
  // 2 lambda e >= 1: no steady state.
  EXPECT_THROW(SteadyConformation(RotatedExtension(0.6, 0.4), lambda), InvalidParameter);
}

TEST(InflowConformation, PoiseuilleSideIsTheFullyDevelopedChannelState) {
  Grid grid{8, 16, 0.125, 0.0, 0.0};  // 1 x 2
  DomainParams domain;
  domain.size = Vec2(1.0, 2.0);
  domain.h = 0.125;
  domain.sides[static_cast<int>(Side::kBottom)] =
      BoundarySide{SideType::kVelocity, Profile::kPoiseuille, Vec2::Zero(), Vec2(0.0, 0.5)};
  domain.sides[static_cast<int>(Side::kLeft)] =
      BoundarySide{SideType::kVelocity, Profile::kUniform, Vec2(1.0, 0.0), Vec2::Zero()};
  const double lambda = 1.4;
  for (int k = 0; k <= grid.nx; ++k) {
    // v(x) = 0.5 * 4 x (1 - x): shear rate dv/dx = 2 (1 - 2x); the channel state has the flow along
    // y.
    const double x = k * grid.h, g = 2.0 * (1.0 - 2.0 * x);
    const SymTensor a = InflowConformation(grid, domain, Side::kBottom, k, lambda);
    const double wi = lambda * g;
    EXPECT_NEAR(a.a11, 1.0, 1e-13);
    EXPECT_NEAR(a.a12, wi, 1e-13);
    EXPECT_NEAR(a.a22, 1.0 + 2.0 * wi * wi, 1e-12);
  }
  const SymTensor uniform = InflowConformation(grid, domain, Side::kLeft, 3, lambda);
  EXPECT_EQ(uniform.a11, 1.0);
  EXPECT_EQ(uniform.a12, 0.0);
  EXPECT_EQ(uniform.a22, 1.0);
}

TEST(MinEigenvalue, KeepsRelativeAccuracyForLargeStretch) {
  // A = R diag(1e5, 1e-3) R^T: the textbook formula loses all digits of the small eigenvalue.
  const double c = std::cos(0.3), s = std::sin(0.3), big = 1e5, small = 1e-3;
  const SymTensor a{big * c * c + small * s * s, (big - small) * c * s,
                    big * s * s + small * c * c};
  EXPECT_NEAR(MinEigenvalue(a), small, 1e-9 * small * 1e3);
  EXPECT_LT(MinEigenvalue(SymTensor{1.0, 2.0, 1.0}), 0.0);
}

}  // namespace
}  // namespace dlmfd
