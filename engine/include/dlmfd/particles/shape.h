// The shape of a rigid particle: the geometry that the multiplier points, the mass and inertia and
// the rules read, for every kind of particle (design.md: particles rooms).
//
// A shape lives in its body frame: centred on the particle's centre X, its axes turned by the
// particle's angle theta from the domain's (x_world = X + Rot(theta) r_body). Kinds:
// - disk of radius R: the paper's particle; its geometry does not depend on theta.
// - ellipse with semi-axes a (along the body's x axis) and b (along its y axis): boundary
//   (x/a)^2 + (y/b)^2 = 1 (scene keys shape = "ellipse", semi_axes = [a, b], angle).
// Per unit length (2D), with rho_d the density: area |P| = pi a b, mass M = rho_d pi a b, moment of
// inertia about the centre I = M (a^2 + b^2) / 4 (a disk: M R^2 / 2; a disk's numbers are
// computed in the engine's historical operation order, so its runs are bit for bit unchanged).
// What a shape answers, in its body frame: Inside (strictly), SignedDistance (negative inside; for
// the ellipse Eberly's robust bisection of the closest-point equation, 2013), Support (the
// boundary point farthest along a direction, the support function a convex collision distance is
// built on), the perimeter (an ellipse's by 8-point Gauss-Legendre on 128 panels of its parameter,
// round-off accurate for a / b <= 4), and boundary points with their outward normals, equally
// spaced in arc length from the point (a, 0) (an ellipse's by inverting its arc length with
// Newton's method on the same quadrature).
// How a convex polygon would join: a kind with its vertices; Support is the farthest vertex,
// SignedDistance the distance to the nearest edge, boundary points walk the edges.
// References: Eberly, "Distance from a point to an ellipse, an ellipsoid, or a hyperellipsoid"
// (Geometric Tools, 2013); Glowinski, Pan, Hesla, Joseph, Periaux, J. Comput. Phys. 169 (2001)
// 363-426 (DLM/FD for rigid bodies of any shape).
#pragma once

#include <vector>

#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"

namespace dlmfd {

// The most elongated ellipse a scene may declare: max(a, b) / min(a, b) <= 8 (its perimeter's
// quadrature is checked there; particle_shape_test).
inline constexpr double kMaxEllipseAspect = 8.0;

// A point on the boundary, in the body frame, and the outward unit normal there.
struct BoundaryPoint {
  Vec2 position;
  Vec2 normal;
};

class Shape {
 public:
  // A disk of radius 0.1 (the default ParticleParams' diameter 0.2).
  Shape() = default;
  static Shape Disk(double radius);
  // Semi-axes a (body x) and b (body y), both > 0.
  static Shape Ellipse(double a, double b);
  // The shape a scene gives particle `p`.
  static Shape Of(const ParticleParams& p);
  // The shape of a particle's state (its kind, semi-axes and bounding radius).
  static Shape Of(const ParticleState& p);

  ShapeKind kind() const { return kind_; }
  bool IsDisk() const { return kind_ == ShapeKind::kDisk; }
  // (a, b); (R, R) for a disk.
  Vec2 SemiAxes() const { return Vec2(a_, b_); }
  // Whether turning the particle moves its boundary (false for a disk).
  bool TurnsWithAngle() const { return kind_ != ShapeKind::kDisk; }
  // The radius of the smallest circle about the centre holding the shape: max(a, b).
  double BoundingRadius() const { return a_ > b_ ? a_ : b_; }
  // pi a b.
  double Area() const;
  // The mass of the shape at this density, rho pi a b (for a disk computed as rho pi R R).
  double Mass(double density) const;
  // Its moment of inertia about the centre at this density, rho pi a b (a^2 + b^2) / 4 (a disk:
  // rho pi R^4 / 2).
  double MomentOfInertia(double density) const;
  // 1 / I for a body of this shape and mass: 4 / (mass (a^2 + b^2)) (a disk: 2 / (mass R R)).
  double InverseMomentOfInertia(double mass) const;
  // The same from 1 / mass: 4 inverse_mass / (a^2 + b^2) (a disk: 2 inverse_mass / (R R)).
  double InverseMomentFromInverseMass(double inverse_mass) const;
  double Perimeter() const;

  // Body frame: strictly inside.
  bool Inside(const Vec2& r) const;
  // Body frame: the distance to the boundary, negative inside.
  double SignedDistance(const Vec2& r) const;
  // Body frame: the boundary point nearest to r (for r at the centre of a disk, (R, 0)).
  Vec2 ClosestBoundaryPoint(const Vec2& r) const;
  // Body frame: the outward unit normal at a boundary point.
  Vec2 Normal(const Vec2& boundary_point) const;
  // Body frame: the boundary point x maximising direction . x (direction != 0).
  Vec2 Support(const Vec2& direction) const;
  // floor(Perimeter() / spacing), at least 3 (1e-9 guards a whole quotient from round-off).
  int BoundaryPointCount(double spacing) const;
  // `count` points equally spaced in arc length, the first at (a, 0), counter-clockwise.
  std::vector<BoundaryPoint> BoundaryPoints(int count) const;

  bool operator==(const Shape& other) const {
    return kind_ == other.kind_ && a_ == other.a_ && b_ == other.b_;
  }
  bool operator!=(const Shape& other) const { return !(*this == other); }

 private:
  Shape(ShapeKind kind, double a, double b)
      : kind_(kind),
        a_(a),
        b_(b) {}

  ShapeKind kind_ = ShapeKind::kDisk;
  double a_ = 0.1, b_ = 0.1;
};

// The rotation by angle theta: Rot(theta) r.
inline Vec2 Rotate(double theta, const Vec2& r) {
  const double c = std::cos(theta), s = std::sin(theta);
  return Vec2(c * r.x() - s * r.y(), s * r.x() + c * r.y());
}

}  // namespace dlmfd
