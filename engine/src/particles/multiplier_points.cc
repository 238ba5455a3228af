// The stacked multiplier points (ring mesh or collocation); see particles/multiplier_points.h.
#include "dlmfd/particles/multiplier_points.h"

#include <algorithm>

#include "dlmfd/particles/particle_rules.h"

namespace dlmfd {

MultiplierPoints::MultiplierPoints(const ParticleMeshParams& mesh, double fluid_h)
    : mesh_(mesh),
      fluid_h_(fluid_h) {}

MultiplierPoints MultiplierPoints::ForScene(const Params& params) {
  MultiplierPoints points(params.particle_mesh, params.domain.h);
  for (const ParticleParams& p : params.particles) points.Add(Shape::Of(p));
  return points;
}

void MultiplierPoints::Add(const Shape& shape) {
  int found = -1;
  for (std::size_t m = 0; m < shape_.size() && !shape.TurnsWithAngle(); ++m) {
    if (shape_[m] == shape) found = static_cast<int>(m);
  }
  if (found < 0) {
    if (mesh_.kind == ParticleMeshKind::kRing) {
      RequireRingMeshShape(shape, set_of_.size());
      meshes_.emplace_back(shape.BoundingRadius(), mesh_.RingMeshSize(fluid_h_));
    } else {
      collocation_.emplace_back(shape, fluid_h_, mesh_.spacing, mesh_.interpolation);
    }
    shape_.push_back(shape);
    found = static_cast<int>(shape_.size()) - 1;
    turned_.emplace_back();
    set_angle_.push_back(0.0);
    if (shape.TurnsWithAngle()) turned_[found] = collocation_[found].points();
  }
  set_of_.push_back(found);
  offset_.push_back(offset_.back() + SetCount(found));
}

int MultiplierPoints::SetCount(std::size_t m) const {
  return mesh_.kind == ParticleMeshKind::kRing ? meshes_[m].NodeCount() : collocation_[m].Count();
}

const std::vector<Vec2>& MultiplierPoints::SetPoints(std::size_t m) const {
  if (mesh_.kind == ParticleMeshKind::kRing) return meshes_[m].nodes();
  return shape_[m].TurnsWithAngle() ? turned_[m] : collocation_[m].points();
}

bool MultiplierPoints::Turn(std::size_t p, double theta) {
  const std::size_t m = set_of_[p];
  if (!shape_[m].TurnsWithAngle() || set_angle_[m] == theta) return false;
  const std::vector<Vec2>& body = collocation_[m].points();
  for (std::size_t k = 0; k < body.size(); ++k) turned_[m][k] = Rotate(theta, body[k]);
  set_angle_[m] = theta;
  return true;
}

void MultiplierPoints::ApplySetProduct(std::size_t m, const double* in, double* out) const {
  if (mesh_.kind == ParticleMeshKind::kRing) {
    meshes_[m].ApplyGram2(in, out);
  } else {
    std::copy(in, in + 2 * collocation_[m].Count(), out);
  }
}

double MultiplierPoints::RoundOffWeight(std::size_t p) const {
  if (mesh_.kind == ParticleMeshKind::kCollocation) return 2.0 * Count(p);
  const ParticleMesh& mesh = Mesh(p);
  const double ratio =
      mesh.radius() /
      (mesh.nodes()[mesh.NodeCount() - 1] - mesh.nodes()[mesh.NodeCount() - 2]).norm();
  return 2.0 * mesh.Area() * (1.0 + ratio * ratio);
}

}  // namespace dlmfd
