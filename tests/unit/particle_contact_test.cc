// The proper distance between particles of any shape and to walls (particles/contact_distance.h),
// and the collision forces (14)-(15) on it (particles/collision_forces.h): gaps against a dense
// search along the boundary, the closest points and the normal, the wall gap of a turned ellipse
// in closed form, equal and opposite forces whose torques conserve angular momentum, and two
// disks unchanged by the shape path.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dlmfd/core/constants.h"
#include "dlmfd/particles/collision_forces.h"
#include "dlmfd/particles/contact_distance.h"
#include "dlmfd/particles/shape.h"

namespace dlmfd {
namespace {

// min over 20000 points of A's boundary of the signed distance to B (Shape::SignedDistance is
// checked against a brute-force search in particle_shape_test).
double DenseGap(const PlacedShape& a, const PlacedShape& b) {
  const Vec2 axes = a.shape->SemiAxes();
  double best = 1e300;
  for (int k = 0; k < 20000; ++k) {
    const double t = 2.0 * kPi * k / 20000;
    const Vec2 on_a =
        a.centre + Rotate(a.angle, Vec2(axes.x() * std::cos(t), axes.y() * std::sin(t)));
    best = std::min(best, b.shape->SignedDistance(Rotate(-b.angle, on_a - b.centre)));
  }
  return best;
}

double Cross2(const Vec2& r, const Vec2& f) { return r.x() * f.y() - r.y() * f.x(); }

TEST(ContactDistance, EllipsesAndDisksMatchADenseSearchWithConsistentClosestPoints) {
  const Shape shapes[] = {Shape::Ellipse(0.2, 0.1), Shape::Ellipse(0.05, 0.4),
                          Shape::Ellipse(0.4, 0.05), Shape::Disk(0.12)};
  int separated = 0;
  for (int n = 0; n < 120; ++n) {
    const Shape& sa = shapes[n % 4];
    const Shape& sb = shapes[(n / 4) % 4];
    const double direction = 2.0 * kPi * std::fmod(0.6180339887 * n, 1.0);
    const double distance = 0.1 + 0.5 * std::fmod(0.7548776662 * n + 0.2, 1.0);
    const PlacedShape a{&sa, Vec2(0.3, -0.2), 2.0 * kPi * std::fmod(0.5698402910 * n, 1.0)};
    const PlacedShape b{&sb, a.centre - distance * Vec2(std::cos(direction), std::sin(direction)),
                        2.0 * kPi * std::fmod(0.4142135624 * n + 0.1, 1.0)};
    const Contact c = PairContact(a, b);
    const double dense = DenseGap(a, b);
    EXPECT_NEAR(c.normal.norm(), 1.0, 1e-14);
    // Overlapping bodies: both measure a penetration (with a disk the contact measures it from
    // the disk's centre, and inside B the signed distance has kinks, so the values differ).
    EXPECT_EQ(c.gap < 0.0, dense < 0.0) << n;
    if (c.gap > 0.0) {
      // Separated, the dense search is at most (2 pi a / 20000)^2 / (2 rho_min) above the minimum.
      EXPECT_LE(c.gap, dense + 1e-12) << n;
      EXPECT_GE(c.gap, dense - 1e-6) << n;
      ++separated;
      // The closest points lie on the boundaries, the gap between them along the normal.
      EXPECT_NEAR(sa.SignedDistance(Rotate(-a.angle, c.point_a - a.centre)), 0.0, 1e-12);
      EXPECT_NEAR(sb.SignedDistance(Rotate(-b.angle, c.point_b - b.centre)), 0.0, 1e-12);
      EXPECT_NEAR((c.point_a - c.point_b - c.gap * c.normal).norm(), 0.0, 1e-9) << n;
      // Swapping the pair gives the same gap and the opposite normal.
      const Contact swapped = PairContact(b, a);
      EXPECT_NEAR(swapped.gap, c.gap, 1e-9) << n;
      EXPECT_NEAR((swapped.normal + c.normal).norm(), 0.0, 1e-5) << n;
    }
  }
  EXPECT_GT(separated, 40);
  EXPECT_LT(separated, 120);  // overlapping pairs were measured too
}

TEST(ContactDistance, TwoDisksAndATurnedEllipseAtAWallInClosedForm) {
  const Shape d1 = Shape::Disk(0.1), d2 = Shape::Disk(0.05);
  const Contact c = PairContact({&d1, Vec2(0.0, 0.0), 0.0}, {&d2, Vec2(0.3, 0.4), 1.0});
  EXPECT_NEAR(c.gap, 0.5 - 0.15, 1e-15);
  EXPECT_NEAR((c.normal - Vec2(-0.6, -0.8)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((c.point_a - Vec2(0.06, 0.08)).norm(), 0.0, 1e-15);
  const Shape e = Shape::Ellipse(0.2, 0.1);
  for (double theta : {0.0, 0.3, 1.2, 2.5}) {
    // The bottom wall 0.25 below the centre: the extent downward is sqrt(a^2 s^2 + b^2 c^2).
    const Contact w = WallContact({&e, Vec2(0.5, 0.25), theta}, Vec2(0.0, 1.0), 0.25);
    const double extent = std::hypot(0.2 * std::sin(theta), 0.1 * std::cos(theta));
    EXPECT_NEAR(w.gap, 0.25 - extent, 1e-15);
    EXPECT_NEAR(w.point_a.y(), 0.25 - extent, 1e-15);
    EXPECT_NEAR(w.point_b.y(), 0.0, 1e-15);
  }
}

Params CollisionScene() {
  Params p;
  p.domain.size = Vec2(1.0, 1.0);
  p.domain.h = 1.0 / 32;
  p.collisions.range = 2.0;
  return p;
}

TEST(CollisionForces, EllipsesRepelByTheirDistanceWithTorquesThatConserveAngularMomentum) {
  const Params p = CollisionScene();
  const Grid grid = p.domain.VelocityGrid();
  const std::vector<Shape> shapes = {Shape::Ellipse(0.2, 0.05), Shape::Ellipse(0.15, 0.1)};
  CollisionForces collisions(p, grid, {0.2, 0.15});
  collisions.SetShapes(shapes);
  const double range = 2.0 / 32;
  // Side by side along x, both upright (the second tilted by 0.1), so that the bounding circles
  // overlap but the bodies are about a third of the range apart: a bounding-circle law would push
  // them hard; this one gently, off-centre.
  const std::vector<Vec2> x = {Vec2(0.4, 0.5), Vec2(0.4 + 0.05 + 0.1 + range / 3, 0.53)};
  collisions.SetAngles({kPi / 2, kPi / 2 + 0.1});
  std::vector<Vec2> f(2);
  const int contacts = collisions.Compute(x, f);
  EXPECT_EQ(contacts, 1);
  const Contact c = PairContact({&shapes[0], x[0], kPi / 2}, {&shapes[1], x[1], kPi / 2 + 0.1});
  ASSERT_GT(c.gap, 0.0);
  ASSERT_LT(c.gap, range);
  const double magnitude = (std::sqrt(0.2 * 0.05) + std::sqrt(0.15 * 0.1) + c.gap) *
                           (range - c.gap) * (range - c.gap) / p.collisions.particle_stiffness;
  EXPECT_NEAR(f[0].norm(), magnitude, 1e-12 * magnitude);
  EXPECT_NEAR((f[0] + f[1]).norm(), 0.0, 1e-15 * magnitude);
  EXPECT_LT(f[0].x(), 0.0);  // particle 0 is on the left
  const std::vector<double>& t = collisions.Torques();
  EXPECT_GT(std::abs(t[0]) + std::abs(t[1]), 1e-3 * magnitude * 0.05);
  EXPECT_NEAR(Cross2(x[0], f[0]) + Cross2(x[1], f[1]) + t[0] + t[1], 0.0, 1e-14 * magnitude);
  // Their proper gap is what Gaps reports, not the bounding circles' (negative) one.
  EXPECT_NEAR(collisions.Gaps(x).pair, c.gap, 1e-15);
  // Turned apart (both horizontal) they are farther than the range: no force.
  collisions.SetAngles({0.0, 0.0});
  EXPECT_EQ(collisions.Compute({Vec2(0.4, 0.5), Vec2(0.4, 0.5 + 0.05 + 0.1 + 2 * range)}, f), 0);
}

TEST(CollisionForces, AnEllipseAtAWallFeelsTheWallLawAtItsNearestPoint) {
  const Params p = CollisionScene();
  const Grid grid = p.domain.VelocityGrid();
  CollisionForces collisions(p, grid, {0.2});
  collisions.SetShapes({Shape::Ellipse(0.2, 0.05)});
  const double range = 2.0 / 32, theta = 0.4;
  const double extent = std::hypot(0.2 * std::sin(theta), 0.05 * std::cos(theta));
  const double g = range / 4;
  const std::vector<Vec2> x = {Vec2(0.5, extent + g)};
  collisions.SetAngles({theta});
  std::vector<Vec2> f(1);
  EXPECT_EQ(collisions.Compute(x, f), 1);
  const double magnitude = 2.0 * (std::sqrt(0.2 * 0.05) + g) * (range - 2.0 * g) *
                           (range - 2.0 * g) / p.collisions.wall_stiffness;
  EXPECT_NEAR((f[0] - Vec2(0.0, magnitude)).norm(), 0.0, 1e-12 * magnitude);
  // The nearest point is off the centre line, so the wall turns the ellipse: its long axis,
  // tilted up by theta, is pushed flat (clockwise, negative torque).
  const Shape ellipse = Shape::Ellipse(0.2, 0.05);
  const Contact w = WallContact({&ellipse, x[0], theta}, Vec2(0, 1), x[0].y());
  EXPECT_NEAR(collisions.Torques()[0], Cross2(w.point_a - x[0], f[0]), 1e-15 * magnitude);
  EXPECT_LT(collisions.Torques()[0], 0.0);
  EXPECT_NEAR(collisions.Gaps(x).wall, g, 1e-15);
}

TEST(CollisionForces, TwoDisksGiveTheSameBitsWithOrWithoutShapes) {
  const Params p = CollisionScene();
  const Grid grid = p.domain.VelocityGrid();
  CollisionForces plain(p, grid, {0.1, 0.1}), shaped(p, grid, {0.1, 0.1});
  shaped.SetShapes({Shape::Disk(0.1), Shape::Disk(0.1)});
  shaped.SetAngles({0.3, 1.0});
  const std::vector<Vec2> x = {Vec2(0.5, 0.5), Vec2(0.53, 0.72)};
  std::vector<Vec2> f_plain(2), f_shaped(2);
  EXPECT_EQ(plain.Compute(x, f_plain), shaped.Compute(x, f_shaped));
  EXPECT_EQ(f_plain[0], f_shaped[0]);
  EXPECT_EQ(f_plain[1], f_shaped[1]);
  EXPECT_GT(f_plain[0].norm(), 0.0);
}

}  // namespace
}  // namespace dlmfd
