#include "dlmfd/scene/scene_footprint.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dlmfd/core/constants.h"
#include "dlmfd/particles/recycled_directions.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

double Saturated(double x) { return std::min(x, std::numeric_limits<double>::max()); }

// The scene as it runs (Params built in code leaves "auto" choices absent).
Params Resolved(Params params) {
  ResolveDefaults(params);
  return params;
}

}  // namespace

SceneFootprint EstimateFootprint(const Params& params) {
  const DomainParams& d = params.domain;
  SceneFootprint f;
  const double nx = std::round(d.size.x() / d.h);
  const double ny = std::round(d.size.y() / d.h);
  f.velocity_nodes = Saturated((nx + 1.0) * (ny + 1.0));
  const bool collocation = params.particle_mesh.kind == ParticleMeshKind::kCollocation;
  const bool cut_cell = params.particle_mesh.kind == ParticleMeshKind::kCutCell;
  for (const ParticleParams& q : params.particles) {
    if (cut_cell) continue;  // no multipliers
    if (collocation) {
      const double r = q.Radius() / d.h;
      f.multiplier_nodes = Saturated(f.multiplier_nodes + kPi * r * r +
                                     2.0 * kPi * r / params.particle_mesh.spacing + 4.0);
      continue;
    }
    const double r = q.Radius() / params.particle_mesh.RingMeshSize(d.h);
    f.multiplier_nodes = Saturated(f.multiplier_nodes + kPi * r * (r + 2.0) + 3.0 * r + 4.0);
  }
  const double recycled = RecycledDirections::Used(Resolved(params))
                              ? RecycledDirections::kDoublesPerNode * sizeof(double)
                              : 0.0;
  f.bytes = Saturated(kBytesPerNode * (f.velocity_nodes + f.multiplier_nodes) +
                      recycled * f.velocity_nodes);
  return f;
}

}  // namespace dlmfd
