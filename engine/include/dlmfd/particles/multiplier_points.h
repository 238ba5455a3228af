// The multiplier point set of the DLM step (37): the points of every particle at which the fluid
// velocity is made rigid, stacked, with the inner product of the multiplier space.
//
// Kinds (particle_mesh.kind):
// - ring: the ring mesh of each disk (particles/particle_mesh.h, method notes 2, section 1.1); the
//   product is the H1 Gram matrix G = M_p + R^2 K_p of (24), per velocity component; E is P1.
// - collocation: points on the true boundary of the particle's shape plus interior lattice points
//   (particles/collocation_points.h, particle-coupling.md section 3); the product is Euclidean
//   (G = I); E is quadratic (P2 macro-triangle) or linear at the boundary points, P1 inside.
// One point set per distinct shape (particles/shape.h), shared by the particles of that shape;
// a shape that turns with its particle (an ellipse) has a set of its own per particle, its points
// the body-frame points turned by the particle's angle theta (Turn: r = Rot(theta) r_body).
// Stacking: particle p owns the points Begin(p) .. End(p) - 1, and every stacked nodal array holds
// 2 values per point (x, y).
// Contract (what the coupling operator E, the rigid modes and the CG read): the stacking, the
// points relative to the particle centre (they translate with it; a disk's do not rotate, an
// ellipse's turn with it), the
// interpolation rule of each point, the particle's shape, the product on one particle's block, and
// a round-off weight (about <1, 1>_G) for the CG's floor.
#pragma once

#include <cstddef>
#include <vector>

#include "dlmfd/core/params.h"
#include "dlmfd/particles/collocation_points.h"
#include "dlmfd/particles/particle_mesh.h"
#include "dlmfd/particles/shape.h"

namespace dlmfd {

class MultiplierPoints {
 public:
  MultiplierPoints() = default;
  // A set of this kind; fluid_h (domain.h) sizes the collocation points.
  MultiplierPoints(const ParticleMeshParams& mesh, double fluid_h);
  // The points of every particle of params, in order.
  static MultiplierPoints ForScene(const Params& params);

  // Appends a particle of this shape; its point set is shared with the earlier particles of the
  // same shape. Throws InvalidParameter (see ParticleMesh, CollocationPoints; the ring mesh is a
  // disk's only).
  void Add(const Shape& shape);
  // Turns the points of particle p to the angle theta (r = Rot(theta) r_body); returns whether they
  // moved (never for a disk, nor when theta is the angle they already have).
  bool Turn(std::size_t p, double theta);
  // Whether particle p's points turn with it (its own set, an ellipse's).
  bool Turns(std::size_t p) const { return ShapeOf(p).TurnsWithAngle(); }

  ParticleMeshKind Kind() const { return mesh_.kind; }
  std::size_t ParticleCount() const { return set_of_.size(); }
  std::size_t Total() const { return offset_.back(); }  // stacked points of all particles
  std::size_t Begin(std::size_t p) const { return offset_[p]; }
  std::size_t End(std::size_t p) const { return offset_[p + 1]; }
  // Begin(p) for p = 0 .. ParticleCount(), the last one the total.
  const std::size_t* Offsets() const { return offset_.data(); }
  int Count(std::size_t p) const { return SetCount(set_of_[p]); }
  // The points of particle p relative to its centre.
  const std::vector<Vec2>& Points(std::size_t p) const { return SetPoints(set_of_[p]); }
  const Shape& ShapeOf(std::size_t p) const { return shape_[set_of_[p]]; }
  // The radius of the smallest circle about the centre that holds particle p.
  double BoundingRadius(std::size_t p) const { return ShapeOf(p).BoundingRadius(); }
  // True when E evaluates point k of particle p by the quadratic (P2 macro-triangle) stencil.
  bool Quadratic(std::size_t p, int k) const {
    return mesh_.kind == ParticleMeshKind::kCollocation && collocation_[set_of_[p]].Quadratic(k);
  }
  // The quadratic points of particle p are its first QuadraticCount(p) (the boundary points come
  // first): Quadratic(p, k) is k < QuadraticCount(p).
  int QuadraticCount(std::size_t p) const {
    if (mesh_.kind != ParticleMeshKind::kCollocation) return 0;
    const CollocationPoints& set = collocation_[set_of_[p]];
    return set.Quadratic(0) ? set.BoundaryCount() : 0;
  }
  // The ring mesh of particle p (ring kind only).
  const ParticleMesh& Mesh(std::size_t p) const { return meshes_[set_of_[p]]; }

  // The distinct point sets; particle p uses set SetIndex(p).
  std::size_t SetCount() const { return shape_.size(); }
  int SetIndex(std::size_t p) const { return set_of_[p]; }
  int SetCount(std::size_t m) const;
  const std::vector<Vec2>& SetPoints(std::size_t m) const;
  // out = G in on a two-component field of set m.
  void ApplySetProduct(std::size_t m, const double* in, double* out) const;

  // out = G in on the block of particle p (in and out point at the block's first value).
  void ApplyProduct(std::size_t p, const double* in, double* out) const {
    ApplySetProduct(set_of_[p], in, out);
  }
  // About <1, 1>_G of a unit two-component field on particle p (the scale of the CG's round-off
  // floor): ring 2 |P| (1 + (R / s)^2), s the spacing of the outer ring; collocation 2 N.
  double RoundOffWeight(std::size_t p) const;

 private:
  ParticleMeshParams mesh_;
  double fluid_h_ = 0.0;
  std::vector<Shape> shape_;                    // per set
  std::vector<ParticleMesh> meshes_;            // per set, ring kind
  std::vector<CollocationPoints> collocation_;  // per set, collocation kind
  std::vector<std::vector<Vec2>> turned_;       // per set: the turned points of a turning shape
  std::vector<double> set_angle_;               // per set: the angle of turned_
  std::vector<int> set_of_;
  std::vector<std::size_t> offset_ = {0};
};

}  // namespace dlmfd
