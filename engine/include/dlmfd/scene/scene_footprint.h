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
// Cut cells (particle_mesh.kind = "cut_cell"; docs/evidence/cut_cell_boundary.md, "The memory of a
// cut-cell run"): no multipliers, but the assembled cut-cell forms and their reduced rows,
// kCutCellBytesPerNode a velocity node in all (measured 2.4-2.7 KB with fixed bodies, 3.0-3.4
// with moving ones; since the recut in place 1.7 KB on SolveMemory's fixed disk, 2.35-2.7 on its
// towed and free ones, which 3,500 held to 1.14-2.04 times and 3,200 holds to 1.09-1.86); a moving
// body (prescribed or free) also holds the fast solver's response to each of its capacitance rows,
// a node array each (particles/cut_cell_capacitance.h: 8 bytes a node a row; where the responses
// are local also their entries, at most n / 8 of 12 bytes, which the velocity block's rows a moving
// body no longer builds outweigh: the 5.2 pair at h = 1/48 peaks at 211 MB against 218 before,
// docs/evidence/cut_cell_boundary.md, "Where a free step's CPU goes"; since the recut in place,
// without the velocity block and the summed divergence over every node, at 183-191 MB: "The recut
// in place"), k = kCutCellRowsPerDiameter D / h + kCutCellRowsFloor rows a disk (measured
// 11.1-11.25 D/h from D/h = 9.6 to 28.8, 64 at 4.8); a free body its three unit solves (velocity
// and pressure, particles/cut_cell_free_bodies.h). So a moving disk's memory grows as (D/h) h^-2:
// at D/h = 19.2 in Faxen's 1 x 8 channel (74,590 nodes) a free disk holds 129 MB of responses.
#pragma once

#include "dlmfd/core/params.h"

namespace dlmfd {

inline constexpr double kBytesPerNode = 640.0;
inline constexpr double kCutCellBytesPerNode = 3200.0;
inline constexpr double kCutCellRowsPerDiameter = 11.25;  // capacitance rows a moving disk, per D/h
inline constexpr double kCutCellRowsFloor = 10.0;
inline constexpr double kCutCellFreeBodyBytesPerNode = 3.0 * 2.25 * 8.0;  // 3 unit solves (u, v, p)

struct SceneFootprint {
  double velocity_nodes = 0.0;
  double multiplier_nodes = 0.0;  // over all particles
  double cut_cell_rows = 0.0;     // capacitance rows of the moving cut bodies (a node array each)
  double bytes = 0.0;             // estimated peak memory of dlmfd-solve
};

// The estimate for `params`, whose lengths (domain.size, domain.h, diameters, particle_mesh.h)
// are > 0.
SceneFootprint EstimateFootprint(const Params& params);

}  // namespace dlmfd
