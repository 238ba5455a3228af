// The coupling operators E and E^T of the DLM step (37); see particles/coupling_operator.h.
#include "dlmfd/particles/coupling_operator.h"

#include <algorithm>
#include <sstream>
#include <string>

#include "../mesh/macro_triangle_stencil.h"
#include "../mesh/point_location.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/side_names.h"

namespace dlmfd {

CouplingOperator::CouplingOperator(const Params& params, const Grid& grid, std::size_t max_points)
    : grid_(grid),
      periodic_x_(params.domain.PeriodicX()),
      periodic_y_(params.domain.PeriodicY()),
      biquadratic_(params.particle_mesh.interpolation == BoundaryInterpolation::kBiquadratic),
      both_diagonals_(params.domain.diagonals == MeshDiagonals::kBoth),
      fluid_density_(params.fluid.density),
      max_points_(max_points) {
  for (int s = 0; s < 4; ++s) {
    const SideType type = params.domain.sides[s].type;
    dirichlet_[s] = type == SideType::kWall || type == SideType::kVelocity;
    neumann_[s] = type == SideType::kOutflow;
  }
  const std::size_t max_slots = MaxSlots();
  stencil_start_.assign(max_points + 1, 0);
  stencil_node_.assign(max_slots, 0);
  stencil_slot_.assign(max_slots, 0);
  stencil_point_.assign(max_slots, 0);
  stencil_weight_.assign(max_slots, 0.0);
  stencil_scatter_.assign(max_slots, 0.0);
  touched_.assign(max_slots + 1, 0);
  stamp_.assign(grid.NodeCount(), -1);
  slot_of_.assign(grid.NodeCount(), 0);
  spread_start_.assign(max_slots + 2, 0);
  spread_cursor_.assign(max_slots + 2, 0);
  spread_source_.assign(max_slots, 0);
  spread_weight_.assign(max_slots, 0.0);
  particle_entries_.assign(params.particles.size() + 1, 0);
  crossing_side_.assign(params.particles.size(), -1);
}

double CouplingOperator::InverseNodeMass(int i, int j) const {
  const int left = static_cast<int>(Side::kLeft), right = static_cast<int>(Side::kRight);
  const int bottom = static_cast<int>(Side::kBottom), top = static_cast<int>(Side::kTop);
  double factor = 1.0;
  if (!periodic_x_) {
    const int s = i == 0 ? left : (i == grid_.nx ? right : -1);
    if (s >= 0 && dirichlet_[s]) return 0.0;
    if (s >= 0 && neumann_[s]) factor *= 0.5;
  }
  if (!periodic_y_) {
    const int s = j == 0 ? bottom : (j == grid_.ny ? top : -1);
    if (s >= 0 && dirichlet_[s]) return 0.0;
    if (s >= 0 && neumann_[s]) factor *= 0.5;
  }
  return 1.0 / (fluid_density_ * grid_.h * grid_.h * factor);
}

void CouplingOperator::SetEntry(std::size_t entry, std::size_t point, int i, int j, double weight) {
  const std::size_t node = grid_.Index(i, j);
  stencil_point_[entry] = static_cast<std::uint32_t>(point);
  stencil_node_[entry] = static_cast<std::uint32_t>(node);
  stencil_weight_[entry] = weight;
  stencil_scatter_[entry] = weight * InverseNodeMass(i, j);
}

template <class Stencil>
std::size_t CouplingOperator::SetStencil(std::size_t entry, std::size_t point,
                                         const Stencil& stencil) {
  constexpr int kNodes = static_cast<int>(sizeof(stencil.weight) / sizeof(stencil.weight[0]));
  for (int q = 0; q < kNodes; ++q)
    SetEntry(entry + q, point, stencil.i[q], stencil.j[q], stencil.weight[q]);
  return entry + kNodes;
}

std::size_t CouplingOperator::EntriesOf(const MultiplierPoints& points, std::size_t p) const {
  std::size_t entries = 0;
  for (int k = 0; k < points.Count(p); ++k) {
    if (points.Quadratic(p, k)) {
      entries += biquadratic_ || both_diagonals_ ? 9 : 6;  // Q2 or the mean P2; P2
    } else {
      entries += both_diagonals_ ? 4 : 3;  // the mean P1; P1
    }
  }
  return entries;
}

int CouplingOperator::LocateParticle(const MultiplierPoints& points, const Vec2& centre,
                                     std::size_t p) {
  const std::vector<Vec2>& relative = points.Points(p);
  std::size_t entry = particle_entries_[p];
  for (int k = 0; k < points.Count(p); ++k) {
    const Vec2 y = centre + relative[k];
    int side = 0;
    const std::size_t point = points.Begin(p) + k;
    stencil_start_[point] = entry;
    bool inside = true;
    if (points.Quadratic(p, k) && (biquadratic_ || both_diagonals_)) {
      kernels::Q2Stencil stencil;
      inside = biquadratic_ ? kernels::LocatePointBiquadratic(grid_, periodic_x_, periodic_y_,
                                                              y.x(), y.y(), &stencil, &side)
                            : kernels::LocatePointMeanQuadratic(grid_, periodic_x_, periodic_y_,
                                                                y.x(), y.y(), &stencil, &side);
      if (inside) entry = SetStencil(entry, point, stencil);
    } else if (points.Quadratic(p, k)) {
      kernels::P2Stencil stencil;
      inside = kernels::LocatePointQuadratic(grid_, periodic_x_, periodic_y_, y.x(), y.y(),
                                             &stencil, &side);
      if (inside) entry = SetStencil(entry, point, stencil);
    } else if (both_diagonals_) {
      kernels::MeanP1Stencil stencil;
      inside =
          kernels::LocatePointMean(grid_, periodic_x_, periodic_y_, y.x(), y.y(), &stencil, &side);
      if (inside) entry = SetStencil(entry, point, stencil);
    } else {
      kernels::P1Stencil stencil;
      inside = kernels::LocatePoint(grid_, periodic_x_, periodic_y_, y.x(), y.y(), &stencil, &side);
      if (inside) entry = SetStencil(entry, point, stencil);
    }
    if (!inside) return side;
  }
  return -1;
}

void CouplingOperator::ThrowCrossing(double time, const MultiplierPoints& points,
                                     const ParticleState& particle, std::size_t p, int side) const {
  const bool low = side == 0 || side == 2;
  const bool along_x = side < 2;
  const double extent = along_x ? grid_.Width() : grid_.Height();
  const double origin = along_x ? grid_.x0 : grid_.y0;
  const double coordinate = along_x ? particle.position.x() : particle.position.y();
  const double distance = low ? coordinate - origin : origin + extent - coordinate;
  std::ostringstream what;
  what << "particle " << particle.id << " crosses the " << SideName(side) << " side at t = " << time
       << " (gap = " << distance - points.BoundingRadius(p) << ")";
  throw ParticlesOverlap(what.str());
}

void CouplingOperator::Build(double time, double dt, const MultiplierPoints& points,
                             const std::vector<ParticleState>& particles) {
  const long n = static_cast<long>(particles.size());
  if (crossing_side_.size() < particles.size()) {  // more particles than the scene's (tests)
    crossing_side_.resize(particles.size());
    particle_entries_.resize(particles.size() + 1);
  }
  int* crossing = crossing_side_.data();
#pragma omp parallel if (static_cast <std::size_t>(n) >= kParallelParticles)
  {
#pragma omp for schedule(static)
    for (long p = 0; p < n; ++p) particle_entries_[p + 1] = EntriesOf(points, p);
#pragma omp single
    for (long p = 0; p < n; ++p) particle_entries_[p + 1] += particle_entries_[p];
#pragma omp for schedule(static)
    for (long p = 0; p < n; ++p) crossing[p] = LocateParticle(points, particles[p].position, p);
  }
  for (long p = 0; p < n; ++p) {
    if (crossing[p] >= 0) ThrowCrossing(time, points, particles[p], p, crossing[p]);
  }
  entries_ = particle_entries_[n];
  stencil_start_[points.Total()] = entries_;
  AssignSlots();
  BuildSpreading(dt);
}

void CouplingOperator::AssignSlots() {
  // In entry order (the stacked point order): the same slots on any team.
  ++stamp_counter_;
  slot_count_ = 0;
  for (std::size_t entry = 0; entry < entries_; ++entry) {
    stencil_slot_[entry] = 0;
    if (stencil_scatter_[entry] == 0.0) continue;
    const std::size_t node = stencil_node_[entry];
    if (stamp_[node] != stamp_counter_) {
      stamp_[node] = stamp_counter_;
      slot_of_[node] = static_cast<std::uint32_t>(++slot_count_);
      touched_[slot_count_] = static_cast<std::uint32_t>(node);
    }
    stencil_slot_[entry] = slot_of_[node];
  }
}

void CouplingOperator::BuildSpreading(double dt) {
  // Counting sort of the stencil entries by slot; entries stay in stacked point order per slot.
  const std::size_t entries = entries_;
  std::fill(spread_start_.begin(), spread_start_.begin() + slot_count_ + 2, 0);
  for (std::size_t q = 0; q < entries; ++q) {
    if (stencil_slot_[q] != 0) ++spread_start_[stencil_slot_[q] + 1];
  }
  spread_start_[1] = 0;
  for (std::size_t slot = 1; slot <= slot_count_; ++slot)
    spread_start_[slot + 1] += spread_start_[slot];
  std::copy(spread_start_.begin(), spread_start_.begin() + slot_count_ + 2, spread_cursor_.begin());
  for (std::size_t q = 0; q < entries; ++q) {
    if (stencil_slot_[q] == 0) continue;
    const std::size_t at = spread_cursor_[stencil_slot_[q]]++;
    spread_source_[at] = stencil_point_[q];
    spread_weight_[at] = dt * stencil_scatter_[q];
  }
}

void CouplingOperator::Spread(const double* dir, double* ub, double* vb) const {
  const long slots = static_cast<long>(slot_count_);
  const std::size_t* start = spread_start_.data();
  const std::uint32_t* source = spread_source_.data();
  const double* weight = spread_weight_.data();
#pragma omp for schedule(static)
  for (long slot = 1; slot <= slots; ++slot) {
    double su = 0.0, sv = 0.0;
    for (std::size_t c = start[slot]; c < start[slot + 1]; ++c) {
      su += weight[c] * dir[2 * source[c]];
      sv += weight[c] * dir[2 * source[c] + 1];
    }
    ub[slot] = su;
    vb[slot] = sv;
  }
}

void CouplingOperator::CopyPeriodicDuplicates(double* u, double* v) const {
  kernels::CopyPeriodicDuplicates(grid_, periodic_x_, periodic_y_, u);
  kernels::CopyPeriodicDuplicates(grid_, periodic_x_, periodic_y_, v);
}

}  // namespace dlmfd
