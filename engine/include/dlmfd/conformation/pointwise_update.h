// The pointwise part of step (35): dA/dt = L A + A L^T - (A - I)/lambda with L frozen, solved
// exactly up to a quadrature (method notes 2, section 2.1, "exponential integrator").
//
// Equation: paper (5) without the convective term, L_ij = du_i/dx_j of u^{n+2/4} frozen over the
// step. Discrete method: with F(s) = exp(s L),
//   A(dt) = e^{-dt/lambda} F(dt) A F(dt)^T + (1/lambda) int_0^dt e^{-s/lambda} F(s) F(s)^T ds.
//   F(s) in closed form: L0 = L - (tr L / 2) I, q^2 = -det L0, F = e^{s tr L/2} (c I + sigma L0)
//   with c = cosh(q s), sigma = sinh(q s)/q (q^2 > 0), the cos/sin forms (q^2 < 0), and the even
//   power series in x = q^2 s^2 when |x| < 1e-2 (5 terms: truncation below 1e-16). The integral:
//   composite 3-point Gauss-Legendre on n panels over [0, end], n = ceil(end (1/lambda + |tr L|
//   + 2|q|) / 0.125), at most 256; end = dt, or where the integrand has decayed by e^{-50} when
//   lambda << dt (IntegralEnd). Relative error of one panel about 0.125^6 / 2016000 ~ 2e-12, far
//   less when the rate is small (2e-15 at the paper's dt/lambda = 0.04); measured on steady shear:
//   1.7e-11 at the panel limit, order 6 in the panel width. The weights w_k e^{-s_k/lambda}/lambda
//   are rescaled so that they integrate e^{-s/lambda}/lambda exactly: they stay positive, and
//   homogeneous relaxation (L = 0) is exact to round-off: A <- e^{-dt/lambda} A + (1 -
//   e^{-dt/lambda}) I. Per node of a step: ExponentialIntegrator (one panel: two closed-form
//   exponentials) and its vectorised row form OnePanelRow; the general rule StretchAndRelax where
//   one panel is not enough.
// Positive definiteness, for any dt: det F = e^{s tr L} > 0, so F A F^T is SPD when A is, and the
//   update is a positive combination of SPD matrices (F(s) F(s)^T is SPD).
// Not supported: lambda <= 0 (a Newtonian liquid has no conformation step).
// References: method notes 2, sections 2.1 and 2.3; Higham, Functions of Matrices (2008), 10.
#pragma once

#include <algorithm>
#include <cmath>

#include "dlmfd/conformation/sym_tensor.h"

namespace dlmfd {

// e^y by its 9-term Taylor polynomial (truncation |y|^9/9! < 6e-18 relative for |y| <= 0.05).
inline double ExpPolynomial(double y) {
  // Multiplications by reciprocals: divisions would form a long-latency chain in the hot loop.
  constexpr double k3 = 1.0 / 3.0, k5 = 1.0 / 5.0, k6 = 1.0 / 6.0, k7 = 1.0 / 7.0;
  return 1.0 +
         y * (1.0 +
              y * 0.5 *
                  (1.0 +
                   y * k3 *
                       (1.0 +
                        y * 0.25 *
                            (1.0 + y * k5 * (1.0 + y * k6 * (1.0 + y * k7 * (1.0 + y * 0.125)))))));
}

// e^y: the polynomial for |y| <= 0.05, the library otherwise.
inline double ExpOf(double y) { return std::abs(y) <= 0.05 ? ExpPolynomial(y) : std::exp(y); }

// exp(s L) = scale (c I + sigma L0), L0 = L - (tr L/2) I = [[d, l12], [l21, -d]].
struct ExponentialParts {
  double scale, c, sigma, d;
};

// c = cosh(q s) and sigma = sinh(q s)/q (or their cos/sin forms) from q^2 and s.
inline void HyperbolicPair(double q2, double s, double& c, double& sigma) {
  const double x = q2 * s * s;
  if (std::abs(x) < 1e-2) {
    // cosh(sqrt x) and sinh(sqrt x)/sqrt x as power series in x (valid for either sign of x).
    constexpr double k12 = 1.0 / 12.0, k30 = 1.0 / 30.0, k56 = 1.0 / 56.0, k90 = 1.0 / 90.0;
    constexpr double k6 = 1.0 / 6.0, k20 = 1.0 / 20.0, k42 = 1.0 / 42.0, k72 = 1.0 / 72.0,
                     k110 = 1.0 / 110.0;
    c = 1.0 + x * 0.5 * (1.0 + x * k12 * (1.0 + x * k30 * (1.0 + x * k56 * (1.0 + x * k90))));
    sigma =
        s * (1.0 + x * k6 * (1.0 + x * k20 * (1.0 + x * k42 * (1.0 + x * k72 * (1.0 + x * k110)))));
  } else if (q2 > 0.0) {
    const double q = std::sqrt(q2);
    c = std::cosh(q * s);
    sigma = std::sinh(q * s) / q;
  } else {
    const double q = std::sqrt(-q2);
    c = std::cos(q * s);
    sigma = std::sin(q * s) / q;
  }
}

inline ExponentialParts ExponentialPartsOf(const Mat2& l, double s) {
  const double half_trace = 0.5 * (l.m11 + l.m22);
  const double d = l.m11 - half_trace;
  double c = 1.0, sigma = s;
  HyperbolicPair(d * d + l.m12 * l.m21, s, c, sigma);
  return ExponentialParts{ExpOf(s * half_trace), c, sigma, d};
}

// scale (c I + sign sigma L0): sign = +1 gives exp(s L), sign = -1 gives exp(-s L).
inline Mat2 Assemble(const ExponentialParts& e, const Mat2& l, double sign) {
  const double scale = sign > 0.0 ? e.scale : 1.0 / e.scale;
  const double sg = sign * e.sigma;
  return Mat2{scale * (e.c + sg * e.d), scale * sg * l.m12, scale * sg * l.m21,
              scale * (e.c - sg * e.d)};
}

// exp(s L) for a 2x2 L, in closed form.
inline Mat2 MatrixExponential(const Mat2& l, double s) {
  return Assemble(ExponentialPartsOf(l, s), l, 1.0);
}

inline Mat2 Product(const Mat2& a, const Mat2& b) {
  return Mat2{a.m11 * b.m11 + a.m12 * b.m21, a.m11 * b.m12 + a.m12 * b.m22,
              a.m21 * b.m11 + a.m22 * b.m21, a.m21 * b.m12 + a.m22 * b.m22};
}

// A(dt) of the frozen-L Oldroyd-B ODE from A(0) = a (see the header block).
// The largest dt (1/lambda + |tr L| + 2|q|) of one quadrature panel.
constexpr double kMaxPanelRate = 0.125;
constexpr int kMaxPanels = 256;
// Gauss-Legendre nodes on [0, 1] (1/2 -+ kGaussOffset) and weights (sum 1).
constexpr double kGaussOffset = 0.3872983346207417;  // sqrt(3/5)/2
constexpr double kGaussNode[3] = {0.5 - kGaussOffset, 0.5, 0.5 + kGaussOffset};
constexpr double kGaussWeight[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};

inline double PanelRate(const Mat2& l, double inv_lambda) {
  const double half_trace = 0.5 * (l.m11 + l.m22);
  const double d = l.m11 - half_trace;
  const double q = std::sqrt(std::abs(d * d + l.m12 * l.m21));
  return inv_lambda + 2.0 * std::abs(half_trace) + 2.0 * q;
}

// The integral's tail: where the integrand decays, the panels stop at kTailDecay e-foldings.
constexpr double kTailDecay = 50.0;

// The end of the integral's panels: dt, or where the integrand has decayed by e^{-kTailDecay}.
// |e^{-s/lambda} F(s) F(s)^T| <= e^{-kappa s} with kappa = 1/lambda - |tr L| - 2 |L0|_F (|e^{s L0}|
// <= e^{s |L0|}), so for kappa > 0 the part beyond kTailDecay / kappa is below e^{-50} / (kappa
// lambda) of the weight: with lambda << dt the panels resolve the layer of width lambda where the
// integral lives instead of spreading over dt (at dt / lambda = 2000 the 256 panels were 8 lambda
// wide, and A - I came out far from its limit lambda (L + L^T)).
inline double IntegralEnd(const Mat2& l, double dt, double lambda) {
  const double half_trace = 0.5 * (l.m11 + l.m22);
  const double d = l.m11 - half_trace;
  const double l0 = std::sqrt(2.0 * d * d + l.m12 * l.m12 + l.m21 * l.m21);
  const double kappa = 1.0 / lambda - 2.0 * std::abs(half_trace) - 2.0 * l0;
  return kappa > 0.0 ? std::min(dt, kTailDecay / kappa) : dt;
}

inline SymTensor StretchAndRelax(const SymTensor& a, const Mat2& l, double dt, double lambda) {
  const double rate = PanelRate(l, 1.0 / lambda);
  const double end = IntegralEnd(l, dt, lambda);
  // At most kMaxPanels: beyond end rate = 32 the growth e^{2 end rate} puts A past what doubles
  // resolve (cond(A) > 1e16), so more panels buy no accuracy; SPD holds for any panel count.
  const double wanted = std::ceil(std::min(end * rate / kMaxPanelRate, double(kMaxPanels)));
  const int panels = std::max(1, static_cast<int>(wanted));
  const double width = end / panels;

  SymTensor integral{0.0, 0.0, 0.0};
  double weight_sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    for (int k = 0; k < 3; ++k) {
      const double s = (p + kGaussNode[k]) * width;
      const double w = kGaussWeight[k] * width * std::exp(-s / lambda) / lambda;
      const SymTensor g = GramOf(MatrixExponential(l, s));
      integral.a11 += w * g.a11;
      integral.a12 += w * g.a12;
      integral.a22 += w * g.a22;
      weight_sum += w;
    }
  }
  const double decay = std::exp(-dt / lambda);
  const double exact_weight = -std::expm1(-end / lambda);  // int_0^end e^{-s/lambda}/lambda ds
  const double rescale = exact_weight / weight_sum;
  const SymTensor stretched = Congruence(MatrixExponential(l, dt), a);
  return SymTensor{decay * stretched.a11 + rescale * integral.a11,
                   decay * stretched.a12 + rescale * integral.a12,
                   decay * stretched.a22 + rescale * integral.a22};
}

// The per-step constants of the one-panel rule (ExponentialIntegrator, OnePanelRow).
struct OnePanelConstants {
  double dt, inv_lambda, decay, max_rate, w1, w2, w3;
};

// dt (1/lambda + |tr L| + 2|q|) <= kMaxPanelRate, without a square root.
inline bool OnePanelApplies(const OnePanelConstants& k, const Mat2& l) {
  const double ht = 0.5 * (l.m11 + l.m22);
  const double d = l.m11 - ht;
  const double q2 = d * d + l.m12 * l.m21;
  const double room = k.max_rate - k.inv_lambda - 2.0 * std::abs(ht);  // >= 2 |q| wanted
  return room >= 0.0 && 4.0 * std::abs(q2) <= room * room;
}

// StretchAndRelax for many nodes with the same dt and lambda: the one-panel weights are made once,
// and a node whose rate allows one panel needs two closed-form exponentials: with E = F(dt/2) and
// G = F(delta), F(dt/2 -+ delta) = E G^{-+1} (G^{-1} from the same c and sigma) and F(dt) = E^2, so
//   A(dt) = E [decay E A E^T + w1 G^{-1} G^{-T} + w2 I + w3 G G^T] E^T (about 120 flops a node).
// Other nodes take the general composite rule. Equal to StretchAndRelax up to round-off.
class ExponentialIntegrator {
 public:
  ExponentialIntegrator(double dt, double lambda)
      : dt_(dt),
        lambda_(lambda),
        inv_lambda_(1.0 / lambda),
        decay_(std::exp(-dt / lambda)),
        max_rate_(kMaxPanelRate / dt) {
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
      weight_[k] = kGaussWeight[k] * dt * std::exp(-kGaussNode[k] * dt / lambda) / lambda;
      sum += weight_[k];
    }
    const double rescale = -std::expm1(-dt / lambda) / sum;
    for (double& w : weight_) w *= rescale;
  }

  SymTensor Apply(const SymTensor& a, const Mat2& l) const {
    if (PanelRate(l, inv_lambda_) > max_rate_) return StretchAndRelax(a, l, dt_, lambda_);
    const double half_trace = 0.5 * (l.m11 + l.m22);
    const double d = l.m11 - half_trace;
    const double q2 = d * d + l.m12 * l.m21;
    // E = F(dt/2) = e_h (c_h I + sigma_h L0).
    const double half_dt = 0.5 * dt_, delta = kGaussOffset * dt_;
    double c_h = 1.0, sigma_h = half_dt, c_d = 1.0, sigma_d = delta;
    HyperbolicPair(q2, half_dt, c_h, sigma_h);
    HyperbolicPair(q2, delta, c_d, sigma_d);
    const double e_h = ExpOf(half_dt * half_trace);
    const Mat2 e{e_h * (c_h + sigma_h * d), e_h * sigma_h * l.m12, e_h * sigma_h * l.m21,
                 e_h * (c_h - sigma_h * d)};
    // G^{-+1} = g^{-+1} (c I -+ sigma L0): G G^T and G^{-1} G^{-T} share c^2 I + sigma^2 L0 L0^T
    // and differ in the sign of c sigma (L0 + L0^T), so M = w1 G^{-1} G^{-T} + w2 I + w3 G G^T = p
    // (c^2 I + sigma^2 S) + m c sigma P + w2 I.
    const double g2 = ExpOf(2.0 * delta * half_trace), g2_inv = ExpOf(-2.0 * delta * half_trace);
    const double plus = weight_[0] * g2_inv + weight_[2] * g2,
                 minus = weight_[2] * g2 - weight_[0] * g2_inv;
    const double cc = c_d * c_d, ss = sigma_d * sigma_d, cs = minus * c_d * sigma_d;
    const SymTensor inner = Congruence(e, a);
    const SymTensor middle{
        decay_ * inner.a11 + plus * (cc + ss * (d * d + l.m12 * l.m12)) + cs * 2.0 * d + weight_[1],
        decay_ * inner.a12 + plus * ss * d * (l.m21 - l.m12) + cs * (l.m12 + l.m21),
        decay_ * inner.a22 + plus * (cc + ss * (d * d + l.m21 * l.m21)) - cs * 2.0 * d +
            weight_[1]};
    return Congruence(e, middle);
  }

  OnePanelConstants Constants() const {
    return OnePanelConstants{dt_,        inv_lambda_, decay_,    max_rate_,
                             weight_[0], weight_[1],  weight_[2]};
  }

 private:
  double dt_, lambda_, inv_lambda_, decay_, max_rate_;
  double weight_[3];
};

// The one-panel update of ExponentialIntegrator::Apply for a row of nodes, without branches so that
// the compiler vectorises it. Valid where dt (1/lambda + |tr L| + 2|q|) <= kMaxPanelRate: then
// |q^2 (dt/2)^2| <= 1e-3 (the cosh/sinh series apply) and |2 delta tr L/2| <= 0.05 (the exponential
// polynomial applies). Elsewhere (OnePanelApplies false) the outputs are meaningless; the caller
// redoes those nodes with ExponentialIntegrator::Apply. Compiled for AVX2 and for the baseline
// (chosen at load time); both do the same IEEE operations in the same order.
void OnePanelRow(int count, const OnePanelConstants& k, const double* __restrict a11,
                 const double* __restrict a12, const double* __restrict a22,
                 const double* __restrict l11, const double* __restrict l12,
                 const double* __restrict l21, const double* __restrict l22, double* __restrict o11,
                 double* __restrict o12, double* __restrict o22);

}  // namespace dlmfd
