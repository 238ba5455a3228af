// The relaxation models of fluid.model (relaxation_model.h) in homogeneous flows, against closed
// forms: steady simple shear (viscosity and first normal stress difference against the shear rate,
// Bird, Armstrong & Hassager 1987 vol. 1 4.3 for Giesekus; the planar FENE-P and PTT forms reduce
// to a cubic or to Lambert's W, solved here independently of the code), start-up of shear
// (Oldroyd-B closed form), steady planar extension below and above lambda * rate = 1/2 (unbounded
// for Oldroyd-B, bounded for Giesekus and FENE-P), and the observed order in dt of the model step.
// Units: lambda = 1, G = 1, so Wi = lambda * rate and eta_p(rate)/eta_p0 = T12 / Wi.
// Tolerances: the model step's only error at a steady state is the Gauss quadrature of its frozen
// update (relative 2e-12 a panel at the panel limit, model_pointwise_update.h), hence 1e-10.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "dlmfd/conformation/fene_p_relaxation.h"
#include "dlmfd/conformation/giesekus_relaxation.h"
#include "dlmfd/conformation/inflow_state.h"
#include "dlmfd/conformation/model_pointwise_update.h"
#include "dlmfd/conformation/oldroyd_b_relaxation.h"
#include "dlmfd/conformation/pointwise_update.h"
#include "dlmfd/conformation/ptt_relaxation.h"
#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

constexpr double kSteadyTolerance = 1e-10;

Mat2 Shear(double rate) { return Mat2{0.0, rate, 0.0, 0.0}; }
Mat2 Extension(double rate) { return Mat2{rate, 0.0, 0.0, -rate}; }

// Viscosity ratio and N1 / G of a steady state in shear at Wi.
struct ShearFunctions {
  double viscosity_ratio, n1;
};

ShearFunctions OfState(const RelaxationModel& m, const SymTensor& a, double wi) {
  const SymTensor t = m.Stress(a);
  return ShearFunctions{t.a12 / wi, t.a11 - t.a22};
}

// The real root of y^3 + p y + q = 0 when (q/2)^2 + (p/3)^3 >= 0 (Cardano).
double CardanoRoot(double p, double q) {
  const double disc = std::sqrt(0.25 * q * q + p * p * p / 27.0);
  return std::cbrt(-0.5 * q + disc) + std::cbrt(-0.5 * q - disc);
}

// Bird, Armstrong & Hassager (1987), vol. 1, Table 4.3-2 (Giesekus steady shear).
ShearFunctions GiesekusShear(double alpha, double wi) {
  const double chi2 = (std::sqrt(1.0 + 16.0 * alpha * (1.0 - alpha) * wi * wi) - 1.0) /
                      (8.0 * alpha * (1.0 - alpha) * wi * wi);
  const double chi = std::sqrt(chi2);
  const double f = (1.0 - chi) / (1.0 + (1.0 - 2.0 * alpha) * chi);
  return ShearFunctions{(1.0 - f) * (1.0 - f) / (1.0 + (1.0 - 2.0 * alpha) * f),
                        2.0 * f * (1.0 - alpha * f) / (alpha * (1.0 - f))};
}

// Planar FENE-P: A22 = a/f, A12 = Wi a/f^2, A11 = a/f + 2 Wi^2 a/f^3, tr A = L^2 (1 - 1/f), so
// f^3 - a f^2 - 2 a Wi^2 / L^2 = 0; eta/eta_0 = a/f, N1/G = 2 Wi^2 a / f^2.
ShearFunctions FenePShear(double l2, double wi) {
  const double a = 1.0 / (1.0 - 2.0 / l2);
  const double c = 2.0 * a * wi * wi / l2;
  const double f = a / 3.0 + CardanoRoot(-a * a / 3.0, -2.0 * a * a * a / 27.0 - c);
  return ShearFunctions{a / f, 2.0 * wi * wi * a / (f * f)};
}

// PTT: A22 = 1, A12 = Wi/Y, A11 - 1 = 2 Wi^2/Y^2; linear Y^3 - Y^2 - 2 eps Wi^2 = 0, exponential
// Y = exp(W(4 eps Wi^2)/2). eta/eta_0 = 1/Y, N1/G = 2 Wi^2/Y^2.
ShearFunctions PttShear(double eps, double wi, bool exponential) {
  double y;
  if (exponential) {
    const double z = 4.0 * eps * wi * wi;
    double w = std::log1p(z);  // Lambert W by Newton from log(1 + z)
    for (int k = 0; k < 50; ++k) w -= (w * std::exp(w) - z) / (std::exp(w) * (1.0 + w));
    y = std::exp(0.5 * w);
  } else {
    y = 1.0 / 3.0 + CardanoRoot(-1.0 / 3.0, -2.0 / 27.0 - 2.0 * eps * wi * wi);
  }
  return ShearFunctions{1.0 / y, 2.0 * wi * wi / (y * y)};
}

struct ModelCase {
  const char* name;
  std::function<std::unique_ptr<RelaxationModel>()> make;
  std::function<ShearFunctions(double)> shear;
};

std::vector<ModelCase> Models() {
  std::vector<ModelCase> cases;
  for (double alpha : {0.1, 0.3, 0.5}) {
    cases.push_back({"giesekus", [alpha] { return std::make_unique<GiesekusRelaxation>(alpha); },
                     [alpha](double wi) { return GiesekusShear(alpha, wi); }});
  }
  for (double l2 : {10.0, 100.0}) {
    cases.push_back({"fene_p", [l2] { return std::make_unique<FenePRelaxation>(l2); },
                     [l2](double wi) { return FenePShear(l2, wi); }});
  }
  for (double eps : {0.05, 0.25}) {
    cases.push_back({"ptt_linear", [eps] { return std::make_unique<PttRelaxation>(eps, false); },
                     [eps](double wi) { return PttShear(eps, wi, false); }});
    cases.push_back({"ptt_exponential",
                     [eps] { return std::make_unique<PttRelaxation>(eps, true); },
                     [eps](double wi) { return PttShear(eps, wi, true); }});
  }
  return cases;
}

TEST(ConformationModels, SteadyShearMatchesTheClosedFormsAndThins) {
  for (const ModelCase& c : Models()) {
    const std::unique_ptr<RelaxationModel> m = c.make();
    double last_viscosity = 1.0;
    for (double wi : {0.1, 0.5, 1.0, 2.0, 5.0, 10.0, 30.0}) {
      SCOPED_TRACE(std::string(c.name) + " at Wi = " + std::to_string(wi));
      const ShearFunctions want = c.shear(wi);
      const ShearFunctions got = OfState(*m, SteadyModelConformation(*m, Shear(wi), 1.0), wi);
      EXPECT_NEAR(got.viscosity_ratio, want.viscosity_ratio,
                  kSteadyTolerance * want.viscosity_ratio);
      EXPECT_NEAR(got.n1, want.n1, kSteadyTolerance * want.n1);
      // Shear thinning: the viscosity falls with the rate, below the Oldroyd-B value 1.
      EXPECT_LT(got.viscosity_ratio, last_viscosity);
      last_viscosity = got.viscosity_ratio;
      // Oldroyd-B's N1/G = 2 Wi^2 bounds them all from above.
      EXPECT_LT(got.n1, 2.0 * wi * wi);
    }
  }
}

TEST(ConformationModels, SteadyShearIsTheLimitOfTheTimeSteppedModel) {
  // From rest, 400 steps of dt = 0.1 lambda: the fixed point of the step is the steady state.
  for (const ModelCase& c : Models()) {
    const std::unique_ptr<RelaxationModel> m = c.make();
    const double wi = 3.0;
    SymTensor a{};
    for (int n = 0; n < 400; ++n) ASSERT_TRUE(ModelPointwiseStep(*m, a, Shear(wi), 0.1, 1.0, &a));
    const ShearFunctions want = c.shear(wi), got = OfState(*m, a, wi);
    EXPECT_NEAR(got.viscosity_ratio, want.viscosity_ratio, kSteadyTolerance) << c.name;
    EXPECT_NEAR(got.n1, want.n1, kSteadyTolerance * want.n1) << c.name;
  }
}

TEST(ConformationModels, ParametersAtZeroAreOldroydB) {
  // alpha = 0 and epsilon = 0 are Oldroyd-B: A11 = 1 + 2 Wi^2, A12 = Wi, A22 = 1.
  const GiesekusRelaxation giesekus(0.0);
  const PttRelaxation ptt(0.0, false);
  const OldroydBRelaxation oldroyd_b;
  for (const RelaxationModel* m :
       std::vector<const RelaxationModel*>{&giesekus, &ptt, &oldroyd_b}) {
    const SymTensor a = SteadyModelConformation(*m, Shear(4.0), 1.0);
    const SymTensor want = SimpleShearConformation(1.0, 4.0);
    EXPECT_NEAR(a.a11, want.a11, kSteadyTolerance * want.a11) << m->Name();
    EXPECT_NEAR(a.a12, want.a12, kSteadyTolerance * want.a12) << m->Name();
    EXPECT_NEAR(a.a22, want.a22, kSteadyTolerance) << m->Name();
  }
}

TEST(ConformationModels, OldroydBStartUpOfShearIsExactInBothIntegrators) {
  // A12 = Wi (1 - e^{-s}), A11 = 1 + 2 Wi^2 (1 - e^{-s} (1 + s)), s = t/lambda (Bird et al. 1987,
  // vol. 1, 7.3): exact for frozen L in the Oldroyd-B exponential integrator and the general
  // frozen update (N = I, c = 1 do not depend on A).
  const double wi = 5.0, lambda = 0.7, dt = 0.05;
  const Mat2 l = Shear(wi / lambda);
  const OldroydBRelaxation model;
  const ExponentialIntegrator integrator(dt, lambda);
  SymTensor a{}, b{};
  for (int n = 1; n <= 60; ++n) {
    a = integrator.Apply(a, l);
    ASSERT_TRUE(ModelPointwiseStep(model, b, l, dt, lambda, &b));
    const double s = n * dt / lambda;
    const double a12 = wi * (1.0 - std::exp(-s));
    const double a11 = 1.0 + 2.0 * wi * wi * (1.0 - std::exp(-s) * (1.0 + s));
    // The quadrature bound of the integrators (1e-11 relative, pointwise_update.h) and round-off.
    EXPECT_NEAR(a.a12, a12, 1e-11 * a11);
    EXPECT_NEAR(a.a11, a11, 1e-11 * a11);
    EXPECT_NEAR(b.a12, a12, 1e-11 * a11);
    EXPECT_NEAR(b.a11, a11, 1e-11 * a11);
    EXPECT_NEAR(b.a22, 1.0, 1e-13);
  }
}

// The model ODE dA/dt = L A + A L^T - R(A)/lambda by classical RK4 with a small step.
SymTensor ReferenceStartUp(const RelaxationModel& m, const Mat2& l, double t_end, int steps) {
  auto rhs = [&](const SymTensor& a) {
    const SymTensor r = m.Source(a);
    return SymTensor{2.0 * (l.m11 * a.a11 + l.m12 * a.a12) - r.a11,
                     l.m11 * a.a12 + l.m12 * a.a22 + a.a11 * l.m21 + a.a12 * l.m22 - r.a12,
                     2.0 * (l.m21 * a.a12 + l.m22 * a.a22) - r.a22};
  };
  auto axpy = [](const SymTensor& a, double s, const SymTensor& k) {
    return SymTensor{a.a11 + s * k.a11, a.a12 + s * k.a12, a.a22 + s * k.a22};
  };
  const double h = t_end / steps;
  SymTensor a{};
  for (int n = 0; n < steps; ++n) {
    const SymTensor k1 = rhs(a), k2 = rhs(axpy(a, 0.5 * h, k1)), k3 = rhs(axpy(a, 0.5 * h, k2)),
                    k4 = rhs(axpy(a, h, k3));
    a = SymTensor{a.a11 + h / 6.0 * (k1.a11 + 2.0 * k2.a11 + 2.0 * k3.a11 + k4.a11),
                  a.a12 + h / 6.0 * (k1.a12 + 2.0 * k2.a12 + 2.0 * k3.a12 + k4.a12),
                  a.a22 + h / 6.0 * (k1.a22 + 2.0 * k2.a22 + 2.0 * k3.a22 + k4.a22)};
  }
  return a;
}

TEST(ConformationModels, StartUpOfShearConvergesAtSecondOrderInDt) {
  // Start-up at Wi = 5 to t = 2 lambda (the stress overshoot), dt = lambda/10 ... lambda/80,
  // against RK4 with dt = lambda/20000 (error below 1e-12). The predictor-corrector's order is 2.
  for (const ModelCase& c : Models()) {
    const std::unique_ptr<RelaxationModel> m = c.make();
    const Mat2 l = Shear(5.0);
    const SymTensor ref = ReferenceStartUp(*m, l, 2.0, 40000);
    std::vector<double> errors;
    for (int steps : {20, 40, 80, 160}) {
      SymTensor a{};
      for (int n = 0; n < steps; ++n)
        ASSERT_TRUE(ModelPointwiseStep(*m, a, l, 2.0 / steps, 1.0, &a));
      errors.push_back(std::max(
          {std::abs(a.a11 - ref.a11), std::abs(a.a12 - ref.a12), std::abs(a.a22 - ref.a22)}));
    }
    // Measured orders, dt = 2/40 -> 2/80 -> 2/160 (9 models): 1.93 to 2.16, then 1.90 to 2.08
    // (2.30 at most for the first halving, still pre-asymptotic); asked: the last two in
    // [1.8, 2.2].
    for (std::size_t k = 2; k < errors.size(); ++k) {
      const double order = std::log2(errors[k - 1] / errors[k]);
      EXPECT_GT(order, 1.8) << c.name << " dt = 2/" << (20 << k);
      EXPECT_LT(order, 2.2) << c.name << " dt = 2/" << (20 << k);
    }
  }
}

TEST(ConformationModels, PlanarExtensionOldroydBUnboundedAboveOneHalf) {
  // Steady: A11 = 1/(1 - 2 Wi), A22 = 1/(1 + 2 Wi) for Wi < 1/2; none above.
  const OldroydBRelaxation m;
  for (double wi : {0.1, 0.25, 0.45}) {
    const SymTensor a = SteadyModelConformation(m, Extension(wi), 1.0);
    EXPECT_NEAR(a.a11, 1.0 / (1.0 - 2.0 * wi), kSteadyTolerance / (1.0 - 2.0 * wi));
    EXPECT_NEAR(a.a22, 1.0 / (1.0 + 2.0 * wi), kSteadyTolerance);
    EXPECT_NEAR(a.a12, 0.0, 1e-14);
  }
  EXPECT_THROW(SteadyModelConformation(m, Extension(0.6), 1.0), InvalidParameter);
  EXPECT_THROW(SteadyConformation(Extension(0.6), 1.0), InvalidParameter);
  // Above 1/2, A11 = (1 - c) e^{(2 Wi - 1) t} + c, c = 1/(1 - 2 Wi): exponential growth.
  const double wi = 1.0, c = 1.0 / (1.0 - 2.0 * wi);
  SymTensor a{};
  for (int n = 0; n < 100; ++n) ASSERT_TRUE(ModelPointwiseStep(m, a, Extension(wi), 0.1, 1.0, &a));
  const double want = (1.0 - c) * std::exp((2.0 * wi - 1.0) * 10.0) + c;
  EXPECT_NEAR(a.a11, want, 1e-10 * want);
}

TEST(ConformationModels, PlanarExtensionGiesekusAndFenePStayBounded) {
  for (double wi : {0.25, 1.0, 5.0, 50.0}) {
    SCOPED_TRACE("Wi = " + std::to_string(wi));
    // Giesekus, per principal direction of rate +-Wi: alpha y^2 + (1 -+ 2 Wi) y -+ 2 Wi = 0,
    // y = A - 1.
    const double alpha = 0.1;
    const GiesekusRelaxation giesekus(alpha);
    const SymTensor g = SteadyModelConformation(giesekus, Extension(wi), 1.0);
    const double b1 = 1.0 - 2.0 * wi, b2 = 1.0 + 2.0 * wi;
    const double y1 = (-b1 + std::sqrt(b1 * b1 + 8.0 * alpha * wi)) / (2.0 * alpha);
    const double y2 = (-b2 + std::sqrt(b2 * b2 - 8.0 * alpha * wi)) / (2.0 * alpha);
    EXPECT_NEAR(g.a11, 1.0 + y1, kSteadyTolerance * (1.0 + y1));
    EXPECT_NEAR(g.a22, 1.0 + y2, kSteadyTolerance);
    EXPECT_LT(g.a11, 1.0 + 2.0 * wi / alpha);  // y1 < 2 Wi / alpha: bounded for any rate
    // FENE-P: A11 = a/(f - 2 Wi), A22 = a/(f + 2 Wi), tr A = L^2 (1 - 1/f); f by bisection.
    const double l2 = 100.0;
    const FenePRelaxation fene(l2);
    const double ra = fene.rest_factor();
    auto residual = [&](double f) {
      return ra / (f - 2.0 * wi) + ra / (f + 2.0 * wi) - l2 * (1.0 - 1.0 / f);
    };
    double lo = std::max(2.0 * wi, 1.0) * (1.0 + 1e-15), hi = 1e6;
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      (residual(mid) > 0.0 ? lo : hi) = mid;
    }
    const double f = 0.5 * (lo + hi);
    const SymTensor e = SteadyModelConformation(fene, Extension(wi), 1.0);
    EXPECT_NEAR(e.a11, ra / (f - 2.0 * wi), kSteadyTolerance * e.a11);
    EXPECT_NEAR(e.a22, ra / (f + 2.0 * wi), kSteadyTolerance);
    EXPECT_LT(Trace(e), l2);
  }
}

TEST(ConformationModels, FenePStressHasThePeterlinFunctionAndVanishesAtRest) {
  const FenePRelaxation m(50.0);
  const SymTensor rest = m.Stress(SymTensor{});
  EXPECT_NEAR(rest.a11, 0.0, 1e-15);
  EXPECT_NEAR(rest.a22, 0.0, 1e-15);
  const SymTensor a{20.0, 3.0, 2.0};
  const double f = 1.0 / (1.0 - 22.0 / 50.0), ra = 1.0 / (1.0 - 2.0 / 50.0);
  const SymTensor t = m.Stress(a);
  EXPECT_DOUBLE_EQ(t.a11, f * 20.0 - ra);
  EXPECT_DOUBLE_EQ(t.a12, f * 3.0);
  EXPECT_DOUBLE_EQ(t.a22, f * 2.0 - ra);
  EXPECT_FALSE(m.Admits(SymTensor{49.0, 0.0, 1.0}));
  EXPECT_TRUE(m.Admits(SymTensor{48.0, 0.0, 1.0}));
}

TEST(ConformationModels, StepStaysSpdAndInsideTheModelForLargeSteps) {
  // dt = lambda at lambda |L| = 5 to 20 (dt |L| up to 20): SPD, and tr A < L^2 for FENE-P. (The
  // frozen update is SPD for any dt in exact arithmetic; in doubles a step whose stretch e^{dt
  // |L|} puts cond(A) beyond 1/eps cannot show it, conformation_step.h.)
  for (const ModelCase& c : Models()) {
    const std::unique_ptr<RelaxationModel> m = c.make();
    for (const Mat2& l : {Extension(5.0), Shear(20.0), Mat2{3.0, 20.0, -7.0, -3.0}}) {
      SymTensor a{};
      for (int n = 0; n < 20; ++n) {
        ASSERT_TRUE(ModelPointwiseStep(*m, a, l, 1.0, 1.0, &a)) << c.name;
        ASSERT_GT(MinEigenvalue(a), 0.0) << c.name;
        ASSERT_TRUE(m->Admits(a)) << c.name;
      }
    }
  }
}

}  // namespace
}  // namespace dlmfd
