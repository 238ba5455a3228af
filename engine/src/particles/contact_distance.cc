// The distance between particles of any shape and to walls; see particles/contact_distance.h.
#include "dlmfd/particles/contact_distance.h"

#include <cmath>
#include <utility>

#include "dlmfd/core/constants.h"

namespace dlmfd {
namespace {

constexpr int kSamples = 64;
constexpr int kGoldenIterations = 60;  // the bracket shrinks by 0.618^60 = 3e-13

// The signed distance to B of A's boundary point at parameter t (world frame).
double GapAt(const PlacedShape& a, const PlacedShape& b, double t) {
  const Vec2 axes = a.shape->SemiAxes();
  const Vec2 on_a =
      a.centre + Rotate(a.angle, Vec2(axes.x() * std::cos(t), axes.y() * std::sin(t)));
  return b.shape->SignedDistance(Rotate(-b.angle, on_a - b.centre));
}

// Contact of a disk A (radius R) with B: B's closest boundary point to A's centre.
Contact DiskAgainst(const PlacedShape& a, const PlacedShape& b) {
  const double radius = a.shape->SemiAxes().x();
  const Vec2 centre = Rotate(-b.angle, a.centre - b.centre);  // A's centre in B's body frame
  const Vec2 foot = b.shape->ClosestBoundaryPoint(centre);
  const double signed_distance = b.shape->SignedDistance(centre);
  Contact c;
  c.gap = signed_distance - radius;
  c.normal = Rotate(b.angle, b.shape->Normal(foot));
  c.point_b = b.centre + Rotate(b.angle, foot);
  c.point_a = a.centre - radius * c.normal;
  return c;
}

Contact Flip(Contact c) {
  std::swap(c.point_a, c.point_b);
  c.normal = -c.normal;
  return c;
}

}  // namespace

Contact PairContact(const PlacedShape& a, const PlacedShape& b) {
  if (a.shape->IsDisk()) return DiskAgainst(a, b);
  if (b.shape->IsDisk()) return Flip(DiskAgainst(b, a));
  // Two ellipses: the smallest sample of the gap along A's boundary, then golden section.
  const double step = 2.0 * kPi / kSamples;
  int best = 0;
  double best_gap = GapAt(a, b, 0.0);
  for (int k = 1; k < kSamples; ++k) {
    const double g = GapAt(a, b, k * step);
    if (g < best_gap) {
      best_gap = g;
      best = k;
    }
  }
  double lo = (best - 1) * step, hi = (best + 1) * step;
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
  double f1 = GapAt(a, b, x1), f2 = GapAt(a, b, x2);
  for (int it = 0; it < kGoldenIterations; ++it) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - ratio * (hi - lo);
      f1 = GapAt(a, b, x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + ratio * (hi - lo);
      f2 = GapAt(a, b, x2);
    }
  }
  const double t = f1 < f2 ? x1 : x2;
  const Vec2 axes = a.shape->SemiAxes();
  Contact c;
  c.point_a = a.centre + Rotate(a.angle, Vec2(axes.x() * std::cos(t), axes.y() * std::sin(t)));
  const Vec2 in_b = Rotate(-b.angle, c.point_a - b.centre);
  const Vec2 foot = b.shape->ClosestBoundaryPoint(in_b);
  c.gap = b.shape->SignedDistance(in_b);
  c.point_b = b.centre + Rotate(b.angle, foot);
  c.normal = Rotate(b.angle, b.shape->Normal(foot));
  return c;
}

Contact WallContact(const PlacedShape& a, const Vec2& inward, double dist) {
  const Vec2 toward_wall = Rotate(-a.angle, -inward);  // in A's body frame
  const Vec2 support = Rotate(a.angle, a.shape->Support(toward_wall));
  Contact c;
  c.gap = dist + support.dot(inward);  // dist minus the extent toward the wall
  c.point_a = a.centre + support;
  c.point_b = c.point_a - c.gap * inward;
  c.normal = inward;
  return c;
}

}  // namespace dlmfd
