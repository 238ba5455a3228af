// The proper distance between two rigid particles of any shape (particles/shape.h), and between a
// particle and a straight wall, with the closest points: what the collision forces (14)-(15) of a
// non-circular particle act on (particles/collision_forces.h).
//
// Pair (A at X_A turned by theta_A, B likewise): the gap g = min over the boundary of A of the
// signed distance to B. For separated convex bodies this is their distance (the nearest point
// pair has one point on each boundary); when they overlap it is minus the deepest penetration of
// A's boundary into B. Discrete method: disk-disk in closed form; a disk against any shape by the
// closest boundary point of the shape to the disk's centre (Eberly's root, Shape); two ellipses by
// the signed distance to B along A's boundary x_A(t) = X_A + Rot(theta_A) (a cos t, b sin t),
// sampled at 64 parameters and refined by golden section in the bracket of the smallest sample
// (convergence to round-off of t; the sampling finds the global minimum when the boundary's
// distance profile has no second well narrower than 2 pi / 64 of the parameter, which holds for
// the aspect ratios a scene allows, <= 8: particle_contact_test checks it against a dense search).
// The contact normal n points from B to A: B's outward normal at its closest point p_B (for
// separated bodies (p_A - p_B) / g). The contact point is the midpoint of p_A and p_B.
// Wall (a straight side with the unit normal `inward` pointing into the domain at distance `dist`
// from the centre): the particle's support point in the direction -inward is its point nearest to
// the wall, its gap dist minus the support's extent.
// References: Eberly, "Distance from a point to an ellipse" (Geometric Tools, 2013); Glowinski,
// Pan, Hesla, Joseph, Periaux, J. Comput. Phys. 169 (2001) 363-426 (collisions on the distance).
#pragma once

#include "dlmfd/core/params.h"
#include "dlmfd/particles/shape.h"

namespace dlmfd {

// A particle placed in the domain: its shape, centre and angle.
struct PlacedShape {
  const Shape* shape;
  Vec2 centre;
  double angle;
};

struct Contact {
  double gap = 0.0;       // the distance between the surfaces; negative when they overlap
  Vec2 point_a, point_b;  // the closest points on A and on B (world)
  Vec2 normal;            // unit, from B to A
};

// The contact of A and B (across periodic sides, B placed at X_A minus the minimum-image offset).
Contact PairContact(const PlacedShape& a, const PlacedShape& b);

// The contact of A with a wall: point_b the foot of point_a on the wall, normal = inward.
Contact WallContact(const PlacedShape& a, const Vec2& inward, double dist);

}  // namespace dlmfd
