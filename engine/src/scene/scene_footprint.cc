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
  double free_bodies = 0.0;
  for (const ParticleParams& q : params.particles) {
    if (cut_cell) {  // no multipliers; a moving body's responses
      if (q.motion == Motion::kFixed) continue;
      f.cut_cell_rows = Saturated(f.cut_cell_rows + kCutCellRowsPerDiameter * q.diameter / d.h +
                                  kCutCellRowsFloor);
      if (q.motion == Motion::kFree) free_bodies += 1.0;
      continue;
    }
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
  double grid_and_meshes = kBytesPerNode * (f.velocity_nodes + f.multiplier_nodes);
  if (cut_cell) {
    grid_and_meshes = (kCutCellBytesPerNode + sizeof(double) * f.cut_cell_rows +
                       kCutCellFreeBodyBytesPerNode * free_bodies) *
                      f.velocity_nodes;
  }
  f.bytes = Saturated(grid_and_meshes + recycled * f.velocity_nodes);
  return f;
}

}  // namespace dlmfd
