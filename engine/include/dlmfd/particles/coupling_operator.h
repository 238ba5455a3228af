// The coupling operators of the DLM step (37): E, the interpolation of the fluid velocity at the
// multiplier points, and its transpose E^T, the spreading of nodal forces onto the fluid nodes,
// scaled by dt M^-1.
//
// Discrete method: each point is located in the SW-NE h-mesh and E takes, by the point's rule
// (MultiplierPoints::Quadratic), either the three P1 weights of its h-triangle
// (mesh/point_location.h; method notes 2, section 1.1) or the six P2 weights of the 2h
// macro-triangle that holds it (mesh/macro_triangle_stencil.h; particle-coupling.md section 3), or
// the nine Q2 weights of its macro square (particle_mesh.interpolation = "biquadratic"); with
// domain.diagonals = "both" the P1 and P2 weights are the means over the two diagonals of the
// square (4 and 9 nodes), so E commutes with the mirrors x -> -x and y -> -y as the fluid's forms
// do; E
// is rebuilt each step from the point positions (the particle centres plus the points of a
// MultiplierPoints set, of whatever kind). M is the lumped fluid mass, rho_L h^2 times the
// trapezoid edge factors (1/2 on outflow sides); E^T only reaches fluid nodes that are unknowns
// (Dirichlet nodes keep their data: their weight / mass is 0). Layout, for a cost per CG iteration
// proportional to the points: the distinct fluid nodes that E^T reaches get compact slots 1 ..
// SlotCount() (slot 0 is a slot always zero, the target of the Dirichlet entries), a field by slot
// holds u and v side by side (one two-lane load or store per slot: particles/component_pair.h), E
// keeps for every point its stencil (3 to 9 entries from stencil_start_[q]: fluid nodes, slots and
// weights), and E^T is stored by slot (the transposed list, built by a counting sort once per step,
// each slot's contributions in increasing stacked point order), so a slot gathers its sum without
// atomics and a fluid-sized array is touched only when the response is added to u. Build locates
// the points particle by particle on the OpenMP threads (each particle's entries at a place fixed
// by the particles before it), numbers the slots by their first entries and sorts E^T by slot on
// the threads too from kParallelSlotsTeam threads on (the same slots and order on any team).
// Errors: Build throws ParticlesOverlap when a point leaves a non-periodic domain (the particle
// crosses a side).
// Not supported: grids of more than 2^32 - 1 nodes (32-bit node indices; RigidBodyConstraint
// rejects them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"
#include "dlmfd/particles/component_pair.h"
#include "dlmfd/particles/multiplier_points.h"

namespace dlmfd {

class CouplingOperator {
 public:
  CouplingOperator() = default;
  // The most entries of one point's stencil (Q2).
  static constexpr std::size_t kMaxStencil = 9;

  // Build runs on the OpenMP threads from this many particles on, and so does the multiplier CG
  // (MultiplierCg::kParallelParticles says why 32).
  static constexpr std::size_t kParallelParticles = 32;
  // Build numbers the slots and sorts E^T on the threads from this many threads on (on fewer, in
  // entry order on one thread): the threads' version takes 1.9 times the instructions (claims,
  // atomics, a sort per slot; 64 M against 33 M over 5 steps of the 102-disk bed of paper 5.4),
  // so it gains nothing on two threads (docs/evidence/performance.md, "Threads").
  static constexpr int kParallelSlotsTeam = 3;

  // For at most max_points stacked points on this grid and domain.
  CouplingOperator(const Params& params, const Grid& grid, std::size_t max_points);

  // E and E^T for the points of every particle at its position; time names the step in errors.
  // Throws ParticlesOverlap.
  void Build(double time, double dt, const MultiplierPoints& points,
             const std::vector<ParticleState>& particles);

  std::size_t SlotCount() const { return slot_count_; }  // slots 1 .. SlotCount() in use
  std::size_t MaxSlots() const { return kMaxStencil * max_points_; }

  // (eu, ev) = (E u, E v) at stacked point q; the interior points' 4-node stencils unrolled, as in
  // InterpolateSlots (the same sums in the same order).
  void Interpolate(std::size_t q, const double* u, const double* v, double& eu, double& ev) const {
    const std::size_t begin = stencil_start_[q], end = stencil_start_[q + 1];
    const double* w = stencil_weight_.data();
    const std::uint32_t* node = stencil_node_.data();
    double su = 0.0, sv = 0.0;
    auto add = [&](std::size_t e) {
      su += w[e] * u[node[e]];
      sv += w[e] * v[node[e]];
    };
    if (end - begin == 4) {
      add(begin);
      add(begin + 1);
      add(begin + 2);
      add(begin + 3);
    } else {
      for (std::size_t e = begin; e < end; ++e) add(e);
    }
    eu = su;
    ev = sv;
  }
  // The same for a field given by slot, u and v side by side (uv[2 s], uv[2 s + 1]; 0 at slot 0).
  // The 4-node stencil of the interior points (the mean P1) unrolled: the same sums in the same
  // order, without the loop's count and branch per entry.
  void InterpolateSlots(std::size_t q, const double* uv, double& eu, double& ev) const {
    const std::size_t begin = stencil_start_[q], end = stencil_start_[q + 1];
    const double* w = stencil_weight_.data();
    const std::uint32_t* slot = stencil_slot_.data();
    auto at = [&](std::size_t e) { return LoadPair(uv + 2 * std::size_t(slot[e])); };
    ComponentPair sum = {0.0, 0.0};
    if (end - begin == 4) {
      sum += w[begin] * at(begin);
      sum += w[begin + 1] * at(begin + 1);
      sum += w[begin + 2] * at(begin + 2);
      sum += w[begin + 3] * at(begin + 3);
    } else {
      for (std::size_t e = begin; e < end; ++e) sum += w[e] * at(e);
    }
    eu = sum[0];
    ev = sum[1];
  }
  // (uv[2 s], uv[2 s + 1]) = dt M^-1 E^T dir at every slot s (dir: stacked nodal forces). Inside a
  // parallel region the slots are shared between its threads (an orphaned omp for, static
  // schedule, with its closing barrier); every thread of the region must call it.
  void Spread(const double* dir, double* uv) const;
  // u += du, v += dv at the fluid nodes of the slots (duv: by slot, side by side).
  void AddAtSlots(const double* duv, double* u, double* v) const {
    for (std::size_t s = 1; s <= slot_count_; ++s) {
      u[touched_[s]] += duv[2 * s];
      v[touched_[s]] += duv[2 * s + 1];
    }
  }
  // The length of a field by slot (SlotField: both components of every slot up to MaxSlots()).
  std::size_t SlotFieldSize() const { return 2 * (MaxSlots() + 1); }
  // Periodic duplicates of the fluid nodes follow their first node.
  void CopyPeriodicDuplicates(double* u, double* v) const;

  // The entries of E, read by the preconditioner (particles/multiplier_preconditioner.h): stacked
  // point q has entries StencilBegin(q) .. StencilBegin(q + 1) - 1, each a fluid node, a slot (0:
  // a Dirichlet node) and a weight; slot s spreads to the points SpreadSource(c) with dt weight /
  // mass SpreadWeight(c), c in SpreadBegin(s) .. SpreadBegin(s + 1) - 1. Build counts the Builds.
  std::size_t StencilBegin(std::size_t q) const { return stencil_start_[q]; }
  std::uint32_t EntryNode(std::size_t e) const { return stencil_node_[e]; }
  std::uint32_t EntrySlot(std::size_t e) const { return stencil_slot_[e]; }
  double EntryWeight(std::size_t e) const { return stencil_weight_[e]; }
  std::size_t SpreadBegin(std::size_t s) const { return spread_start_[s]; }
  std::uint32_t SpreadSource(std::size_t c) const { return spread_source_[c]; }
  double SpreadWeight(std::size_t c) const { return spread_weight_[c]; }
  std::uint64_t BuildCount() const { return builds_; }

 private:
  // The number of stencil entries of particle p's points (their stencils' sizes).
  std::size_t EntriesOf(const MultiplierPoints& points, std::size_t p) const;
  // The stencils of particle p's points (at centre) from entry particle_entries_[p] on, their
  // slots left to AssignSlots; the side that a point crosses (the first one), or -1.
  int LocateParticle(const MultiplierPoints& points, const Vec2& centre, std::size_t p);
  // The slots of the entries (stencil_slot_, touched_, slot_count_). Inside a parallel region;
  // every thread of the region must call it, and BuildSpreading after it (E^T by slot).
  void AssignSlots();
  void BuildSpreading(double dt);
  // What AssignSlots and BuildSpreading give, on one thread in entry order (fewer instructions:
  // no claims, no atomics, no sort).
  void NumberSlotsInOrder(double dt);
  // a[k] = a[0] + ... + a[k - 1] for k in [0, n), on the team of the enclosing region.
  void PrefixSumInRegion(std::size_t* a, long n);
  // Sets the stencil entries from `entry` on, one per node of the stencil (its fluid node (i, j)
  // and weight) for stacked point `point`; returns the next entry.
  template <class Stencil>
  std::size_t SetStencil(std::size_t entry, std::size_t point, const Stencil& stencil);
  [[noreturn]] void ThrowCrossing(double time, const MultiplierPoints& points,
                                  const ParticleState& particle, std::size_t p, int side) const;
  // 1 / the lumped mass of fluid node (i, j), 0 at Dirichlet nodes.
  double InverseNodeMass(int i, int j) const;

  Grid grid_;
  bool periodic_x_ = false, periodic_y_ = false;
  bool biquadratic_ = false;  // particle_mesh.interpolation = biquadratic: Q2 at boundary points
  // domain.diagonals = "both": P2 and P1 are the means over both diagonals (9 and 4 nodes).
  bool both_diagonals_ = false;
  bool dirichlet_[4] = {};  // by Side
  bool neumann_[4] = {};
  double fluid_density_ = 0.0;
  double inner_inverse_mass_ = 0.0;  // InverseNodeMass of a node off the sides
  std::size_t max_points_ = 0;

  // E, entries stencil_start_[q] .. stencil_start_[q + 1] - 1 of stacked point q (3 or 6): the
  // fluid node, its compact response slot (0, a slot always zero, at Dirichlet nodes), the weight
  // and the weight / lumped node mass (0 at Dirichlet nodes).
  std::vector<std::size_t> stencil_start_;
  std::size_t entries_ = 0;
  std::vector<std::uint32_t> stencil_node_, stencil_slot_, stencil_point_;
  std::vector<double> stencil_weight_, stencil_scatter_;
  std::vector<std::size_t> particle_entries_;  // per particle: its first entry (and the total)
  std::vector<int> crossing_side_;             // per particle: the side a point crosses, or -1
  std::size_t slot_count_ = 0;
  std::vector<std::uint32_t> touched_;  // per slot: its fluid node (touched_[0] unused)
  // Per fluid node: the lowest (epoch, entry) that claimed it (AssignSlots) or the last Build that
  // gave it a slot (NumberSlotsInOrder), and its slot then.
  std::vector<std::uint64_t> claim_, stamp_;
  std::vector<std::uint32_t> slot_of_;
  std::uint64_t builds_ = 0;
  // Per thread of the team: the running counts of AssignSlots and PrefixSumInRegion.
  static constexpr int kMaxTeam = 256;
  std::size_t team_firsts_[kMaxTeam + 1] = {};
  // E^T by slot: contributions spread_start_[s] .. spread_start_[s + 1] - 1, each a stacked point
  // and dt times its scatter weight, in increasing stacked point order.
  std::vector<std::size_t> spread_start_, spread_cursor_;
  std::vector<std::uint32_t> spread_source_;
  std::vector<double> spread_weight_;
};

}  // namespace dlmfd
