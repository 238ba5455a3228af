// The shapes of particles (particles/shape.h): area, mass and moment of inertia against quadrature,
// the perimeter against the Gauss-Kummer series, boundary points on the curve, equally
// spaced in arc length with outward unit normals, the inside test, the signed distance against a
// brute-force search, and the support point.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/particles/multiplier_points.h"
#include "dlmfd/particles/shape.h"

namespace dlmfd {
namespace {

// An ellipse's perimeter by the Gauss-Kummer series, pi (a + b) sum_n binom(1/2, n)^2 h^n with
// h = ((a - b) / (a + b))^2 (400 terms: converged to round-off for a / b <= 4, h <= 0.36).
double SeriesPerimeter(double a, double b) {
  const double h = std::pow((a - b) / (a + b), 2);
  double binomial = 1.0, power = 1.0, sum = 1.0;
  for (int n = 1; n < 400; ++n) {
    binomial *= (0.5 - (n - 1)) / n;
    power *= h;
    sum += binomial * binomial * power;
  }
  return kPi * (a + b) * sum;
}

// The distance from r to the curve x(t) = (a cos t, b sin t) by a dense search refined by golden
// section.
double BruteForceDistance(double a, double b, const Vec2& r) {
  const int n = 20000;
  double best = 1e300;
  int best_k = 0;
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * kPi * k / n;
    const double d = (Vec2(a * std::cos(t), b * std::sin(t)) - r).norm();
    if (d < best) {
      best = d;
      best_k = k;
    }
  }
  double lo = 2.0 * kPi * (best_k - 1) / n, hi = 2.0 * kPi * (best_k + 1) / n;
  auto f = [&](double t) { return (Vec2(a * std::cos(t), b * std::sin(t)) - r).norm(); };
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 200; ++it) {
    const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    if (f(x1) < f(x2)) {
      hi = x2;
    } else {
      lo = x1;
    }
  }
  return f(0.5 * (lo + hi));
}

TEST(Shape, DiskMassInertiaAndPointsAreTheCircles) {
  const double r = 0.1;
  const Shape disk = Shape::Disk(r);
  EXPECT_TRUE(disk.IsDisk());
  EXPECT_FALSE(disk.TurnsWithAngle());
  EXPECT_DOUBLE_EQ(disk.Area(), kPi * r * r);
  // The operation order of the engine's disks before the shape existed (bit for bit).
  EXPECT_EQ(disk.Mass(0.01), 0.01 * kPi * r * r);
  EXPECT_EQ(disk.MomentOfInertia(1.5), 0.5 * 1.5 * kPi * std::pow(r, 4));
  EXPECT_EQ(disk.InverseMomentOfInertia(0.3), 2.0 / (0.3 * r * r));
  EXPECT_EQ(disk.InverseMomentFromInverseMass(3.0), 2.0 * 3.0 / (r * r));
  EXPECT_EQ(disk.Perimeter(), 2.0 * kPi * r);
  EXPECT_EQ(disk.BoundaryPointCount(2.0 / 48), 15);
  const std::vector<BoundaryPoint> points = disk.BoundaryPoints(15);
  for (int k = 0; k < 15; ++k) {
    const double angle = 2.0 * kPi * k / 15;
    EXPECT_EQ(points[k].position.x(), r * std::cos(angle));
    EXPECT_EQ(points[k].position.y(), r * std::sin(angle));
    EXPECT_NEAR((points[k].normal - points[k].position / r).norm(), 0.0, 1e-15);
  }
  EXPECT_TRUE(disk.Inside(Vec2(0.07, 0.07)));
  EXPECT_FALSE(disk.Inside(Vec2(0.08, 0.07)));
  EXPECT_DOUBLE_EQ(disk.SignedDistance(Vec2(0.3, 0.4)), 0.4);
  EXPECT_NEAR((disk.Support(Vec2(3.0, 4.0)) - Vec2(0.06, 0.08)).norm(), 0.0, 1e-16);
  EXPECT_THROW(Shape::Disk(0.0), InvalidParameter);
}

TEST(Shape, EllipseAreaMassAndInertiaMatchQuadrature) {
  const double a = 0.3, b = 0.1, rho = 1.2;
  const Shape e = Shape::Ellipse(a, b);
  EXPECT_FALSE(e.IsDisk());
  EXPECT_TRUE(e.TurnsWithAngle());
  EXPECT_DOUBLE_EQ(e.BoundingRadius(), a);
  // Midpoint rule over a fine lattice: area and polar moment to about 1e-4 (the lattice's
  // boundary error).
  const int n = 1200;
  const double dx = 2 * a / n, dy = 2 * b / n;
  double area = 0.0, moment = 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Vec2 r(-a + (i + 0.5) * dx, -b + (j + 0.5) * dy);
      if (!e.Inside(r)) continue;
      area += dx * dy;
      moment += r.squaredNorm() * dx * dy;
    }
  }
  EXPECT_NEAR(area / e.Area() - 1.0, 0.0, 1e-4);
  EXPECT_NEAR(rho * moment / e.MomentOfInertia(rho) - 1.0, 0.0, 1e-4);
  EXPECT_DOUBLE_EQ(e.Mass(rho), rho * kPi * a * b);
  EXPECT_DOUBLE_EQ(e.MomentOfInertia(rho), e.Mass(rho) * (a * a + b * b) / 4.0);
  EXPECT_DOUBLE_EQ(e.InverseMomentOfInertia(e.Mass(rho)), 1.0 / e.MomentOfInertia(rho));
  EXPECT_DOUBLE_EQ(e.InverseMomentFromInverseMass(1.0 / e.Mass(rho)), 1.0 / e.MomentOfInertia(rho));
  EXPECT_THROW(Shape::Ellipse(0.1, -0.1), InvalidParameter);
}

TEST(Shape, EllipsePointsAreEquallySpacedOnTheCurveWithOutwardNormals) {
  for (const auto& [a, b] : {std::pair{0.2, 0.1}, std::pair{0.1, 0.4}, std::pair{0.5, 0.125}}) {
    const Shape e = Shape::Ellipse(a, b);
    EXPECT_NEAR(e.Perimeter() / SeriesPerimeter(a, b) - 1.0, 0.0, 1e-13);
    const int count = 57;
    const std::vector<BoundaryPoint> points = e.BoundaryPoints(count);
    ASSERT_EQ(points.size(), 57u);
    EXPECT_NEAR((points[0].position - Vec2(a, 0.0)).norm(), 0.0, 1e-15);
    // The arc between consecutive points (fine midpoint rule on the polyline between them along
    // the curve's parameter) is the perimeter over the count.
    std::vector<double> t(count);
    for (int k = 0; k < count; ++k) {
      const Vec2 p = points[k].position;
      EXPECT_NEAR(std::pow(p.x() / a, 2) + std::pow(p.y() / b, 2), 1.0, 1e-13);
      EXPECT_NEAR(points[k].normal.norm(), 1.0, 1e-14);
      const Vec2 tangent(-p.y() * a / b, p.x() * b / a);  // d/dt of (a cos t, b sin t)
      EXPECT_NEAR(points[k].normal.dot(tangent), 0.0, 1e-14);
      EXPECT_GT(points[k].normal.dot(p), 0.0);
      t[k] = std::atan2(p.y() / b, p.x() / a);
      if (t[k] < 0.0) t[k] += 2.0 * kPi;
    }
    for (int k = 0; k < count; ++k) {
      const double t0 = t[k], t1 = k + 1 < count ? t[k + 1] : 2.0 * kPi;
      ASSERT_GT(t1, t0);
      double arc = 0.0;
      const int m = 4000;
      for (int i = 0; i < m; ++i) {
        const double s = t0 + (t1 - t0) * (i + 0.5) / m;
        arc += std::hypot(a * std::sin(s), b * std::cos(s)) * (t1 - t0) / m;
      }
      EXPECT_NEAR(arc * count / e.Perimeter(), 1.0, 1e-6) << "a " << a << " b " << b << " k " << k;
    }
  }
}

TEST(Shape, EllipseSignedDistanceMatchesABruteForceSearch) {
  for (const auto& [a, b] : {std::pair{0.3, 0.1}, std::pair{0.1, 0.25}}) {
    const Shape e = Shape::Ellipse(a, b);
    for (int n = 0; n < 300; ++n) {
      const Vec2 r(0.8 * (std::fmod(0.6180339887 * n, 1.0) - 0.5),
                   0.8 * (std::fmod(0.7548776662 * n + 0.3, 1.0) - 0.5));
      const double d = e.SignedDistance(r);
      EXPECT_NEAR(std::abs(d), BruteForceDistance(a, b, r), 1e-10) << r.transpose();
      EXPECT_EQ(d < 0.0, e.Inside(r));
    }
    // On the axes, inside and out.
    EXPECT_NEAR(e.SignedDistance(Vec2(0.0, 0.0)), -std::min(a, b), 1e-15);
    EXPECT_NEAR(e.SignedDistance(Vec2(a + 0.05, 0.0)), 0.05, 1e-15);
    EXPECT_NEAR(e.SignedDistance(Vec2(0.0, -b - 0.02)), 0.02, 1e-15);
  }
}

TEST(Shape, EllipseSupportIsTheFarthestBoundaryPoint) {
  const Shape e = Shape::Ellipse(0.3, 0.1);
  const std::vector<BoundaryPoint> points = e.BoundaryPoints(2000);
  for (int n = 0; n < 64; ++n) {
    const double angle = 2.0 * kPi * (n + 0.3) / 64;
    const Vec2 d(3.0 * std::cos(angle), 3.0 * std::sin(angle));
    const Vec2 s = e.Support(d);
    EXPECT_NEAR(std::pow(s.x() / 0.3, 2) + std::pow(s.y() / 0.1, 2), 1.0, 1e-14);
    for (const BoundaryPoint& p : points) EXPECT_LE(d.dot(p.position), d.dot(s) + 1e-14);
  }
}

TEST(Shape, MultiplierPointsOfAnEllipseLieOnItAndTheRingMeshRefusesIt) {
  ParticleMeshParams mesh;
  mesh.kind = ParticleMeshKind::kCollocation;
  const double h = 1.0 / 64;
  MultiplierPoints points(mesh, h);
  const Shape e = Shape::Ellipse(0.2, 0.05);
  points.Add(Shape::Disk(0.1));
  points.Add(e);
  points.Add(Shape::Disk(0.1));
  EXPECT_EQ(points.SetCount(), 2u);  // one set per distinct shape
  EXPECT_EQ(points.SetIndex(2), 0);
  EXPECT_DOUBLE_EQ(points.BoundingRadius(1), 0.2);
  const int boundary = e.BoundaryPointCount(mesh.spacing * h);
  ASSERT_GT(points.Count(1), boundary);
  for (int k = 0; k < points.Count(1); ++k) {
    const double d = e.SignedDistance(points.Points(1)[k]);
    if (k < boundary) {
      EXPECT_NEAR(d, 0.0, 1e-14);
    } else {
      EXPECT_LT(d, 0.0);
    }
  }
  ParticleMeshParams ring_mesh;
  ring_mesh.kind = ParticleMeshKind::kRing;  // not the default since issue 32
  MultiplierPoints ring(ring_mesh, h);
  ring.Add(Shape::Disk(0.1));
  try {
    ring.Add(e);
    FAIL() << "the ring mesh took an ellipse";
  } catch (const InvalidParameter& error) {
    EXPECT_EQ(error.key(), "particle_mesh.kind");
  }
}

}  // namespace
}  // namespace dlmfd
