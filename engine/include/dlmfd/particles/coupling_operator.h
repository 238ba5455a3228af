// The coupling operators of the DLM step (37): E, the P1 interpolation of the fluid velocity at the
// multiplier points, and its transpose E^T, the spreading of nodal forces onto the fluid nodes,
// scaled by dt M^-1.
//
// Discrete method (method notes 2, section 1.1): each point is located in the SW-NE h-mesh
// (mesh/point_location.h: the square, the triangle, periodic wrap) and E takes the three P1 weights
// of its triangle; E is rebuilt each step from the point positions (the particle centres plus the
// points of a MultiplierPoints set, of whatever kind). M is the lumped fluid mass, rho_L h^2 times
// the trapezoid edge factors (1/2 on outflow sides); E^T only reaches fluid nodes that are unknowns
// (Dirichlet nodes keep their data: their weight / mass is 0).
// Layout, for a cost per CG iteration proportional to the points: the distinct fluid nodes that
// E^T reaches get compact slots 1 .. SlotCount() (slot 0 is a slot always zero, the target of the
// Dirichlet entries), E keeps for every point its three fluid nodes, slots and weights, and E^T is
// stored by slot (the transposed list, built by a counting sort once per step, each slot's
// contributions in increasing stacked point order), so a slot gathers its sum without atomics and a
// fluid-sized array is touched only when the response is added to u.
// Errors: Build throws ParticlesOverlap when a point leaves a non-periodic domain (the particle
// crosses a side). Not supported: grids of more than 2^32 - 1 nodes (32-bit node indices;
// RigidBodyConstraint rejects them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"
#include "dlmfd/particles/multiplier_points.h"

namespace dlmfd {

class CouplingOperator {
 public:
  CouplingOperator() = default;
  // For at most max_points stacked points on this grid and domain.
  CouplingOperator(const Params& params, const Grid& grid, std::size_t max_points);

  // E and E^T for the points of every particle at its position; time names the step in errors.
  // Throws ParticlesOverlap.
  void Build(double time, double dt, const MultiplierPoints& points,
             const std::vector<ParticleState>& particles);

  std::size_t SlotCount() const { return slot_count_; }  // slots 1 .. SlotCount() in use
  std::size_t MaxSlots() const { return 3 * max_points_; }

  // (eu, ev) = (E u, E v) at stacked point q.
  void Interpolate(std::size_t q, const double* u, const double* v, double& eu, double& ev) const {
    const std::uint32_t* at = &stencil_node_[3 * q];
    const double* weight = &stencil_weight_[3 * q];
    double su = 0.0, sv = 0.0;
    for (int k = 0; k < 3; ++k) {
      su += weight[k] * u[at[k]];
      sv += weight[k] * v[at[k]];
    }
    eu = su;
    ev = sv;
  }
  // The same for a field (ub, vb) given by slot (0 at slot 0).
  void InterpolateSlots(std::size_t q, const double* ub, const double* vb, double& eu,
                        double& ev) const {
    const std::uint32_t* slot = &stencil_slot_[3 * q];
    const double* weight = &stencil_weight_[3 * q];
    double su = 0.0, sv = 0.0;
    for (int k = 0; k < 3; ++k) {
      su += weight[k] * ub[slot[k]];
      sv += weight[k] * vb[slot[k]];
    }
    eu = su;
    ev = sv;
  }
  // (ub, vb) = dt M^-1 E^T dir at every slot (dir: stacked nodal forces). Inside a parallel
  // region the slots are shared between its threads (an orphaned omp for, static schedule, with
  // its closing barrier); every thread of the region must call it.
  void Spread(const double* dir, double* ub, double* vb) const;
  // u += du, v += dv at the fluid nodes of the slots.
  void AddAtSlots(const double* du, const double* dv, double* u, double* v) const {
    for (std::size_t s = 1; s <= slot_count_; ++s) {
      u[touched_[s]] += du[s];
      v[touched_[s]] += dv[s];
    }
  }
  // Periodic duplicates of the fluid nodes follow their first node.
  void CopyPeriodicDuplicates(double* u, double* v) const;

 private:
  void BuildSpreading(double dt);
  // 1 / the lumped mass of fluid node (i, j), 0 at Dirichlet nodes.
  double InverseNodeMass(int i, int j) const;

  Grid grid_;
  bool periodic_x_ = false, periodic_y_ = false;
  bool dirichlet_[4] = {};  // by Side
  bool neumann_[4] = {};
  double fluid_density_ = 0.0;
  std::size_t max_points_ = 0;

  // E, 3 entries per stacked point: the fluid node, its compact response slot (0, a slot always
  // zero, at Dirichlet nodes), the P1 weight and the weight / lumped node mass (0 at Dirichlet
  // nodes).
  std::vector<std::uint32_t> stencil_node_, stencil_slot_;
  std::vector<double> stencil_weight_, stencil_scatter_;
  std::size_t slot_count_ = 0;
  std::vector<std::uint32_t> touched_;  // per slot: its fluid node (touched_[0] unused)
  std::vector<long> stamp_;             // per fluid node: last step that gave it a slot
  std::vector<std::uint32_t> slot_of_;  // per fluid node: its slot in that step
  long stamp_counter_ = 0;
  // E^T by slot: contributions spread_start_[s] .. spread_start_[s + 1] - 1, each a stacked point
  // and dt times its scatter weight, in increasing stacked point order.
  std::vector<std::size_t> spread_start_, spread_cursor_;
  std::vector<std::uint32_t> spread_source_;
  std::vector<double> spread_weight_;
};

}  // namespace dlmfd
