// The DLM step (37) by conjugate gradients in the H1 product; see
// particles/rigid_body_constraint.h.
#include "dlmfd/particles/rigid_body_constraint.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>

#include <Eigen/LU>

#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/particles/particle_rules.h"

namespace dlmfd {

namespace {

// Relative round-off level of a converged mismatch, in units of the velocity scale.
constexpr double kRoundOffFloor = 1e-11;
// The CG runs on the OpenMP threads from this many particles on. One CG iteration costs about
// 3.5 us per particle (D = 0.2, h_p = 1/70) and has 4 barriers; with OMP_WAIT_POLICY=passive (the
// setting for shared machines) a barrier is a futex wake-up of 5-50 us, so fewer particles than
// this lose more at the barriers than they gain.
constexpr std::size_t kParallelParticles = 32;

Vec2 Perp(const Vec2& r) { return Vec2(-r.y(), r.x()); }

// a . b over [begin, end) with four running sums (a fixed order: the same result every time, and
// no single chain of dependent additions).
double Dot(const double* a, const double* b, std::size_t begin, std::size_t end) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  std::size_t q = begin;
  for (; q + 4 <= end; q += 4) {
    s0 += a[q] * b[q];
    s1 += a[q + 1] * b[q + 1];
    s2 += a[q + 2] * b[q + 2];
    s3 += a[q + 3] * b[q + 3];
  }
  for (; q < end; ++q) s0 += a[q] * b[q];
  return (s0 + s1) + (s2 + s3);
}

const char* SideName(int s) {
  static const char* const kNames[4] = {"left", "right", "bottom", "top"};
  return kNames[s];
}

}  // namespace

RigidBodyConstraint::RigidBodyConstraint(const Params& params, const Grid& grid)
    : grid_(grid),
      periodic_x_(params.domain.PeriodicX()),
      periodic_y_(params.domain.PeriodicY()),
      fluid_density_(params.fluid.density),
      tolerance_(params.solvers.multiplier_tolerance),
      max_iterations_(params.solvers.multiplier_max_iterations) {
  RequireIndexableGrid(params, grid);
  for (int s = 0; s < 4; ++s) {
    const SideType type = params.domain.sides[s].type;
    dirichlet_[s] = type == SideType::kWall || type == SideType::kVelocity;
    neumann_[s] = type == SideType::kOutflow;
  }
  const std::size_t n = params.particles.size();
  for (std::size_t p = 0; p < n; ++p) {
    const ParticleParams& pp = params.particles[p];
    const double radius = pp.Radius();
    int found = -1;
    for (std::size_t m = 0; m < meshes_.size(); ++m) {
      if (meshes_[m].radius() == radius) found = static_cast<int>(m);
    }
    if (found < 0) {
      meshes_.emplace_back(radius, params.particle_mesh.h);
      found = static_cast<int>(meshes_.size()) - 1;
    }
    mesh_of_.push_back(found);
    offset_.push_back(total_nodes_);
    total_nodes_ += meshes_[found].NodeCount();
    const double excess_mass = (pp.density - fluid_density_) * kPi * radius * radius;
    const bool free = pp.motion == Motion::kFree;
    const bool neutral = free && pp.density == fluid_density_;
    neutral_.push_back(neutral ? 1 : 0);
    any_neutral_ = any_neutral_ || neutral;
    if (free && !neutral) {
      RequireNotLighterThanLiquid(params, p);
      inv_excess_mass_.push_back(1.0 / excess_mass);
      inv_excess_inertia_.push_back(2.0 / (excess_mass * radius * radius));
    } else {
      inv_excess_mass_.push_back(0.0);
      inv_excess_inertia_.push_back(0.0);
    }
  }
  stencil_node_.assign(3 * total_nodes_, 0);
  stencil_slot_.assign(3 * total_nodes_, 0);
  stencil_weight_.assign(3 * total_nodes_, 0.0);
  stencil_scatter_.assign(3 * total_nodes_, 0.0);
  const std::size_t max_slots = 3 * total_nodes_;
  touched_.assign(max_slots + 1, 0);
  stamp_.assign(grid.NodeCount(), -1);
  slot_of_.assign(grid.NodeCount(), 0);
  spread_start_.assign(max_slots + 2, 0);
  spread_cursor_.assign(max_slots + 2, 0);
  spread_source_.assign(max_slots, 0);
  spread_weight_.assign(max_slots, 0.0);
  for (auto* a : {&nu_, &g_, &w_, &nub_, &gb_, &scratch_}) a->assign(2 * total_nodes_, 0.0);
  for (auto* a : {&ub_, &vb_, &du_, &dv_}) a->assign(max_slots + 1, 0.0);
  partial_.assign(n, 0.0);
  partial_gg_.assign(n, 0.0);
  parallel_ = n >= kParallelParticles;
  offset_.push_back(total_nodes_);  // offset_[n]: the end of the last particle
  velocity_.assign(n, Vec2::Zero());
  velocity_b_.assign(n, Vec2::Zero());
  force_sum_.assign(n, Vec2::Zero());
  omega_.assign(n, 0.0);
  omega_b_.assign(n, 0.0);
  torque_sum_.assign(n, 0.0);
  BuildRigidModes();
}

void RigidBodyConstraint::BuildRigidModes() {
  gram_rigid_.resize(meshes_.size());
  rigid_gram_inverse_.resize(meshes_.size());
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    const ParticleMesh& mesh = meshes_[m];
    const std::size_t size = 2 * static_cast<std::size_t>(mesh.NodeCount());
    std::vector<double> mode(size);
    std::vector<double>& gc = gram_rigid_[m];
    gc.assign(3 * size, 0.0);
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < mesh.NodeCount(); ++k) {
        const Vec2 r = mesh.nodes()[k];
        const Vec2 e = c == 0 ? Vec2(1.0, 0.0) : (c == 1 ? Vec2(0.0, 1.0) : Perp(r));
        mode[2 * k] = e.x();
        mode[2 * k + 1] = e.y();
      }
      mesh.ApplyGram2(mode.data(), gc.data() + c * size);
    }
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();  // C^T G C, column a = C^T (G C)_a
    for (int a = 0; a < 3; ++a) {
      for (int k = 0; k < mesh.NodeCount(); ++k) {
        const Vec2 gc_k(gc[a * size + 2 * k], gc[a * size + 2 * k + 1]);
        s(0, a) += gc_k.x();
        s(1, a) += gc_k.y();
        s(2, a) += Perp(mesh.nodes()[k]).dot(gc_k);
      }
    }
    rigid_gram_inverse_[m] = (0.5 * (s + s.transpose())).inverse();
  }
}

Eigen::Vector3d RigidBodyConstraint::RigidPart(std::size_t p, const double* a) const {
  const ParticleMesh& mesh = MeshOf(p);
  const std::size_t size = 2 * static_cast<std::size_t>(mesh.NodeCount());
  const double* gc = gram_rigid_[mesh_of_[p]].data();
  Eigen::Vector3d moments;
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (std::size_t q = 0; q < size; ++q) sum += gc[c * size + q] * a[q];
    moments[c] = sum;
  }
  return rigid_gram_inverse_[mesh_of_[p]] * moments;
}

void RigidBodyConstraint::ProjectMismatchOf(std::size_t p, double* a) const {
  const Eigen::Vector3d rigid = RigidPart(p, a);
  const ParticleMesh& mesh = MeshOf(p);
  for (int k = 0; k < mesh.NodeCount(); ++k) {
    const Vec2 motion = Vec2(rigid[0], rigid[1]) + rigid[2] * Perp(mesh.nodes()[k]);
    a[2 * k] -= motion.x();
    a[2 * k + 1] -= motion.y();
  }
}

void RigidBodyConstraint::ProjectMismatch(double* a) const {
  if (!any_neutral_) return;
  for (std::size_t p = 0; p < mesh_of_.size(); ++p) {
    if (neutral_[p]) ProjectMismatchOf(p, a + 2 * offset_[p]);
  }
}

void RigidBodyConstraint::ProjectForcesOf(std::size_t p, double* f) const {
  const ParticleMesh& mesh = MeshOf(p);
  const std::size_t size = 2 * static_cast<std::size_t>(mesh.NodeCount());
  Eigen::Vector3d moments = Eigen::Vector3d::Zero();  // C^T f
  for (int k = 0; k < mesh.NodeCount(); ++k) {
    const Vec2 force(f[2 * k], f[2 * k + 1]);
    moments += Eigen::Vector3d(force.x(), force.y(), Perp(mesh.nodes()[k]).dot(force));
  }
  const Eigen::Vector3d t = rigid_gram_inverse_[mesh_of_[p]] * moments;
  const double* gc = gram_rigid_[mesh_of_[p]].data();
  for (std::size_t q = 0; q < size; ++q) {
    f[q] -= gc[q] * t[0] + gc[size + q] * t[1] + gc[2 * size + q] * t[2];
  }
}

void RigidBodyConstraint::ProjectForces(double* f) const {
  if (!any_neutral_) return;
  for (std::size_t p = 0; p < mesh_of_.size(); ++p) {
    if (neutral_[p]) ProjectForcesOf(p, f + 2 * offset_[p]);
  }
}

double RigidBodyConstraint::InverseNodeMass(int i, int j) const {
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

void RigidBodyConstraint::BuildInterpolation(double time, double dt,
                                             const std::vector<ParticleState>& particles) {
  ++stamp_counter_;
  slot_count_ = 0;
  const double h = grid_.h;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const ParticleMesh& mesh = MeshOf(p);
    const Vec2& centre = particles[p].position;
    for (int k = 0; k < mesh.NodeCount(); ++k) {
      const Vec2 y = centre + mesh.nodes()[k];
      int cell[2];
      double local[2];
      const double s[2] = {(y.x() - grid_.x0) / h, (y.y() - grid_.y0) / h};
      const int cells[2] = {grid_.nx, grid_.ny};
      const bool periodic[2] = {periodic_x_, periodic_y_};
      for (int a = 0; a < 2; ++a) {
        int c = static_cast<int>(std::floor(s[a]));
        double t = s[a] - c;
        if (periodic[a]) {
          c = ((c % cells[a]) + cells[a]) % cells[a];
        } else if (c == cells[a] && t == 0.0) {
          c = cells[a] - 1;
          t = 1.0;
        } else if (c < 0 || c >= cells[a]) {
          const int side = 2 * a + (c < 0 ? 0 : 1);
          const double extent = a == 0 ? grid_.Width() : grid_.Height();
          const double origin = a == 0 ? grid_.x0 : grid_.y0;
          const double coordinate = a == 0 ? centre.x() : centre.y();
          const double distance = c < 0 ? coordinate - origin : origin + extent - coordinate;
          std::ostringstream what;
          what << "particle " << particles[p].id << " crosses the " << SideName(side)
               << " side at t = " << time << " (gap = " << distance - mesh.radius() << ")";
          throw ParticlesOverlap(what.str());
        }
        cell[a] = c;
        local[a] = t;
      }
      const int i0 = cell[0], j0 = cell[1];
      const int i1 = (periodic_x_ && i0 + 1 == grid_.nx) ? 0 : i0 + 1;
      const int j1 = (periodic_y_ && j0 + 1 == grid_.ny) ? 0 : j0 + 1;
      const double xi = local[0], eta = local[1];
      int ii[3], jj[3];
      double wt[3];
      if (xi >= eta) {
        ii[0] = i0;
        jj[0] = j0;
        wt[0] = 1.0 - xi;
        ii[1] = i1;
        jj[1] = j0;
        wt[1] = xi - eta;
        ii[2] = i1;
        jj[2] = j1;
        wt[2] = eta;
      } else {
        ii[0] = i0;
        jj[0] = j0;
        wt[0] = 1.0 - eta;
        ii[1] = i1;
        jj[1] = j1;
        wt[1] = xi;
        ii[2] = i0;
        jj[2] = j1;
        wt[2] = eta - xi;
      }
      for (int q = 0; q < 3; ++q) {
        const std::size_t entry = 3 * (offset_[p] + k) + q;
        const std::size_t node = grid_.Index(ii[q], jj[q]);
        const double scatter = wt[q] * InverseNodeMass(ii[q], jj[q]);
        stencil_node_[entry] = static_cast<std::uint32_t>(node);
        stencil_weight_[entry] = wt[q];
        stencil_scatter_[entry] = scatter;
        stencil_slot_[entry] = 0;
        if (scatter != 0.0) {
          if (stamp_[node] != stamp_counter_) {
            stamp_[node] = stamp_counter_;
            slot_of_[node] = static_cast<std::uint32_t>(++slot_count_);
            touched_[slot_count_] = static_cast<std::uint32_t>(node);
          }
          stencil_slot_[entry] = slot_of_[node];
        }
      }
    }
  }
  BuildSpreading(dt);
}

void RigidBodyConstraint::BuildSpreading(double dt) {
  // Counting sort of the stencil entries by slot; entries stay in stacked node order per slot.
  std::fill(spread_start_.begin(), spread_start_.begin() + slot_count_ + 2, 0);
  for (std::size_t q = 0; q < 3 * total_nodes_; ++q) {
    if (stencil_slot_[q] != 0) ++spread_start_[stencil_slot_[q] + 1];
  }
  spread_start_[1] = 0;
  for (std::size_t slot = 1; slot <= slot_count_; ++slot)
    spread_start_[slot + 1] += spread_start_[slot];
  std::copy(spread_start_.begin(), spread_start_.begin() + slot_count_ + 2, spread_cursor_.begin());
  for (std::size_t q = 0; q < 3 * total_nodes_; ++q) {
    if (stencil_slot_[q] == 0) continue;
    const std::size_t at = spread_cursor_[stencil_slot_[q]]++;
    spread_source_[at] = static_cast<std::uint32_t>(q / 3);
    spread_weight_[at] = dt * stencil_scatter_[q];
  }
}

void RigidBodyConstraint::MismatchOf(std::size_t p, const double* u, const double* v,
                                     const Vec2* velocity, const double* omega, double* g) const {
  const ParticleMesh& mesh = MeshOf(p);
  for (int k = 0; k < mesh.NodeCount(); ++k) {
    const std::size_t node = offset_[p] + k;
    const std::uint32_t* at = &stencil_node_[3 * node];
    const double* weight = &stencil_weight_[3 * node];
    double eu = 0.0, ev = 0.0;
    for (int q = 0; q < 3; ++q) {
      eu += weight[q] * u[at[q]];
      ev += weight[q] * v[at[q]];
    }
    const Vec2 rigid = velocity[p] + omega[p] * Perp(mesh.nodes()[k]);
    g[2 * node] = eu - rigid.x();
    g[2 * node + 1] = ev - rigid.y();
  }
}

void RigidBodyConstraint::Mismatch(const double* u, const double* v, const Vec2* velocity,
                                   const double* omega, double* g) const {
  const long particles = static_cast<long>(mesh_of_.size());
#pragma omp parallel for schedule(static) if (parallel_)
  for (long p = 0; p < particles; ++p) MismatchOf(p, u, v, velocity, omega, g);
}

void RigidBodyConstraint::RigidResponseOf(std::size_t p, double dt, const double* dir) {
  const ParticleMesh& mesh = MeshOf(p);
  const double* f = dir + 2 * offset_[p];
  Vec2 sum = Vec2::Zero();
  double torque = 0.0;
  for (int k = 0; k < mesh.NodeCount(); ++k) {
    const Vec2 force(f[2 * k], f[2 * k + 1]);
    sum += force;
    torque += Perp(mesh.nodes()[k]).dot(force);
  }
  velocity_b_[p] = -dt * inv_excess_mass_[p] * sum;
  omega_b_[p] = -dt * inv_excess_inertia_[p] * torque;
}

void RigidBodyConstraint::SpreadSlot(std::size_t slot, const double* dir) {
  const std::size_t* start = spread_start_.data();
  const std::uint32_t* source = spread_source_.data();
  const double* weight = spread_weight_.data();
  double su = 0.0, sv = 0.0;
  for (std::size_t c = start[slot]; c < start[slot + 1]; ++c) {
    su += weight[c] * dir[2 * source[c]];
    sv += weight[c] * dir[2 * source[c] + 1];
  }
  ub_[slot] = su;
  vb_[slot] = sv;
}

void RigidBodyConstraint::ResponseMismatchOf(std::size_t p) {
  const ParticleMesh& mesh = MeshOf(p);
  for (int k = 0; k < mesh.NodeCount(); ++k) {
    const std::size_t node = offset_[p] + k;
    const std::uint32_t* slot = &stencil_slot_[3 * node];
    const double* weight = &stencil_weight_[3 * node];
    double eu = 0.0, ev = 0.0;
    for (int q = 0; q < 3; ++q) {
      eu += weight[q] * ub_[slot[q]];
      ev += weight[q] * vb_[slot[q]];
    }
    const Vec2 rigid = velocity_b_[p] + omega_b_[p] * Perp(mesh.nodes()[k]);
    gb_[2 * node] = eu - rigid.x();
    gb_[2 * node + 1] = ev - rigid.y();
  }
  if (neutral_[p]) ProjectMismatchOf(p, gb_.data() + 2 * offset_[p]);
}

void RigidBodyConstraint::Respond(double dt, const double* dir) {
  const long particles = static_cast<long>(mesh_of_.size());
  const long slots = static_cast<long>(slot_count_);
#pragma omp parallel if (parallel_)
  {
#pragma omp for schedule(static) nowait
    for (long p = 0; p < particles; ++p) RigidResponseOf(p, dt, dir);
#pragma omp for schedule(static)
    for (long slot = 1; slot <= slots; ++slot) SpreadSlot(slot, dir);
#pragma omp for schedule(static)
    for (long p = 0; p < particles; ++p) ResponseMismatchOf(p);
  }
}

void RigidBodyConstraint::AddResponse(const double* ub, const double* vb, double* u,
                                      double* v) const {
  for (std::size_t slot = 1; slot <= slot_count_; ++slot) {
    u[touched_[slot]] += ub[slot];
    v[touched_[slot]] += vb[slot];
  }
}

void RigidBodyConstraint::ApplyGram(const double* a, double* out) const {
  const long particles = static_cast<long>(mesh_of_.size());
#pragma omp parallel for schedule(static) if (parallel_)
  for (long p = 0; p < particles; ++p)
    MeshOf(p).ApplyGram2(a + 2 * offset_[p], out + 2 * offset_[p]);
}

double RigidBodyConstraint::GramDot(const double* a, const double* b) {
  const long particles = static_cast<long>(mesh_of_.size());
  double* gram_b = scratch_.data();
#pragma omp parallel for schedule(static) if (parallel_)
  for (long p = 0; p < particles; ++p) {
    MeshOf(p).ApplyGram2(b + 2 * offset_[p], gram_b + 2 * offset_[p]);
    partial_[p] = Dot(a, gram_b, 2 * offset_[p], 2 * offset_[p + 1]);
  }
  double sum = 0.0;  // by particle in order, as in the CG
  for (long p = 0; p < particles; ++p) sum += partial_[p];
  return sum;
}

bool RigidBodyConstraint::ConjugateGradients(double dt, double threshold, double& gg,
                                             int& iterations, double* curvature_out) {
  // One parallel region for the whole CG: the loops below are work-shared, and sums are per
  // particle, then over the particles in order (by every thread): the same result for every
  // thread count.
  const long particles = static_cast<long>(mesh_of_.size());
  const long slots = static_cast<long>(slot_count_);
  const std::size_t* offset = offset_.data();
  double* nu = nu_.data();
  double* g = g_.data();
  double* w = w_.data();
  double* gw = nub_.data();  // G w
  double* gb = gb_.data();
  double* gram_g = scratch_.data();  // G g
  double* partial = partial_.data();
  double* partial_gg = partial_gg_.data();
  bool broke_down = false;
#pragma omp parallel if (parallel_)
  {
    // Every thread keeps the CG scalars itself: each sums the per-particle parts in the same order
    // and gets the same values, so the scalars need no extra barrier; the two sums alternate
    // between partial_ and partial_gg_ so that a thread still summing one is never overwritten.
    double local_gg = gg;
    int local_iterations = iterations;
    bool local_broke_down = false;
#pragma omp for schedule(static)
    for (long p = 0; p < particles; ++p) RigidResponseOf(p, dt, gw);
    while (local_gg > threshold && local_iterations < max_iterations_) {
#pragma omp for schedule(static)
      for (long slot = 1; slot <= slots; ++slot) SpreadSlot(slot, gw);
#pragma omp for schedule(static)
      for (long p = 0; p < particles; ++p) {
        ResponseMismatchOf(p);
        partial[p] = Dot(gb, gw, 2 * offset[p], 2 * offset[p + 1]);  // <gb, w>_G = gb . G w
      }
      double curvature = 0.0;
      for (long p = 0; p < particles; ++p) curvature += partial[p];
      if (!(curvature > 0.0)) {
        local_broke_down = true;
#pragma omp master
        *curvature_out = curvature;
        break;
      }
      const double step = local_gg / curvature;
#pragma omp for schedule(static) nowait
      for (long p = 0; p < particles; ++p) {
        const std::size_t begin = 2 * offset[p], end = 2 * offset[p + 1];
        for (std::size_t q = begin; q < end; ++q) {
          nu[q] -= step * gw[q];
          g[q] -= step * gb[q];
        }
        MeshOf(p).ApplyGram2(g + begin, gram_g + begin);
        partial_gg[p] = Dot(g, gram_g, begin, end);
        velocity_[p] -= step * velocity_b_[p];
        omega_[p] -= step * omega_b_[p];
      }
#pragma omp for schedule(static)
      for (long slot = 1; slot <= slots; ++slot) {
        du_[slot] -= step * ub_[slot];
        dv_[slot] -= step * vb_[slot];
      }
      double gg_new = 0.0;
      for (long p = 0; p < particles; ++p) gg_new += partial_gg[p];
      const double beta = gg_new / local_gg;
      local_gg = gg_new;
      ++local_iterations;
#pragma omp for schedule(static)
      for (long p = 0; p < particles; ++p) {
        const std::size_t begin = 2 * offset[p], end = 2 * offset[p + 1];
        for (std::size_t q = begin; q < end; ++q) {
          w[q] = g[q] + beta * w[q];
          gw[q] = gram_g[q] + beta * gw[q];
        }
        // Exact already for a neutral particle (w is G-orthogonal to C); keeps round-off out.
        if (neutral_[p]) ProjectForcesOf(p, gw + begin);
        RigidResponseOf(p, dt, gw);
      }
    }
#pragma omp master
    {
      gg = local_gg;
      iterations = local_iterations;
      broke_down = local_broke_down;
    }
  }
  return !broke_down;
}

RigidBodyConstraint::Outcome RigidBodyConstraint::Enforce(double time, double dt,
                                                          std::vector<ParticleState>& particles,
                                                          double* u, double* v) {
  return Enforce(time, dt, particles, u, v, nullptr);
}

RigidBodyConstraint::Outcome RigidBodyConstraint::Enforce(double time, double dt,
                                                          std::vector<ParticleState>& particles,
                                                          double* u, double* v,
                                                          const Vec2* net_force) {
  Outcome outcome;
  const std::size_t n = particles.size();
  if (n == 0) return outcome;
  BuildInterpolation(time, dt, particles);
  for (std::size_t p = 0; p < n; ++p) {
    velocity_[p] = particles[p].velocity;
    omega_[p] = particles[p].angular_velocity;
  }

  // Cold-start mismatch (unprojected for the report); its projection is the absolute reference of
  // the stopping rule.
  Mismatch(u, v, velocity_.data(), omega_.data(), g_.data());
  double scale = 0.0, floor_weight = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    const ParticleMesh& mesh = MeshOf(p);
    scale = std::max(scale, velocity_[p].norm() + std::abs(omega_[p]) * mesh.radius());
    const double ratio =
        mesh.radius() /
        (mesh.nodes()[mesh.NodeCount() - 1] - mesh.nodes()[mesh.NodeCount() - 2]).norm();
    floor_weight += 2.0 * mesh.Area() * (1.0 + ratio * ratio);
  }
  for (std::size_t q = 0; q < total_nodes_; ++q) {
    outcome.cold_residual = std::max(
        outcome.cold_residual, std::sqrt(g_[2 * q] * g_[2 * q] + g_[2 * q + 1] * g_[2 * q + 1]));
    scale = std::max(scale, outcome.cold_residual);
  }
  ProjectMismatch(g_.data());

  // The particular nodal forces of the neutral particles: nu_f = G C S^-1 (F', 0), C^T nu_f = F'.
  std::fill(nu_.begin(), nu_.end(), 0.0);
  bool have_net_force = false;
  if (any_neutral_ && net_force != nullptr) {
    for (std::size_t p = 0; p < n; ++p) {
      if (!neutral_[p] || net_force[p].isZero()) continue;
      have_net_force = true;
      const Eigen::Vector3d t = rigid_gram_inverse_[mesh_of_[p]] *
                                Eigen::Vector3d(net_force[p].x(), net_force[p].y(), 0.0);
      const std::size_t size = MultiplierSize(p);
      const double* gc = gram_rigid_[mesh_of_[p]].data();
      double* f = nu_.data() + 2 * offset_[p];
      for (std::size_t q = 0; q < size; ++q) {
        f[q] = gc[q] * t[0] + gc[size + q] * t[1] + gc[2 * size + q] * t[2];
      }
    }
  }
  if (have_net_force) {
    Respond(dt, nu_.data());
    for (std::size_t q = 0; q < 2 * total_nodes_; ++q) g_[q] += gb_[q];
    AddResponse(ub_.data(), vb_.data(), u, v);
    for (std::size_t p = 0; p < n; ++p) {
      velocity_[p] += velocity_b_[p];
      omega_[p] += omega_b_[p];
    }
  }
  const double cold = GramDot(g_.data(), g_.data());
  const double threshold = std::max(tolerance_ * tolerance_ * cold,
                                    kRoundOffFloor * kRoundOffFloor * scale * scale * floor_weight);

  // Warm start from the stored nodal forces when they reduce the mismatch (for a neutral particle,
  // the stored forces less their net force and torque, on top of nu_f).
  bool have_warm = false;
  for (std::size_t p = 0; p < n; ++p) {
    const auto& stored = particles[p].multiplier;
    if (stored.size() != MultiplierSize(p)) continue;
    std::copy(stored.begin(), stored.end(), nub_.begin() + 2 * offset_[p]);
    have_warm = true;
  }
  double gg = cold;
  if (have_warm && cold > threshold) {
    for (std::size_t p = 0; p < n; ++p) {
      if (particles[p].multiplier.size() != MultiplierSize(p)) {
        std::fill(nub_.begin() + 2 * offset_[p], nub_.begin() + 2 * offset_[p] + MultiplierSize(p),
                  0.0);
      }
    }
    ProjectForces(nub_.data());
    Respond(dt, nub_.data());
    for (std::size_t q = 0; q < 2 * total_nodes_; ++q) w_[q] = g_[q] + gb_[q];
    const double warm = GramDot(w_.data(), w_.data());
    if (warm < cold) {
      outcome.warm_start = true;
      gg = warm;
      std::swap(g_, w_);
      for (std::size_t q = 0; q < 2 * total_nodes_; ++q) nu_[q] += nub_[q];
      AddResponse(ub_.data(), vb_.data(), u, v);
      for (std::size_t p = 0; p < n; ++p) {
        velocity_[p] += velocity_b_[p];
        omega_[p] += omega_b_[p];
      }
    }
  }

  // Conjugate gradients in <., .>_G (method notes 1.3, steps 2-7), iterate tracked as nu = G
  // lambda.
  std::copy(g_.begin(), g_.end(), w_.begin());
  ApplyGram(w_.data(), nub_.data());
  ProjectForces(nub_.data());  // exact already (w is G-orthogonal to C); keeps round-off out
  std::fill(du_.begin(), du_.begin() + slot_count_ + 1, 0.0);
  std::fill(dv_.begin(), dv_.begin() + slot_count_ + 1, 0.0);
  int it = 0;
  double curvature = 0.0;
  const bool converged_or_stopped = ConjugateGradients(dt, threshold, gg, it, &curvature);
  AddResponse(du_.data(), dv_.data(), u, v);
  if (!converged_or_stopped) {
    std::ostringstream what;
    what << "DLM multiplier CG (37) broke down at t = " << time << " (curvature " << curvature
         << " after " << it << " iterations)";
    throw SolverNotConverged(what.str());
  }
  if (gg > threshold) {
    std::ostringstream what;
    what << "DLM multiplier CG (37) did not converge at t = " << time << " after " << it
         << " iterations: residual " << std::sqrt(gg) << " > " << std::sqrt(threshold)
         << " (raise solvers.multiplier_max_iterations or solvers.multiplier_tolerance)";
    throw SolverNotConverged(what.str());
  }
  outcome.iterations = it;

  // Periodic duplicates follow their first node.
  if (periodic_x_) {
    for (int j = 0; j <= grid_.ny; ++j) {
      u[grid_.Index(grid_.nx, j)] = u[grid_.Index(0, j)];
      v[grid_.Index(grid_.nx, j)] = v[grid_.Index(0, j)];
    }
  }
  if (periodic_y_) {
    for (int i = 0; i <= grid_.nx; ++i) {
      u[grid_.Index(i, grid_.ny)] = u[grid_.Index(i, 0)];
      v[grid_.Index(i, grid_.ny)] = v[grid_.Index(i, 0)];
    }
  }

  // Neutral particles: (U, omega) = the G-weighted rigid part of E u.
  if (any_neutral_) {
    for (std::size_t p = 0; p < n; ++p) {
      if (!neutral_[p]) continue;
      velocity_[p].setZero();
      omega_[p] = 0.0;
    }
    Mismatch(u, v, velocity_.data(), omega_.data(), g_.data());
    for (std::size_t p = 0; p < n; ++p) {
      if (!neutral_[p]) continue;
      const Eigen::Vector3d rigid = RigidPart(p, g_.data() + 2 * offset_[p]);
      velocity_[p] = Vec2(rigid[0], rigid[1]);
      omega_[p] = rigid[2];
    }
  }

  // The true residual, the new particle velocities, and the nodal force sums.
  Mismatch(u, v, velocity_.data(), omega_.data(), g_.data());
  for (std::size_t q = 0; q < total_nodes_; ++q) {
    outcome.residual = std::max(outcome.residual,
                                std::sqrt(g_[2 * q] * g_[2 * q] + g_[2 * q + 1] * g_[2 * q + 1]));
  }
  for (std::size_t p = 0; p < n; ++p) {
    ParticleState& particle = particles[p];
    if (particle.motion == Motion::kFree) {
      particle.velocity = velocity_[p];
      particle.angular_velocity = omega_[p];
    }
    const ParticleMesh& mesh = MeshOf(p);
    particle.multiplier.resize(MultiplierSize(p));  // allocates only on the first step
    Vec2 sum = Vec2::Zero();
    double torque = 0.0;
    for (int k = 0; k < mesh.NodeCount(); ++k) {
      const std::size_t node = offset_[p] + k;
      const Vec2 f(nu_[2 * node], nu_[2 * node + 1]);
      particle.multiplier[2 * k] = f.x();
      particle.multiplier[2 * k + 1] = f.y();
      sum += f;
      torque += Perp(mesh.nodes()[k]).dot(f);
    }
    force_sum_[p] = sum;
    torque_sum_[p] = torque;
  }
  return outcome;
}

}  // namespace dlmfd
