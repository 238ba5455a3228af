// The coupling operators E and E^T of the DLM step (37); see particles/coupling_operator.h.
#include "dlmfd/particles/coupling_operator.h"

#include <omp.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "../mesh/macro_triangle_stencil.h"
#include "../mesh/point_location.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/side_names.h"

namespace dlmfd {

namespace {

// *target = min(*target, value), atomically.
void AtomicMin(std::uint64_t* target, std::uint64_t value) {
  std::uint64_t seen = __atomic_load_n(target, __ATOMIC_RELAXED);
  while (value < seen && !__atomic_compare_exchange_n(target, &seen, value, true, __ATOMIC_RELAXED,
                                                      __ATOMIC_RELAXED)) {}
}

}  // namespace

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
  claim_.assign(grid.NodeCount(), ~std::uint64_t(0));
  stamp_.assign(grid.NodeCount(), 0);
  slot_of_.assign(grid.NodeCount(), 0);
  spread_start_.assign(max_slots + 2, 0);
  spread_cursor_.assign(max_slots + 2, 0);
  spread_source_.assign(max_slots, 0);
  spread_weight_.assign(max_slots, 0.0);
  particle_entries_.assign(params.particles.size() + 1, 0);
  crossing_side_.assign(params.particles.size(), -1);
  inner_inverse_mass_ = InverseNodeMass(grid.nx / 2, grid.ny / 2);
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

template <class Stencil>
std::size_t CouplingOperator::SetStencil(std::size_t entry, std::size_t point,
                                         const Stencil& stencil) {
  // Each node: its index, the point, the weight and weight / mass (the nodes off the sides, nearly
  // all, share one mass; the sides' own rules only where they apply). Members in locals: the
  // stores to the entry arrays could alias them, so the compiler would read them again per node.
  constexpr int kNodes = static_cast<int>(sizeof(stencil.weight) / sizeof(stencil.weight[0]));
  const int nx = grid_.nx, ny = grid_.ny;
  const std::size_t row = std::size_t(nx) + 1;
  const double inner_mass = inner_inverse_mass_;
  std::uint32_t* node = stencil_node_.data() + entry;
  std::uint32_t* owner = stencil_point_.data() + entry;
  double* weight = stencil_weight_.data() + entry;
  double* scatter = stencil_scatter_.data() + entry;
  for (int q = 0; q < kNodes; ++q) {
    const int i = stencil.i[q], j = stencil.j[q];
    const double w = stencil.weight[q];
    node[q] = static_cast<std::uint32_t>(std::size_t(j) * row + std::size_t(i));  // Grid::Index
    owner[q] = static_cast<std::uint32_t>(point);
    weight[q] = w;
    const bool inner = i > 0 && i < nx && j > 0 && j < ny;
    scatter[q] = w * (inner ? inner_mass : InverseNodeMass(i, j));
  }
  return entry + kNodes;
}

std::size_t CouplingOperator::EntriesOf(const MultiplierPoints& points, std::size_t p) const {
  const std::size_t quadratic = static_cast<std::size_t>(points.QuadraticCount(p));
  const std::size_t linear = static_cast<std::size_t>(points.Count(p)) - quadratic;
  const std::size_t quadratic_nodes = biquadratic_ || both_diagonals_ ? 9 : 6;  // Q2, mean P2; P2
  const std::size_t linear_nodes = both_diagonals_ ? 4 : 3;                     // the mean P1; P1
  return quadratic * quadratic_nodes + linear * linear_nodes;
}

int CouplingOperator::LocateParticle(const MultiplierPoints& points, const Vec2& centre,
                                     std::size_t p) {
  const Vec2* relative = points.Points(p).data();
  const int count = points.Count(p), quadratic = points.QuadraticCount(p);
  const std::size_t first = points.Begin(p);
  std::size_t entry = particle_entries_[p];
  for (int k = 0; k < count; ++k) {
    const Vec2 y = centre + relative[k];
    int side = 0;
    const std::size_t point = first + k;
    stencil_start_[point] = entry;
    bool inside = true;
    if (k < quadratic && (biquadratic_ || both_diagonals_)) {
      kernels::Q2Stencil stencil;
      inside = biquadratic_ ? kernels::LocatePointBiquadratic(grid_, periodic_x_, periodic_y_,
                                                              y.x(), y.y(), &stencil, &side)
                            : kernels::LocatePointMeanQuadratic(grid_, periodic_x_, periodic_y_,
                                                                y.x(), y.y(), &stencil, &side);
      if (inside) entry = SetStencil(entry, point, stencil);
    } else if (k < quadratic) {
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
  const bool parallel = particles.size() >= kParallelParticles;
  int* crossing = crossing_side_.data();
#pragma omp parallel if (parallel)
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
  if (!parallel || omp_get_max_threads() < kParallelSlotsTeam) {
    NumberSlotsInOrder(dt);
    return;
  }
#pragma omp parallel num_threads(std::min(omp_get_max_threads(), kMaxTeam))
  {
    AssignSlots();
    BuildSpreading(dt);
  }
}

void CouplingOperator::NumberSlotsInOrder(double dt) {
  // The slots by first entry (a stamped node map), counting each slot's entries in the same pass
  // (count[s], zeroed when slot s is numbered), then E^T by a counting sort. Members in locals:
  // the stores to the index arrays could alias them, so the compiler would read them again per
  // entry (docs/evidence/performance.md, "A thousand particles").
  const std::uint64_t build = ++builds_;
  const std::size_t entries = entries_;
  const std::uint32_t* node_of = stencil_node_.data();
  const std::uint32_t* point_of = stencil_point_.data();
  const double* scatter = stencil_scatter_.data();
  std::uint32_t* slot_of_entry = stencil_slot_.data();
  std::uint64_t* stamp = stamp_.data();
  std::uint32_t* slot_of_node = slot_of_.data();
  std::uint32_t* touched = touched_.data();
  std::size_t* start = spread_start_.data();
  std::size_t* count = start + 1;
  std::size_t slots = 0;
  for (std::size_t e = 0; e < entries; ++e) {
    std::uint32_t slot = 0;
    if (scatter[e] != 0.0) {
      const std::uint32_t node = node_of[e];
      if (stamp[node] != build) {
        stamp[node] = build;
        slot_of_node[node] = static_cast<std::uint32_t>(++slots);
        touched[slots] = node;
        count[slots] = 0;
      }
      slot = slot_of_node[node];
      ++count[slot];
    }
    slot_of_entry[e] = slot;
  }
  slot_count_ = slots;
  start[0] = 0;
  start[1] = 0;
  for (std::size_t slot = 1; slot <= slots; ++slot) start[slot + 1] += start[slot];
  std::size_t* cursor = spread_cursor_.data();
  std::copy(start, start + slots + 2, cursor);
  std::uint32_t* source = spread_source_.data();
  double* weight = spread_weight_.data();
  for (std::size_t e = 0; e < entries; ++e) {
    const std::uint32_t slot = slot_of_entry[e];
    if (slot == 0) continue;
    const std::size_t at = cursor[slot]++;
    source[at] = point_of[e];
    weight[at] = dt * scatter[e];
  }
}

void CouplingOperator::AssignSlots() {
  // A node's slot is numbered by its first entry, in entry order (the stacked point order), as a
  // serial pass would number them: the same slots on any team. The first entry is the lowest that
  // claims the node this Build; a claim is (this Build's epoch, entry), epochs falling.
  const std::uint64_t epoch = std::uint64_t(0xffffffffu - (++builds_ & 0xffffffffu)) << 32;
  const long entries = static_cast<long>(entries_);
  const std::uint32_t* node = stencil_node_.data();
  const double* scatter = stencil_scatter_.data();
  std::uint64_t* claim = claim_.data();
#pragma omp for schedule(static)
  for (long e = 0; e < entries; ++e) {
    if (scatter[e] != 0.0) AtomicMin(claim + node[e], epoch | std::uint64_t(e));
  }
  auto first = [&](long e) {
    return scatter[e] != 0.0 && claim[node[e]] == (epoch | std::uint64_t(e));
  };
  const int team = omp_get_num_threads(), thread = omp_get_thread_num();
  const long begin = entries * thread / team, end = entries * (thread + 1) / team;
  std::size_t firsts = 0;
  for (long e = begin; e < end; ++e) firsts += first(e) ? 1 : 0;
  team_firsts_[thread + 1] = firsts;
#pragma omp barrier
#pragma omp single
  {
    team_firsts_[0] = 0;
    for (int t = 0; t < team; ++t) team_firsts_[t + 1] += team_firsts_[t];
    slot_count_ = team_firsts_[team];
  }
  std::size_t slot = team_firsts_[thread];
  for (long e = begin; e < end; ++e) {
    if (!first(e)) continue;
    slot_of_[node[e]] = static_cast<std::uint32_t>(++slot);
    touched_[slot] = node[e];
  }
#pragma omp barrier
#pragma omp for schedule(static)
  for (long e = 0; e < entries; ++e) stencil_slot_[e] = scatter[e] != 0.0 ? slot_of_[node[e]] : 0;
}

void CouplingOperator::BuildSpreading(double dt) {
  // A counting sort of the entries by slot, each slot's entries then put in entry order (the
  // stacked point order), whatever order the threads placed them in.
  const long entries = static_cast<long>(entries_);
  const long slots = static_cast<long>(slot_count_);
  std::size_t* start = spread_start_.data();
  std::size_t* cursor = spread_cursor_.data();
  std::uint32_t* source = spread_source_.data();
  const std::uint32_t* slot_of_entry = stencil_slot_.data();
#pragma omp for schedule(static)
  for (long s = 0; s <= slots + 1; ++s) start[s] = 0;
#pragma omp for schedule(static)
  for (long e = 0; e < entries; ++e) {
    if (slot_of_entry[e] != 0) __atomic_fetch_add(start + slot_of_entry[e], 1, __ATOMIC_RELAXED);
  }
  PrefixSumInRegion(start + 1, slots + 1);  // start[s] = entries of slots 1 .. s - 1
#pragma omp for schedule(static)
  for (long s = 0; s <= slots + 1; ++s) cursor[s] = start[s];
#pragma omp for schedule(static)
  for (long e = 0; e < entries; ++e) {
    if (slot_of_entry[e] == 0) continue;
    source[__atomic_fetch_add(cursor + slot_of_entry[e], 1, __ATOMIC_RELAXED)] =
        static_cast<std::uint32_t>(e);
  }
#pragma omp for schedule(static)
  for (long s = 1; s <= slots; ++s) {
    std::sort(source + start[s], source + start[s + 1]);
    for (std::size_t c = start[s]; c < start[s + 1]; ++c) {
      const std::uint32_t e = source[c];
      source[c] = stencil_point_[e];
      spread_weight_[c] = dt * stencil_scatter_[e];
    }
  }
}

void CouplingOperator::PrefixSumInRegion(std::size_t* a, long n) {
  // Each thread sums its static block, the blocks' sums are offset in thread order, then each
  // thread runs its block's prefix from its offset.
  const int team = omp_get_num_threads(), thread = omp_get_thread_num();
  const long begin = n * thread / team, end = n * (thread + 1) / team;
  std::size_t block = 0;
  for (long k = begin; k < end; ++k) block += a[k];
  team_firsts_[thread + 1] = block;
#pragma omp barrier
#pragma omp single
  {
    team_firsts_[0] = 0;
    for (int t = 0; t < team; ++t) team_firsts_[t + 1] += team_firsts_[t];
  }
  std::size_t running = team_firsts_[thread];
  for (long k = begin; k < end; ++k) {
    const std::size_t here = a[k];
    a[k] = running;
    running += here;
  }
#pragma omp barrier
}

void CouplingOperator::Spread(const double* dir, double* uv) const {
  const long slots = static_cast<long>(slot_count_);
  const std::size_t* start = spread_start_.data();
  const std::uint32_t* source = spread_source_.data();
  const double* weight = spread_weight_.data();
#pragma omp for schedule(static)
  for (long slot = 1; slot <= slots; ++slot) {
    // Two contributions a pass (the same sum in the same order, half the loop's count and branch).
    auto at = [&](std::size_t c) { return weight[c] * LoadPair(dir + 2 * std::size_t(source[c])); };
    ComponentPair sum = {0.0, 0.0};
    const std::size_t end = start[slot + 1];
    std::size_t c = start[slot];
    for (; c + 2 <= end; c += 2) {
      sum += at(c);
      sum += at(c + 1);
    }
    if (c < end) sum += at(c);
    StorePair(uv + 2 * slot, sum);
  }
}

void CouplingOperator::CopyPeriodicDuplicates(double* u, double* v) const {
  kernels::CopyPeriodicDuplicates(grid_, periodic_x_, periodic_y_, u);
  kernels::CopyPeriodicDuplicates(grid_, periodic_x_, periodic_y_, v);
}

}  // namespace dlmfd
