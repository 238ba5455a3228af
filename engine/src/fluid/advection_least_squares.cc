#include "dlmfd/fluid/advection_least_squares.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dlmfd/core/errors.h"
#include "dlmfd/fluid/line_search.h"
#include "dlmfd/mesh/fem_operators.h"

namespace dlmfd {

AdvectionLeastSquares::AdvectionLeastSquares(const Grid& grid, const DomainParams& domain,
                                             const FluidParams& fluid, double beta,
                                             SteadyCorrection correction,
                                             const SolverParams& solvers,
                                             const BoundaryData& boundary_data)
    : grid_(grid),
      topo_(BoundaryTopology::ForVelocity(domain)),
      diagonals_(domain.diagonals),
      nodes_(grid_, topo_),
      rho_(fluid.density),
      nu_b_(beta * fluid.ImplicitViscosity(grid.h)),
      taylor_viscosity_(SteadyCorrectionCap(correction, fluid, grid.h)),
      tolerance_(solvers.advection_tolerance),
      max_iterations_(solvers.advection_max_iterations),
      boundary_data_(boundary_data) {
  for (int s = 0; s < 4; ++s) outflow_[s] = domain.sides[s].type == SideType::kOutflow;
  const std::size_t n = grid_.NodeCount();
  mass_.assign(n, 0.0);
  LumpedMassDiagonal(grid_, topo_, mass_.data());
  tendency_ = correction == SteadyCorrection::kTendency;
  if (tendency_) {
    tu_.assign(grid_.NodeCount(), 0.0);
    tv_.assign(grid_.NodeCount(), 0.0);
    taylor_viscosity_ = 0.0;  // backward Euler's fixed point is exact: nothing to remove
  }
  for (auto* a : {&su_,  &sv_,  &gxu_, &gyu_, &gxv_, &gyv_, &gxw_, &gyw_, &gxwv_, &gywv_, &t0u_,
                  &t0v_, &t1u_, &t1v_, &t2u_, &t2v_, &yu_,  &yv_,  &z1u_, &z1v_,  &z2u_,  &z2v_,
                  &ru_,  &rv_,  &gu_,  &gv_,  &wu_,  &wv_,  &s1_,  &s2_,  &s3_,   &s4_}) {
    a->assign(n, 0.0);
  }
}

AdvectionLeastSquares::~AdvectionLeastSquares() = default;

void AdvectionLeastSquares::BeginStep(const double* u, const double* v) {
  if (!tendency_) return;
  std::copy(u, u + tu_.size(), tu_.begin());
  std::copy(v, v + tv_.size(), tv_.begin());
  entry_set_ = true;
}

void AdvectionLeastSquares::SetReference(double dt, const double* u, const double* v) {
  if (dt != dt_) {
    dt_ = dt;
    rho_over_dt_ = rho_ / dt;
    if (nu_b_ > 0.0) {
      helmholtz_ = std::make_unique<SeparableHelmholtz>(grid_, topo_, rho_over_dt_, nu_b_, 2);
    }
  }
  std::copy(u, u + su_.size(), su_.begin());
  std::copy(v, v + sv_.size(), sv_.begin());
}

void AdvectionLeastSquares::RemoveBackwardEulerTerm(double* u, double* v) {
  const long n = static_cast<long>(mass_.size());
  double *nu = s1_.data(), *nv = s2_.data();
  const double *gxu = gxu_.data(), *gyu = gyu_.data(), *gxv = gxv_.data(), *gyv = gyv_.data();
  const double *su = su_.data(), *sv = sv_.data(), *m = mass_.data();
  GradientsOf(u, v);  // N(u, u)
#pragma omp parallel for schedule(static)
  for (long k = 0; k < n; ++k) {
    nu[k] = u[k] * gxu[k] + v[k] * gyu[k];
    nv[k] = u[k] * gxv[k] + v[k] * gyv[k];
  }
  GradientsOf(su, sv);  // N(u*, u*)
  const double* unknown = nodes_.unknown().data();
  const double dt = dt_, cap = taylor_viscosity_;
#pragma omp parallel for schedule(static)
  for (long k = 0; k < n; ++k) {
    if (unknown[k] == 0.0) continue;
    const double nsu = su[k] * gxu[k] + sv[k] * gyu[k];
    const double nsv = su[k] * gxv[k] + sv[k] * gyv[k];
    const double streamline = dt * (su[k] * su[k] + sv[k] * sv[k]);  // dt |u*|^2
    const double theta = SteadyCorrectionShare(streamline, cap);
    u[k] += theta * dt / m[k] * (nu[k] - nsu);
    v[k] += theta * dt / m[k] * (nv[k] - nsv);
  }
}

void AdvectionLeastSquares::GradientsOf(const double* u, const double* v) {
  ApplyIntegratedGradient(grid_, topo_, u, gxu_.data(), gyu_.data(), diagonals_);
  ApplyIntegratedGradient(grid_, topo_, v, gxv_.data(), gyv_.data(), diagonals_);
}

void AdvectionLeastSquares::Residual(const double* u, const double* v, double* out_u,
                                     double* out_v) {
  GradientsOf(u, v);
  ApplyStiffness(grid_, topo_, u, s1_.data());
  ApplyStiffness(grid_, topo_, v, s2_.data());
  const long n = static_cast<long>(mass_.size());
  const double *m = mass_.data(), *su = su_.data(), *sv = sv_.data(), *ku = s1_.data(),
               *kv = s2_.data(), *gxu = gxu_.data(), *gyu = gyu_.data(), *gxv = gxv_.data(),
               *gyv = gyv_.data();
  const double rdt = rho_over_dt_, rho = rho_, nub = nu_b_;
#pragma omp parallel for schedule(static)
  for (long k = 0; k < n; ++k) {
    out_u[k] = rdt * m[k] * (u[k] - su[k]) + rho * (u[k] * gxu[k] + v[k] * gyu[k]) + nub * ku[k];
    out_v[k] = rdt * m[k] * (v[k] - sv[k]) + rho * (u[k] * gxv[k] + v[k] * gyv[k]) + nub * kv[k];
  }
  if (tendency_) {
    const double *ru = tu_.data(), *rv = tv_.data();
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      out_u[k] -= rho * m[k] * ru[k];
      out_v[k] -= rho * m[k] * rv[k];
    }
  }
  nodes_.ZeroKnown(out_u);
  nodes_.ZeroKnown(out_v);
}

// T'(u) w = (rho/dt) M w + rho [N(u, w) + N(w, u)] + nu_b K w. Uses gxu_.. of u (GradientsOf(u)).
void AdvectionLeastSquares::Jacobian(const double* u, const double* v, const double* wu,
                                     const double* wv, double* out_u, double* out_v) {
  GradientsOf(u, v);
  ApplyIntegratedGradient(grid_, topo_, wu, gxw_.data(), gyw_.data(), diagonals_);
  ApplyIntegratedGradient(grid_, topo_, wv, gxwv_.data(), gywv_.data(), diagonals_);
  ApplyStiffness(grid_, topo_, wu, s1_.data());
  ApplyStiffness(grid_, topo_, wv, s2_.data());
  const long n = static_cast<long>(mass_.size());
  const double *m = mass_.data(), *ku = s1_.data(), *kv = s2_.data(), *gxu = gxu_.data(),
               *gyu = gyu_.data(), *gxv = gxv_.data(), *gyv = gyv_.data(), *gxw = gxw_.data(),
               *gyw = gyw_.data(), *gxwv = gxwv_.data(), *gywv = gywv_.data();
  const double rdt = rho_over_dt_, rho = rho_, nub = nu_b_;
#pragma omp parallel for schedule(static)
  for (long k = 0; k < n; ++k) {
    out_u[k] = rdt * m[k] * wu[k] +
               rho * (u[k] * gxw[k] + v[k] * gyw[k] + wu[k] * gxu[k] + wv[k] * gyu[k]) +
               nub * ku[k];
    out_v[k] = rdt * m[k] * wv[k] +
               rho * (u[k] * gxwv[k] + v[k] * gywv[k] + wu[k] * gxv[k] + wv[k] * gyv[k]) +
               nub * kv[k];
  }
  nodes_.ZeroKnown(out_u);
  nodes_.ZeroKnown(out_v);
}

// Adds n_c int_side z_h phi_j ds on outflow sides whose normal has a `component` part (0 = x, 1 =
// y).
void AdvectionLeastSquares::AddBoundaryTransposeTerm(const double* z, int component,
                                                     double* out) const {
  const double h6 = grid_.h / 6.0;
  for (int s = 0; s < 4; ++s) {
    if (!outflow_[s]) continue;
    const Side side = static_cast<Side>(s);
    const bool vertical = (side == Side::kLeft || side == Side::kRight);
    if ((vertical ? 0 : 1) != component) continue;
    const double sign = (side == Side::kLeft || side == Side::kBottom) ? -1.0 : 1.0;
    const int count = vertical ? grid_.ny : grid_.nx;
    const bool wraps =
        vertical ? topo_.y.low == EndKind::kPeriodic : topo_.x.low == EndKind::kPeriodic;
    auto id = [&](int k) {
      return vertical ? grid_.Index(side == Side::kLeft ? 0 : grid_.nx, k)
                      : grid_.Index(k, side == Side::kBottom ? 0 : grid_.ny);
    };
    for (int k = 0; k <= count; ++k) {
      if (wraps && k == count) continue;  // the duplicate: folded into k = 0
      double mz;
      if (k == 0 && !wraps) {
        mz = h6 * (2.0 * z[id(0)] + z[id(1)]);
      } else if (k == count) {
        mz = h6 * (2.0 * z[id(count)] + z[id(count - 1)]);
      } else {
        const int km = (k == 0) ? count - 1 : k - 1;
        mz = h6 * (4.0 * z[id(k)] + z[id(km)] + z[id(k + 1)]);
      }
      out[id(k)] += sign * mz;
    }
  }
}

// T'(u)^T y, component c = (rho/dt) M y_c + nu_b K y_c + rho [G_x^T (u y_c) + G_y^T (v y_c)]
//                          + rho sum_d y_d (G_c u_d),   with G^T z = -G z + boundary term.
void AdvectionLeastSquares::JacobianTranspose(const double* u, const double* v, const double* yu,
                                              const double* yv, double* out_u, double* out_v) {
  GradientsOf(u, v);
  const long n = static_cast<long>(mass_.size());
  const double* m = mass_.data();
  const double rdt = rho_over_dt_, rho = rho_, nub = nu_b_;
  // Scratch: s1 = u y_c, s2 = v y_c; G of them into gxw_/gyw_ and gxwv_/gywv_.
  for (int c = 0; c < 2; ++c) {
    const double* y = c == 0 ? yu : yv;
    double* out = c == 0 ? out_u : out_v;
    double* s1 = s1_.data();
    double* s2 = s2_.data();
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      s1[k] = u[k] * y[k];
      s2[k] = v[k] * y[k];
    }
    nodes_.SyncPeriodic(s1);
    nodes_.SyncPeriodic(s2);
    ApplyIntegratedGradient(grid_, topo_, s1, gxw_.data(), gyw_.data(),
                            diagonals_);  // use G_x (u y_c)
    ApplyIntegratedGradient(grid_, topo_, s2, gxwv_.data(), gywv_.data(),
                            diagonals_);  // use G_y (v y_c)
    ApplyStiffness(grid_, topo_, y, s3_.data());
    const double *gx1 = gxw_.data(), *gy2 = gywv_.data(), *ky = s3_.data();
    const double* gcu = c == 0 ? gxu_.data() : gyu_.data();  // G_c u
    const double* gcv = c == 0 ? gxv_.data() : gyv_.data();  // G_c v
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      out[k] = rdt * m[k] * y[k] + nub * ky[k] - rho * (gx1[k] + gy2[k]) +
               rho * (yu[k] * gcu[k] + yv[k] * gcv[k]);
    }
    // Boundary terms of G_x^T (u y_c) (x-normal sides) and G_y^T (v y_c) (y-normal sides).
    std::fill(s4_.begin(), s4_.end(), 0.0);
    AddBoundaryTransposeTerm(s1, 0, s4_.data());
    AddBoundaryTransposeTerm(s2, 1, s4_.data());
    const double* bt = s4_.data();
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) out[k] += rho * bt[k];
    nodes_.ZeroKnown(out);
  }
}

void AdvectionLeastSquares::ApplyPreconditioner(const double* tu, const double* tv, double* yu,
                                                double* yv) {
  if (helmholtz_) {
    std::fill(yu, yu + mass_.size(), 0.0);
    std::fill(yv, yv + mass_.size(), 0.0);
    helmholtz_->SolvePair(tu, yu, tv, yv);
  } else {
    const long n = static_cast<long>(mass_.size());
    const double* m = mass_.data();
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      yu[k] = tu[k] / (rho_over_dt_ * m[k]);
      yv[k] = tv[k] / (rho_over_dt_ * m[k]);
    }
  }
  nodes_.ZeroKnown(yu);
  nodes_.ZeroKnown(yv);
  nodes_.SyncPeriodic(yu);
  nodes_.SyncPeriodic(yv);
}

void AdvectionLeastSquares::Record(const AdvectionReport& result, StepReport& report) const {
  report.Set("advection_iterations", result.iterations);
  report.Set("advection_residual", result.residual);
}

// NOLINTNEXTLINE(readability-function-size): predates the limit; split it when you change it
AdvectionReport AdvectionLeastSquares::Solve(double dt, double* u, double* v) {
  AdvectionReport report;
  SetReference(dt, u, v);
  const long n = static_cast<long>(mass_.size());
  if (tendency_) {
    // r = (u^{n+1/4} - u^n) / dt at the unknowns (0 without a BeginStep since the last Solve).
    const double inv_dt = entry_set_ ? 1.0 / dt_ : 0.0;
    entry_set_ = false;
    const double* unknown = nodes_.unknown().data();
    double *ru = tu_.data(), *rv = tv_.data();
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      ru[k] = unknown[k] == 0.0 ? 0.0 : (u[k] - ru[k]) * inv_dt;
      rv[k] = unknown[k] == 0.0 ? 0.0 : (v[k] - rv[k]) * inv_dt;
    }
  }
  const int solves_per_p = helmholtz_ ? 2 : 0;
  // 1. T0 = T(u), y = P^-1 T0, r = T'^T y, g = P^-1 r, w = g.
  Residual(u, v, t0u_.data(), t0v_.data());
  ApplyPreconditioner(t0u_.data(), t0v_.data(), yu_.data(), yv_.data());
  JacobianTranspose(u, v, yu_.data(), yv_.data(), ru_.data(), rv_.data());
  ApplyPreconditioner(ru_.data(), rv_.data(), gu_.data(), gv_.data());
  report.fast_solves = 2 * solves_per_p;
  double gr = nodes_.Dot2(gu_.data(), ru_.data(), gv_.data(), rv_.data());
  const double gr0 = gr;
  std::copy(gu_.begin(), gu_.end(), wu_.begin());
  std::copy(gv_.begin(), gv_.end(), wv_.begin());
  int it = 0;
  double ratio = 0.0;
  if (gr0 > 0.0) {
    for (;;) {
      if (it == max_iterations_) {
        std::ostringstream msg;
        msg << "advection step (34), least-squares CG: not converged after " << it
            << " iterations; gradient ratio sqrt(g.r/g0.r0) = " << ratio << " > tolerance "
            << tolerance_ << " (solvers.advection_max_iterations, solvers.advection_tolerance)";
        throw SolverNotConverged(msg.str());
      }
      ++it;
      // T1 = T'(u) w, T2 = rho N(w, w), z1 = P^-1 T1, z2 = P^-1 T2.
      Jacobian(u, v, wu_.data(), wv_.data(), t1u_.data(), t1v_.data());
      {
        const double *wu = wu_.data(), *wv = wv_.data(), *gxw = gxw_.data(), *gyw = gyw_.data(),
                     *gxwv = gxwv_.data(), *gywv = gywv_.data();
        double *t2u = t2u_.data(), *t2v = t2v_.data();
        const double rho = rho_;
#pragma omp parallel for schedule(static)
        for (long k = 0; k < n; ++k) {
          t2u[k] = rho * (wu[k] * gxw[k] + wv[k] * gyw[k]);
          t2v[k] = rho * (wu[k] * gxwv[k] + wv[k] * gywv[k]);
        }
        nodes_.ZeroKnown(t2u);
        nodes_.ZeroKnown(t2v);
      }
      ApplyPreconditioner(t1u_.data(), t1v_.data(), z1u_.data(), z1v_.data());
      ApplyPreconditioner(t2u_.data(), t2v_.data(), z2u_.data(), z2v_.data());
      report.fast_solves += 2 * solves_per_p;
      QuarticLine line;
      line.a00 = nodes_.Dot2(t0u_.data(), yu_.data(), t0v_.data(), yv_.data());
      line.a01 = nodes_.Dot2(t0u_.data(), z1u_.data(), t0v_.data(), z1v_.data());
      line.a02 = nodes_.Dot2(t0u_.data(), z2u_.data(), t0v_.data(), z2v_.data());
      line.a11 = nodes_.Dot2(t1u_.data(), z1u_.data(), t1v_.data(), z1v_.data());
      line.a12 = nodes_.Dot2(t1u_.data(), z2u_.data(), t1v_.data(), z2v_.data());
      line.a22 = nodes_.Dot2(t2u_.data(), z2u_.data(), t2v_.data(), z2v_.data());
      const double l = MinimiseQuarticLine(line);
      {
        double *t0u = t0u_.data(), *t0v = t0v_.data(), *yu = yu_.data(), *yv = yv_.data();
        const double *t1u = t1u_.data(), *t1v = t1v_.data(), *t2u = t2u_.data(), *t2v = t2v_.data(),
                     *z1u = z1u_.data(), *z1v = z1v_.data(), *z2u = z2u_.data(), *z2v = z2v_.data(),
                     *wu = wu_.data(), *wv = wv_.data();
        const double l2 = l * l;
#pragma omp parallel for schedule(static)
        for (long k = 0; k < n; ++k) {
          u[k] -= l * wu[k];
          v[k] -= l * wv[k];
          t0u[k] += -l * t1u[k] + l2 * t2u[k];
          t0v[k] += -l * t1v[k] + l2 * t2v[k];
          yu[k] += -l * z1u[k] + l2 * z2u[k];
          yv[k] += -l * z1v[k] + l2 * z2v[k];
        }
      }
      // r' = T'(u)^T y, g' = P^-1 r'; Polak-Ribiere with restart.
      const double g_dot_r_old_g = gr;
      JacobianTranspose(u, v, yu_.data(), yv_.data(), t1u_.data(), t1v_.data());  // r' into T1
      ApplyPreconditioner(t1u_.data(), t1v_.data(), z1u_.data(), z1v_.data());    // g' into z1
      report.fast_solves += solves_per_p;
      const double gr_new = nodes_.Dot2(z1u_.data(), t1u_.data(), z1v_.data(), t1v_.data());
      const double gr_cross = nodes_.Dot2(z1u_.data(), ru_.data(), z1v_.data(), rv_.data());
      std::swap(ru_, t1u_);
      std::swap(rv_, t1v_);
      ratio = std::sqrt(std::max(gr_new, 0.0) / gr0);
      gr = gr_new;
      if (ratio <= tolerance_) break;
      const double gamma = std::max(0.0, (gr_new - gr_cross) / g_dot_r_old_g);
      {
        double *wu = wu_.data(), *wv = wv_.data();
        const double *gnu = z1u_.data(), *gnv = z1v_.data();
#pragma omp parallel for schedule(static)
        for (long k = 0; k < n; ++k) {
          wu[k] = gnu[k] + gamma * wu[k];
          wv[k] = gnv[k] + gamma * wv[k];
        }
      }
    }
  }
  if (taylor_viscosity_ > 0.0) RemoveBackwardEulerTerm(u, v);
  if (tendency_) {
    const double *ru = tu_.data(), *rv = tv_.data();
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      u[k] -= dt * ru[k];
      v[k] -= dt * rv[k];
    }
  }
  nodes_.SyncPeriodic(u);
  nodes_.SyncPeriodic(v);
  boundary_data_.Apply(u, v);
  report.iterations = it;
  report.residual = ratio;
  return report;
}

}  // namespace dlmfd
