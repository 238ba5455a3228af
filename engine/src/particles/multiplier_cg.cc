// The CG of the DLM step (37) in the H1 product; see particles/multiplier_cg.h.
#include "dlmfd/particles/multiplier_cg.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "dlmfd/core/errors.h"

namespace dlmfd {

namespace {

// a . b over [begin, end) with four running sums (a fixed order: the same result every time, and
// no single chain of dependent additions), s0 and s1 in one two-lane value, s2 and s3 in another.
double Dot(const double* a, const double* b, std::size_t begin, std::size_t end) {
  ComponentPair s01 = {0.0, 0.0}, s23 = {0.0, 0.0};
  std::size_t q = begin;
  for (; q + 4 <= end; q += 4) {
    s01 += LoadPair(a + q) * LoadPair(b + q);
    s23 += LoadPair(a + q + 2) * LoadPair(b + q + 2);
  }
  double s0 = s01[0];
  for (; q < end; ++q) s0 += a[q] * b[q];
  return (s0 + s01[1]) + (s23[0] + s23[1]);
}

}  // namespace

MultiplierCg::MultiplierCg(const MultiplierPoints& points, std::size_t max_slots,
                           int max_iterations, bool preconditioned)
    : max_iterations_(max_iterations),
      preconditioned_(preconditioned),
      preconditioner_(points.ParticleCount()) {
  const std::size_t n = points.ParticleCount();
  for (auto* a : {&nu_, &g_, &w_, &nub_, &gb_, &scratch_}) a->assign(2 * points.Total(), 0.0);
  if (preconditioned) gram_g_.assign(2 * points.Total(), 0.0);
  for (auto* a : {&uvb_, &duv_}) a->assign(2 * (max_slots + 1), 0.0);
  partial_.assign(n, 0.0);
  partial_gg_.assign(n, 0.0);
  partial_rho_.assign(n, 0.0);
  parallel_ = n >= kParallelParticles;
  velocity_.assign(n, Vec2::Zero());
  velocity_b_.assign(n, Vec2::Zero());
  omega_.assign(n, 0.0);
  omega_b_.assign(n, 0.0);
}

void MultiplierCg::Start(const std::vector<ParticleState>& particles) {
  for (std::size_t p = 0; p < particles.size(); ++p) {
    velocity_[p] = particles[p].velocity;
    omega_[p] = particles[p].angular_velocity;
  }
  std::fill(nu_.begin(), nu_.end(), 0.0);
}

void MultiplierCg::MismatchOf(const ConstraintOperators& op, std::size_t p, const double* u,
                              const double* v) {
  // Locals: the stores to g could alias the members, so the compiler would read them again per
  // point (as in ResponseMismatchOf).
  const Vec2* r = op.points.Points(p).data();
  const std::size_t first = op.points.Begin(p);
  const int count = op.points.Count(p);
  const Vec2 velocity = velocity_[p];
  const double omega = omega_[p];
  double* g = g_.data();
  for (int k = 0; k < count; ++k) {
    const std::size_t node = first + k;
    double eu, ev;
    op.coupling.Interpolate(node, u, v, eu, ev);
    const Vec2 rigid = velocity + omega * RigidModes::Perp(r[k]);
    g[2 * node] = eu - rigid.x();
    g[2 * node + 1] = ev - rigid.y();
  }
}

void MultiplierCg::Mismatch(const ConstraintOperators& op, const double* u, const double* v) {
  const long particles = static_cast<long>(op.points.ParticleCount());
#pragma omp parallel for schedule(static) if (parallel_)
  for (long p = 0; p < particles; ++p) MismatchOf(op, p, u, v);
}

double MultiplierCg::MaxMismatch() const {
  double largest = 0.0;
  for (std::size_t q = 0; q < g_.size() / 2; ++q) {
    largest = std::max(largest, std::sqrt(g_[2 * q] * g_[2 * q] + g_[2 * q + 1] * g_[2 * q + 1]));
  }
  return largest;
}

void MultiplierCg::RigidResponseOf(const ConstraintOperators& op, std::size_t p, double dt,
                                   const double* dir) {
  op.modes.Response(op.points, p, dt, dir + 2 * op.points.Begin(p), velocity_b_[p], omega_b_[p]);
}

void MultiplierCg::ResponseMismatchOf(const ConstraintOperators& op, std::size_t p) {
  const MultiplierPoints& points = op.points;
  const CouplingOperator& coupling = op.coupling;
  const Vec2* r = points.Points(p).data();
  const std::size_t first = points.Begin(p);
  const int count = points.Count(p);
  // Locals: the stores to gb could alias them, so the compiler would read them again per point.
  const Vec2 velocity = velocity_b_[p];
  const double omega = omega_b_[p];
  const double* uvb = uvb_.data();
  double* gb = gb_.data();
  for (int k = 0; k < count; ++k) {
    const std::size_t node = first + k;
    double eu, ev;
    coupling.InterpolateSlots(node, uvb, eu, ev);
    const Vec2 rigid = velocity + omega * RigidModes::Perp(r[k]);
    gb[2 * node] = eu - rigid.x();
    gb[2 * node + 1] = ev - rigid.y();
  }
  if (op.modes.IsNeutral(p)) op.modes.ProjectMismatchOf(points, p, gb + 2 * first);
}

void MultiplierCg::Respond(const ConstraintOperators& op, double dt, const double* dir) {
  const long particles = static_cast<long>(op.points.ParticleCount());
#pragma omp parallel if (parallel_)
  {
#pragma omp for schedule(static) nowait
    for (long p = 0; p < particles; ++p) RigidResponseOf(op, p, dt, dir);
    op.coupling.Spread(dir, uvb_.data());
#pragma omp for schedule(static)
    for (long p = 0; p < particles; ++p) ResponseMismatchOf(op, p);
  }
}

void MultiplierCg::TakeResponse(const ConstraintOperators& op, double* u, double* v) {
  op.coupling.AddAtSlots(uvb_.data(), u, v);
  for (std::size_t p = 0; p < velocity_.size(); ++p) {
    velocity_[p] += velocity_b_[p];
    omega_[p] += omega_b_[p];
  }
}

void MultiplierCg::ApplyGram(const ConstraintOperators& op, const double* a, double* out) const {
  const long particles = static_cast<long>(op.points.ParticleCount());
  const std::size_t* offset = op.points.Offsets();
#pragma omp parallel for schedule(static) if (parallel_)
  for (long p = 0; p < particles; ++p)
    op.points.ApplyProduct(p, a + 2 * offset[p], out + 2 * offset[p]);
}

double MultiplierCg::GramDot(const ConstraintOperators& op, const double* a, const double* b) {
  const long particles = static_cast<long>(op.points.ParticleCount());
  const std::size_t* offset = op.points.Offsets();
  double* gram_b = scratch_.data();
#pragma omp parallel for schedule(static) if (parallel_)
  for (long p = 0; p < particles; ++p) {
    op.points.ApplyProduct(p, b + 2 * offset[p], gram_b + 2 * offset[p]);
    partial_[p] = Dot(a, gram_b, 2 * offset[p], 2 * offset[p + 1]);
  }
  double sum = 0.0;  // by particle in order, as in the CG
  for (long p = 0; p < particles; ++p) sum += partial_[p];
  return sum;
}

void MultiplierCg::AddParticularForces(const ConstraintOperators& op, double dt,
                                       const Vec2* net_force, const double* net_torque, double* u,
                                       double* v) {
  if (!op.modes.AnyNeutral() || net_force == nullptr) return;
  bool have_net_force = false;
  for (std::size_t p = 0; p < op.points.ParticleCount(); ++p) {
    const double torque = net_torque == nullptr ? 0.0 : net_torque[p];
    if (!op.modes.IsNeutral(p) || (net_force[p].isZero() && torque == 0.0)) continue;
    have_net_force = true;
    op.modes.ParticularForces(op.points, p, net_force[p], torque,
                              nu_.data() + 2 * op.points.Begin(p));
  }
  if (!have_net_force) return;
  Respond(op, dt, nu_.data());
  for (std::size_t q = 0; q < g_.size(); ++q) g_[q] += gb_[q];
  TakeResponse(op, u, v);
}

bool MultiplierCg::RespondToStored(const ConstraintOperators& op, double dt,
                                   const std::vector<ParticleState>& particles) {
  bool have_stored = false;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const auto& stored = particles[p].multiplier;
    const std::size_t begin = 2 * op.points.Begin(p);
    if (stored.size() == 2 * op.points.End(p) - begin) {
      std::copy(stored.begin(), stored.end(), nub_.begin() + begin);
      have_stored = true;
    } else {
      std::fill(nub_.begin() + begin, nub_.begin() + 2 * op.points.End(p), 0.0);
    }
  }
  if (!have_stored) return false;
  op.modes.ProjectForces(op.points, nub_.data());
  Respond(op, dt, nub_.data());
  return true;
}

double MultiplierCg::StoredResponseNorm2(const ConstraintOperators& op, double dt,
                                         const std::vector<ParticleState>& particles) {
  if (!RespondToStored(op, dt, particles)) return 0.0;
  return GramDot(op, gb_.data(), gb_.data());
}

bool MultiplierCg::WarmStart(const ConstraintOperators& op, double dt,
                             const std::vector<ParticleState>& particles, double* u, double* v,
                             double& gg) {
  if (!RespondToStored(op, dt, particles)) return false;
  for (std::size_t q = 0; q < g_.size(); ++q) w_[q] = g_[q] + gb_[q];
  const double warm = GramDot(op, w_.data(), w_.data());
  if (!(warm < gg)) return false;
  gg = warm;
  std::swap(g_, w_);
  for (std::size_t q = 0; q < nu_.size(); ++q) nu_[q] += nub_[q];
  TakeResponse(op, u, v);
  return true;
}

void MultiplierCg::PreconditionOf(const ConstraintOperators& op, std::size_t p, const double* r,
                                  double* z) {
  const std::size_t begin = 2 * op.points.Begin(p);
  if (preconditioned_ && preconditioner_.Factored(p)) {
    preconditioner_.ApplyOf(op.points, p, r + begin, z + begin);
  } else {
    op.points.ApplyProduct(p, r + begin, z + begin);
  }
}

void MultiplierCg::Factor(const ConstraintOperators& op, double dt) {
  if (preconditioner_.Current(op.coupling)) return;
  const long particles = static_cast<long>(op.points.ParticleCount());
#pragma omp parallel for schedule(static) if (parallel_)
  for (long p = 0; p < particles; ++p) {
    preconditioner_.BuildOf(op.points, op.coupling, op.modes, p, dt);
  }
  preconditioner_.MarkBuilt(op.coupling);
}

int MultiplierCg::Solve(const ConstraintOperators& op, double time, double dt, double threshold,
                        double& gg, double* u, double* v) {
  double rho = gg;  // <g, z>: z = G g, or K g
  if (preconditioned_) {
    Factor(op, dt);
    const long particles = static_cast<long>(op.points.ParticleCount());
    const std::size_t* offset = op.points.Offsets();
#pragma omp parallel for schedule(static) if (parallel_)
    for (long p = 0; p < particles; ++p) {
      PreconditionOf(op, p, g_.data(), nub_.data());
      partial_[p] = Dot(g_.data(), nub_.data(), 2 * offset[p], 2 * offset[p + 1]);
    }
    rho = 0.0;
    for (long p = 0; p < particles; ++p) rho += partial_[p];
  } else {
    ApplyGram(op, g_.data(), nub_.data());
  }
  // Exact already (z is free of net force and torque on a neutral particle); keeps round-off out.
  op.modes.ProjectForces(op.points, nub_.data());
  const std::size_t slots = op.coupling.SlotCount();
  std::fill(duv_.begin(), duv_.begin() + 2 * (slots + 1), 0.0);
  int it = 0;
  double curvature = 0.0;
  const bool converged_or_stopped = ConjugateGradients(op, dt, threshold, rho, gg, it, &curvature);
  op.coupling.AddAtSlots(duv_.data(), u, v);
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
  return it;
}

bool MultiplierCg::ConjugateGradients(const ConstraintOperators& op, double dt, double threshold,
                                      double rho, double& gg, int& iterations,
                                      double* curvature_out) {
  // One parallel region for the whole CG: the loops below are work-shared, and sums are per
  // particle, then over the particles in order (by every thread): the same result for every
  // thread count.
  const MultiplierPoints& points = op.points;
  const RigidModes& modes = op.modes;
  const long particles = static_cast<long>(points.ParticleCount());
  const long slots = static_cast<long>(op.coupling.SlotCount());
  const std::size_t* offset = points.Offsets();
  double* nu = nu_.data();
  double* g = g_.data();
  double* gw = nub_.data();  // the direction of nu
  double* gb = gb_.data();
  double* z = scratch_.data();      // G g, or K g
  double* gram_g = gram_g_.data();  // G g (preconditioned)
  double* partial = partial_.data();
  double* partial_gg = partial_gg_.data();
  double* partial_rho = partial_rho_.data();
  const bool preconditioned = preconditioned_;
  double* uvb = uvb_.data();
  double* duv = duv_.data();
  bool broke_down = false;
#pragma omp parallel if (parallel_)
  {
    // Every thread keeps the CG scalars itself: each sums the per-particle parts in the same order
    // and gets the same values, so the scalars need no extra barrier; the two sums alternate
    // between partial_ and partial_gg_ so that a thread still summing one is never overwritten.
    double local_gg = gg, local_rho = rho;
    int local_iterations = iterations;
    bool local_broke_down = false;
#pragma omp for schedule(static)
    for (long p = 0; p < particles; ++p) RigidResponseOf(op, p, dt, gw);
    while (local_gg > threshold && local_iterations < max_iterations_) {
      op.coupling.Spread(gw, uvb);
#pragma omp for schedule(static)
      for (long p = 0; p < particles; ++p) {
        ResponseMismatchOf(op, p);
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
      const double step = local_rho / curvature;
#pragma omp for schedule(static) nowait
      for (long p = 0; p < particles; ++p) {
        const std::size_t begin = 2 * offset[p], end = 2 * offset[p + 1];
        for (std::size_t q = begin; q < end; ++q) {
          nu[q] -= step * gw[q];
          g[q] -= step * gb[q];
        }
        PreconditionOf(op, p, g, z);
        partial_rho[p] = Dot(g, z, begin, end);
        if (preconditioned) {
          points.ApplyProduct(p, g + begin, gram_g + begin);
          partial_gg[p] = Dot(g, gram_g, begin, end);
        }
        velocity_[p] -= step * velocity_b_[p];
        omega_[p] -= step * omega_b_[p];
      }
#pragma omp for schedule(static)
      for (long q = 2; q < 2 * (slots + 1); ++q) duv[q] -= step * uvb[q];  // u and v of the slots
      double rho_new = 0.0, gg_new = 0.0;
      for (long p = 0; p < particles; ++p) rho_new += partial_rho[p];
      if (preconditioned) {
        for (long p = 0; p < particles; ++p) gg_new += partial_gg[p];
      } else {
        gg_new = rho_new;
      }
      const double beta = rho_new / local_rho;
      local_rho = rho_new;
      local_gg = gg_new;
      ++local_iterations;
#pragma omp for schedule(static)
      for (long p = 0; p < particles; ++p) {
        const std::size_t begin = 2 * offset[p], end = 2 * offset[p + 1];
        for (std::size_t q = begin; q < end; ++q) gw[q] = z[q] + beta * gw[q];
        // Exact already for a neutral particle (z is free of net force and torque); keeps
        // round-off out.
        if (modes.IsNeutral(p)) modes.ProjectForcesOf(points, p, gw + begin);
        RigidResponseOf(op, p, dt, gw);
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

void MultiplierCg::RecoverNeutralMotion(const ConstraintOperators& op, const double* u,
                                        const double* v) {
  if (!op.modes.AnyNeutral()) return;
  const std::size_t n = op.points.ParticleCount();
  for (std::size_t p = 0; p < n; ++p) {
    if (!op.modes.IsNeutral(p)) continue;
    velocity_[p].setZero();
    omega_[p] = 0.0;
  }
  Mismatch(op, u, v);
  for (std::size_t p = 0; p < n; ++p) {
    if (!op.modes.IsNeutral(p)) continue;
    const Eigen::Vector3d rigid =
        op.modes.RigidPart(op.points, p, g_.data() + 2 * op.points.Begin(p));
    velocity_[p] = Vec2(rigid[0], rigid[1]);
    omega_[p] = rigid[2];
  }
}

}  // namespace dlmfd
