// The shape of a rigid particle; see particles/shape.h.
#include "dlmfd/particles/shape.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"

namespace dlmfd {
namespace {

// Gauss-Legendre nodes and weights on [-1, 1], 8 points.
constexpr std::array<double, 8> kGaussNode = {
    -0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
    0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kGaussWeight = {
    0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
    0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

// Panels of the ellipse's arc length over its parameter t in [0, 2 pi).
constexpr int kArcPanels = 128;

// |d(a cos t, b sin t)/dt|.
double Speed(double a, double b, double t) {
  const double s = std::sin(t), c = std::cos(t);
  return std::sqrt(a * a * s * s + b * b * c * c);
}

// The arc length from t0 to t1 (one panel or less), 8-point Gauss-Legendre.
double ArcLength(double a, double b, double t0, double t1) {
  const double half = 0.5 * (t1 - t0), mid = 0.5 * (t1 + t0);
  double sum = 0.0;
  for (int k = 0; k < 8; ++k) sum += kGaussWeight[k] * Speed(a, b, mid + half * kGaussNode[k]);
  return half * sum;
}

// Eberly's root of F(s) = (r0 z0 / (s + r0))^2 + (z1 / (s + 1))^2 - 1 by bisection (r0 =
// (e0/e1)^2 >= 1, z the point scaled by the semi-axes, g = F(0)).
double ClosestPointRoot(double r0, double z0, double z1, double g) {
  const double n0 = r0 * z0;
  double s0 = z1 - 1.0;
  double s1 = g < 0.0 ? 0.0 : std::hypot(n0, z1) - 1.0;
  double s = 0.0;
  for (int i = 0; i < 1100; ++i) {
    s = 0.5 * (s0 + s1);
    if (s == s0 || s == s1) break;
    const double ratio0 = n0 / (s + r0), ratio1 = z1 / (s + 1.0);
    const double f = ratio0 * ratio0 + ratio1 * ratio1 - 1.0;
    if (f > 0.0) {
      s0 = s;
    } else if (f < 0.0) {
      s1 = s;
    } else {
      break;
    }
  }
  return s;
}

// The closest point of the ellipse with semi-axes e0 >= e1 along x and y to (y0, y1), y0, y1 >= 0
// (Eberly 2013, section 2.9).
Vec2 ClosestOnEllipse(double e0, double e1, double y0, double y1) {
  if (y1 > 0.0) {
    if (y0 > 0.0) {
      const double z0 = y0 / e0, z1 = y1 / e1;
      const double g = z0 * z0 + z1 * z1 - 1.0;
      if (g == 0.0) return Vec2(y0, y1);
      const double r0 = (e0 / e1) * (e0 / e1);
      const double s = ClosestPointRoot(r0, z0, z1, g);
      return Vec2(r0 * y0 / (s + r0), y1 / (s + 1.0));
    }
    return Vec2(0.0, e1);
  }
  const double numer0 = e0 * y0, denom0 = e0 * e0 - e1 * e1;
  if (numer0 < denom0) {
    const double xde0 = numer0 / denom0;
    return Vec2(e0 * xde0, e1 * std::sqrt(1.0 - xde0 * xde0));
  }
  return Vec2(e0, 0.0);
}

}  // namespace

Shape Shape::Disk(double radius) {
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw InvalidParameter("particles.diameter", ExactText(2.0 * radius), "> 0");
  }
  return Shape(ShapeKind::kDisk, radius, radius);
}

Shape Shape::Ellipse(double a, double b) {
  if (!(a > 0.0) || !(b > 0.0) || !std::isfinite(a) || !std::isfinite(b)) {
    throw InvalidParameter("particles.semi_axes", VecText(Vec2(a, b)),
                           "two semi-axes > 0 (finite)");
  }
  return Shape(ShapeKind::kEllipse, a, b);
}

Shape Shape::Of(const ParticleParams& p) {
  if (p.shape == ShapeKind::kEllipse) return Ellipse(p.semi_axes.x(), p.semi_axes.y());
  return Disk(p.Radius());
}

Shape Shape::Of(const ParticleState& p) {
  if (p.shape == ShapeKind::kEllipse) return Ellipse(p.semi_axes.x(), p.semi_axes.y());
  return Disk(p.radius);
}

double Shape::Area() const { return kPi * a_ * b_; }

double Shape::Mass(double density) const {
  return IsDisk() ? density * kPi * a_ * a_ : density * kPi * a_ * b_;
}

double Shape::MomentOfInertia(double density) const {
  if (IsDisk()) return 0.5 * density * kPi * std::pow(a_, 4);
  return 0.25 * density * kPi * a_ * b_ * (a_ * a_ + b_ * b_);
}

double Shape::InverseMomentOfInertia(double mass) const {
  return IsDisk() ? 2.0 / (mass * a_ * a_) : 4.0 / (mass * (a_ * a_ + b_ * b_));
}

double Shape::InverseMomentFromInverseMass(double inverse_mass) const {
  return IsDisk() ? 2.0 * inverse_mass / (a_ * a_) : 4.0 * inverse_mass / (a_ * a_ + b_ * b_);
}

double Shape::Perimeter() const {
  if (IsDisk()) return 2.0 * kPi * a_;
  const double panel = 2.0 * kPi / kArcPanels;
  double length = 0.0;
  for (int k = 0; k < kArcPanels; ++k) length += ArcLength(a_, b_, k * panel, (k + 1) * panel);
  return length;
}

bool Shape::Inside(const Vec2& r) const {
  if (IsDisk()) return r.norm() < a_;
  const double x = r.x() / a_, y = r.y() / b_;
  return x * x + y * y < 1.0;
}

double Shape::SignedDistance(const Vec2& r) const {
  if (IsDisk()) return r.norm() - a_;
  const double d = (ClosestBoundaryPoint(r) - r).norm();
  return Inside(r) ? -d : d;
}

Vec2 Shape::ClosestBoundaryPoint(const Vec2& r) const {
  if (IsDisk()) {
    const double n = r.norm();
    return n > 0.0 ? Vec2(a_ * r / n) : Vec2(a_, 0.0);
  }
  const double x = std::abs(r.x()), y = std::abs(r.y());
  // Eberly's form wants the longer semi-axis first.
  Vec2 q = a_ >= b_ ? ClosestOnEllipse(a_, b_, x, y) : ClosestOnEllipse(b_, a_, y, x);
  if (a_ < b_) q = Vec2(q.y(), q.x());
  return Vec2(std::copysign(q.x(), r.x()), std::copysign(q.y(), r.y()));
}

Vec2 Shape::Normal(const Vec2& boundary_point) const {
  return Vec2(boundary_point.x() / (a_ * a_), boundary_point.y() / (b_ * b_)).normalized();
}

Vec2 Shape::Support(const Vec2& direction) const {
  if (IsDisk()) return a_ * direction.normalized();
  const double ax = a_ * a_ * direction.x(), by = b_ * b_ * direction.y();
  const double scale = std::sqrt(ax * direction.x() + by * direction.y());
  return Vec2(ax / scale, by / scale);
}

int Shape::BoundaryPointCount(double spacing) const {
  return std::max(3, static_cast<int>(std::floor(Perimeter() / spacing + 1e-9)));
}

std::vector<BoundaryPoint> Shape::BoundaryPoints(int count) const {
  std::vector<BoundaryPoint> points;
  points.reserve(static_cast<std::size_t>(count));
  if (IsDisk()) {
    for (int k = 0; k < count; ++k) {
      const double angle = 2.0 * kPi * k / count;
      const Vec2 normal(std::cos(angle), std::sin(angle));
      points.push_back({Vec2(a_ * std::cos(angle), a_ * std::sin(angle)), normal});
    }
    return points;
  }
  // Arc length at the panel ends, then t(s) in its panel by Newton's method from the linear guess.
  const double panel = 2.0 * kPi / kArcPanels;
  std::vector<double> at(kArcPanels + 1, 0.0);
  for (int k = 0; k < kArcPanels; ++k)
    at[k + 1] = at[k] + ArcLength(a_, b_, k * panel, (k + 1) * panel);
  const double length = at[kArcPanels];
  int panel_index = 0;
  for (int k = 0; k < count; ++k) {
    const double s = length * k / count;
    while (panel_index + 1 < kArcPanels && at[panel_index + 1] <= s) ++panel_index;
    const double t0 = panel_index * panel;
    double t = t0 + panel * (s - at[panel_index]) / (at[panel_index + 1] - at[panel_index]);
    for (int it = 0; it < 50; ++it) {
      const double step = (at[panel_index] + ArcLength(a_, b_, t0, t) - s) / Speed(a_, b_, t);
      t -= step;
      if (std::abs(step) < 1e-15) break;
    }
    const Vec2 position(a_ * std::cos(t), b_ * std::sin(t));
    const Vec2 normal = Vec2(position.x() / (a_ * a_), position.y() / (b_ * b_)).normalized();
    points.push_back({position, normal});
  }
  return points;
}

}  // namespace dlmfd
