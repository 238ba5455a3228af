// The size of a scene's run, estimated from its parameters before anything is allocated: the
// velocity nodes of the h-grid, the multiplier nodes of the particle meshes and the memory of
// dlmfd-solve. One estimate for everyone: the scene validation holds it against the engine's own
// limits (scene/scene_validation.h), the daemon against its configured ones.
//
// Computed in double from lengths that only have to be > 0: a tiny domain.h or particle_mesh.h
// gives a huge estimate (saturated at the largest double, so finite) that the limits reject, never
// an overflowed integer.
// Velocity nodes: (nx + 1)(ny + 1) with nx = round(width / h), ny = round(height / h).
// Multiplier nodes of a disk of radius R, r = R / h_p: the ring mesh of particles/particle_mesh.h
// has K = ceil(r) <= r + 1 rings of max(3, round(2 pi r k / K)) nodes and a centre, at most
// pi r (r + 2) + 3 r + 4 nodes. Collocation points (particles/collocation_points.h), r = R / h: at
// most floor(2 pi r / c) + 3 boundary points and pi r^2 + O(r) interior lattice points inside the
// circle less a band of sqrt(2) h, counted as pi r^2 + 2 pi r / c + 4.
// Memory: kBytesPerNode per node of either kind. Measured (max RSS, 1 and 2 threads, h = 1/96,
// 1/192, 1/288): 630 bytes per velocity node for the paper's 5.2 pair (Oldroyd-B, least-squares
// advection), 570 with the wave-like advection; a Newtonian liquid needs less, and a multiplier
// node's arrays (E, E^T, the CG vectors) well under that. The viscous coupling around fixed
// particles adds its recycled PCG directions (particles/recycled_directions.h, 288 bytes a velocity
// node).
#pragma once

#include "dlmfd/core/params.h"

namespace dlmfd {

inline constexpr double kBytesPerNode = 640.0;

struct SceneFootprint {
  double velocity_nodes = 0.0;
  double multiplier_nodes = 0.0;  // over all particles
  double bytes = 0.0;             // estimated peak memory of dlmfd-solve
};

// The estimate for `params`, whose lengths (domain.size, domain.h, diameters, particle_mesh.h)
// are > 0.
SceneFootprint EstimateFootprint(const Params& params);

}  // namespace dlmfd
