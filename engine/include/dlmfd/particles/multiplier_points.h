// The multiplier point set of the DLM step (37): the points of every particle at which the fluid
// velocity is made rigid, stacked, with the inner product of the multiplier space.
//
// Kind: the ring mesh of each disk (particles/particle_mesh.h, method notes 2, section 1.1), one
// mesh per distinct radius, shared by the particles of that radius; the product is the H1 Gram
// matrix G = M_p + R^2 K_p of (24), per velocity component. Stacking: particle p owns the points
// Begin(p) .. End(p) - 1, and every stacked nodal array holds 2 values per point (x, y).
// Contract (what the coupling operator E, the rigid modes and the CG read, and what a second kind,
// the collocation points on the true circle, provides the same way): the stacking, the points
// relative to the particle centre (they translate with it and do not rotate), the particle radius,
// the product on one particle's block, and a round-off weight (about <1, 1>_G) for the CG's floor.
#pragma once

#include <cstddef>
#include <vector>

#include "dlmfd/core/params.h"
#include "dlmfd/particles/particle_mesh.h"

namespace dlmfd {

class MultiplierPoints {
 public:
  // Appends a particle of this radius; its ring mesh of size mesh_size is shared with the earlier
  // particles of the same radius. Throws InvalidParameter (see ParticleMesh).
  void Add(double radius, double mesh_size);

  std::size_t ParticleCount() const { return mesh_of_.size(); }
  std::size_t Total() const { return offset_.back(); }  // stacked points of all particles
  std::size_t Begin(std::size_t p) const { return offset_[p]; }
  std::size_t End(std::size_t p) const { return offset_[p + 1]; }
  // Begin(p) for p = 0 .. ParticleCount(), the last one the total.
  const std::size_t* Offsets() const { return offset_.data(); }
  int Count(std::size_t p) const { return Mesh(p).NodeCount(); }
  // The points of particle p relative to its centre.
  const std::vector<Vec2>& Points(std::size_t p) const { return Mesh(p).nodes(); }
  double Radius(std::size_t p) const { return Mesh(p).radius(); }
  const ParticleMesh& Mesh(std::size_t p) const { return meshes_[mesh_of_[p]]; }

  // The distinct meshes; particle p uses MeshAt(MeshIndex(p)).
  std::size_t MeshCount() const { return meshes_.size(); }
  int MeshIndex(std::size_t p) const { return mesh_of_[p]; }
  const ParticleMesh& MeshAt(std::size_t m) const { return meshes_[m]; }

  // out = G in on the block of particle p (in and out point at the block's first value).
  void ApplyProduct(std::size_t p, const double* in, double* out) const {
    Mesh(p).ApplyGram2(in, out);
  }
  // 2 |P| (1 + (R / s)^2), s the spacing of the outer ring: about <1, 1>_G of a unit two-component
  // field on particle p (the scale of the CG's round-off floor).
  double RoundOffWeight(std::size_t p) const;

 private:
  std::vector<ParticleMesh> meshes_;
  std::vector<int> mesh_of_;
  std::vector<std::size_t> offset_ = {0};
};

}  // namespace dlmfd
