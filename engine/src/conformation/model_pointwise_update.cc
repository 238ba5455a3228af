#include "dlmfd/conformation/model_pointwise_update.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "dlmfd/conformation/pointwise_update.h"
#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

constexpr int kMaxHalvings = 20;
constexpr double kCoefficientChange = 0.25;
constexpr double kSteadyTolerance = 1e-13;  // Newton: last correction relative to 1 + max|A|
constexpr double kStallTolerance = 1e-10;
constexpr int kMaxNewtonSteps = 30;
constexpr double kJacobianStep = 1e-6;
constexpr double kFirstContinuationStep = 0.125;
constexpr double kLargestContinuationStep = 0.25;
constexpr double kSmallestContinuationStep = 1e-6;

SymTensor Midpoint(const SymTensor& a, const SymTensor& b) {
  return SymTensor{0.5 * (a.a11 + b.a11), 0.5 * (a.a12 + b.a12), 0.5 * (a.a22 + b.a22)};
}

double MaxAbs(const SymTensor& a) {
  return std::max({std::abs(a.a11), std::abs(a.a12), std::abs(a.a22)});
}

// Predictor-corrector over one piece; false when a state leaves the model's domain.
bool PredictCorrect(const RelaxationModel& model, const SymTensor& a, const Mat2& l, double dt,
                    double lambda, SymTensor* out) {
  // A state outside the model, or one whose SPD property doubles no longer show (an overflowing
  // Y of the exponential PTT, a condition number past 1/eps), asks for a shorter piece.
  auto usable = [&model](const SymTensor& x) {
    return IsFinite(x) && model.Admits(x) && MinEigenvalue(x) > 0.0;
  };
  const SymTensor predicted = FrozenUpdate(a, l, dt, lambda, model.Frozen(a));
  if (!usable(predicted)) return false;
  const FrozenRelaxation middle = model.Frozen(Midpoint(a, predicted));
  const SymTensor corrected = FrozenUpdate(a, l, dt, lambda, middle);
  if (!usable(corrected)) return false;
  // The frozen coefficients must stand for the whole piece: N and c at its end within a quarter
  // of those at its middle (a stiff piece, such as a large stretch of the exponential PTT, whose
  // Y changes by orders of magnitude, is split instead). Pieces of a smooth flow change N by O(dt).
  const FrozenRelaxation end = model.Frozen(corrected);
  const double size = std::max(
      {std::abs(middle.n.a11), std::abs(middle.n.a12), std::abs(middle.n.a22), std::abs(middle.c)});
  const double change =
      std::max({std::abs(end.n.a11 - middle.n.a11), std::abs(end.n.a12 - middle.n.a12),
                std::abs(end.n.a22 - middle.n.a22), std::abs(end.c - middle.c)});
  if (!(change <= kCoefficientChange * size)) return false;
  *out = corrected;
  return true;
}

}  // namespace

SymTensor FrozenUpdate(const SymTensor& a, const Mat2& l, double dt, double lambda,
                       const FrozenRelaxation& frozen) {
  const double shift = 0.5 / lambda;
  const Mat2 k{l.m11 - shift * frozen.n.a11, l.m12 - shift * frozen.n.a12,
               l.m21 - shift * frozen.n.a12, l.m22 - shift * frozen.n.a22};
  const double rate = PanelRate(k, 0.0);
  const double wanted = std::ceil(std::min(dt * rate / kMaxPanelRate, double(kMaxPanels)));
  const int panels = std::max(1, static_cast<int>(wanted));
  const double width = dt / panels;
  const double source = frozen.c / lambda;
  SymTensor integral{0.0, 0.0, 0.0};
  for (int p = 0; p < panels; ++p) {
    for (int q = 0; q < 3; ++q) {
      const double s = (p + kGaussNode[q]) * width;
      const double w = source * kGaussWeight[q] * width;
      const SymTensor g = GramOf(MatrixExponential(k, s));
      integral.a11 += w * g.a11;
      integral.a12 += w * g.a12;
      integral.a22 += w * g.a22;
    }
  }
  const SymTensor stretched = Congruence(MatrixExponential(k, dt), a);
  return SymTensor{stretched.a11 + integral.a11, stretched.a12 + integral.a12,
                   stretched.a22 + integral.a22};
}

namespace {

// The step over dt from a, split in halves (recursively, depth at most kMaxHalvings) where a piece
// leaves the model's states; false when a piece of dt / 2^kMaxHalvings still does.
bool AdaptiveStep(const RelaxationModel& model, const SymTensor& a, const Mat2& l, double dt,
                  double lambda, int depth, SymTensor* out) {
  if (PredictCorrect(model, a, l, dt, lambda, out)) return true;
  if (depth == kMaxHalvings) {
    *out = a;
    return false;
  }
  SymTensor half;
  if (!AdaptiveStep(model, a, l, 0.5 * dt, lambda, depth + 1, &half)) {
    *out = half;
    return false;
  }
  return AdaptiveStep(model, half, l, 0.5 * dt, lambda, depth + 1, out);
}

}  // namespace

bool ModelPointwiseStep(const RelaxationModel& model, const SymTensor& a, const Mat2& l, double dt,
                        double lambda, SymTensor* out) {
  return AdaptiveStep(model, a, l, dt, lambda, 0, out);
}

namespace {

// Newton on L A + A L^T - R(A)/lambda = 0 from *a (central-difference Jacobian); true when it
// converges to an SPD state of the model, which is then in *a.
bool SteadyNewton(const RelaxationModel& model, const Mat2& l, double lambda, SymTensor* a) {
  auto residual = [&](const SymTensor& x) {
    const SymTensor r = model.Source(x);
    return std::array<double, 3>{
        2.0 * (l.m11 * x.a11 + l.m12 * x.a12) - r.a11 / lambda,
        l.m11 * x.a12 + l.m12 * x.a22 + x.a11 * l.m21 + x.a12 * l.m22 - r.a12 / lambda,
        2.0 * (l.m21 * x.a12 + l.m22 * x.a22) - r.a22 / lambda};
  };
  SymTensor x = *a;
  double last = std::numeric_limits<double>::infinity();
  for (int it = 0; it < kMaxNewtonSteps; ++it) {
    const std::array<double, 3> f = residual(x);
    double jac[3][3];
    const double step = kJacobianStep * (1.0 + MaxAbs(x));
    for (int c = 0; c < 3; ++c) {
      SymTensor plus = x, minus = x;
      double* pc[3] = {&plus.a11, &plus.a12, &plus.a22};
      double* mc[3] = {&minus.a11, &minus.a12, &minus.a22};
      *pc[c] += step;
      *mc[c] -= step;
      const std::array<double, 3> fp = residual(plus), fm = residual(minus);
      for (int r = 0; r < 3; ++r) jac[r][c] = (fp[r] - fm[r]) / (2.0 * step);
    }
    const std::array<double, 3> d = SolveThreeByThree(jac, {-f[0], -f[1], -f[2]});
    x = SymTensor{x.a11 + d[0], x.a12 + d[1], x.a22 + d[2]};
    if (!IsFinite(x) || !model.Admits(x) || !(MinEigenvalue(x) > 0.0)) return false;
    const double size = MaxAbs(SymTensor{d[0], d[1], d[2]}) / (1.0 + MaxAbs(x));
    // Converged, or stalled at round-off (no longer halving, already below 1e-10).
    if (size <= kSteadyTolerance || (size <= kStallTolerance && size > 0.5 * last)) {
      *a = x;
      return true;
    }
    last = size;
  }
  return false;
}

}  // namespace

SymTensor SteadyModelConformation(const RelaxationModel& model, const Mat2& l, double lambda) {
  // Continuation from rest: the steady states of s L for s from 0 to 1, each Newton started from
  // the last; the step in s grows after a success and halves after a failure.
  SymTensor a{};
  double s = 0.0, ds = kFirstContinuationStep;
  while (s < 1.0 && ds >= kSmallestContinuationStep) {
    const double next = std::min(1.0, s + ds);
    const Mat2 scaled{next * l.m11, next * l.m12, next * l.m21, next * l.m22};
    SymTensor guess = a;
    if (SteadyNewton(model, scaled, lambda, &guess)) {
      a = guess;
      s = next;
      ds = std::min(2.0 * ds, kLargestContinuationStep);
    } else {
      ds *= 0.5;
    }
  }
  if (s >= 1.0) return a;
  std::ostringstream value;
  value << lambda;
  throw InvalidParameter("fluid.relaxation_time", value.str(),
                         std::string("a velocity gradient with a steady ") + model.Name() +
                             " state at an inflow boundary (none is reached in this flow)");
}

}  // namespace dlmfd
