// The stacked ring-mesh multiplier points; see particles/multiplier_points.h.
#include "dlmfd/particles/multiplier_points.h"

namespace dlmfd {

void MultiplierPoints::Add(double radius, double mesh_size) {
  int found = -1;
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    if (meshes_[m].radius() == radius) found = static_cast<int>(m);
  }
  if (found < 0) {
    meshes_.emplace_back(radius, mesh_size);
    found = static_cast<int>(meshes_.size()) - 1;
  }
  mesh_of_.push_back(found);
  offset_.push_back(offset_.back() + meshes_[found].NodeCount());
}

double MultiplierPoints::RoundOffWeight(std::size_t p) const {
  const ParticleMesh& mesh = Mesh(p);
  const double ratio =
      mesh.radius() /
      (mesh.nodes()[mesh.NodeCount() - 1] - mesh.nodes()[mesh.NodeCount() - 2]).norm();
  return 2.0 * mesh.Area() * (1.0 + ratio * ratio);
}

}  // namespace dlmfd
