#include "dlmfd/fluid/stokes_solver.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/ordered_sum.h"
#include "dlmfd/core/parallel_copy.h"
#include "dlmfd/mesh/fem_operators.h"

namespace dlmfd {
namespace {

// A flow slower than this fraction of the data's velocity scale is at rest for the stopping rule:
// 1e-11 is the relative round-off floor of the DLM step's rule too (rigid_body_constraint.cc), far
// above the velocity noise that round-off in the data makes (a few eps of the scale) and far below
// any velocity the tolerances can resolve (tol >= 1e-8 times the flow's own scale).
constexpr double kQuietFlow = 1e-11;

}  // namespace

StokesSolver::StokesSolver(const Grid& grid, const DomainParams& domain, const FluidParams& fluid,
                           double alpha, const SolverParams& solvers,
                           const BoundaryData& boundary_data)
    : grid_(grid),
      pgrid_(grid.Coarse()),
      vtopo_(BoundaryTopology::ForVelocity(domain)),
      ptopo_(BoundaryTopology::ForPressure(domain)),
      diagonals_(domain.diagonals),
      vnodes_(grid_, vtopo_),
      pnodes_(pgrid_, ptopo_),
      density_(fluid.density),
      nu_(alpha * fluid.ImplicitViscosity(grid.h)),
      body_force_(fluid.body_force),
      tolerance_(solvers.stokes_tolerance),
      data_speed_(boundary_data.MaxSpeed()),
      polymer_(!fluid.IsNewtonian()),
      polymer_modulus_(polymer_ ? fluid.PolymerModulus() : 0.0),
      max_iterations_(solvers.stokes_max_iterations),
      boundary_data_(boundary_data),
      pressure_solver_(pgrid_, ptopo_, 0.0, 1.0, 1) {
  const std::size_t n = grid_.NodeCount(), np = pgrid_.NodeCount();
  mass_.assign(n, 0.0);
  LumpedMassDiagonal(grid_, vtopo_, mass_.data());
  pmass_inv_.assign(np, 0.0);
  LumpedMassDiagonal(pgrid_, ptopo_, pmass_inv_.data());
  pmass_.assign(np, 0.0);
  for (std::size_t k = 0; k < np; ++k) {
    pmass_[k] = pnodes_.IsUnknown(k) ? pmass_inv_[k] : 0.0;
    pmass_inv_[k] = pnodes_.IsUnknown(k) ? 1.0 / pmass_inv_[k] : 0.0;
  }
  // ubar_, vbar_ keep zero Dirichlet data for good: the fast solves write unknown nodes only.
  for (auto* a : {&fu_, &fv_, &ubar_, &vbar_, &tu_, &tv_}) a->assign(n, 0.0);
  for (auto* a : {&r_, &g_, &w_, &sw_, &z_, &predicted_}) a->assign(np, 0.0);
  const std::vector<double>& dist = vnodes_.distinct();
  for (std::size_t k = 0; k < n; ++k) area_ += dist[k] * mass_[k];
  if (domain.flow_rate) {
    std::vector<double> weights(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) weights[k] = dist[k] * mass_[k];
    flux_ = std::make_unique<FluxControl>(grid_, domain, std::move(weights));
  }
}

// The velocity scale of the data of (33), from the scene alone: the boundary values, the change a
// body force makes in one step, and the change a polymer stress of one modulus G = eta_p / lambda
// makes in one step over one cell (the scale of the polymer force, whose round-off is what a liquid
// at rest carries). Gravity is not forcing of (33): the split scheme absorbs rho_L g into p. The
// floor of the reference is that scale, times kQuietFlow, over the domain.
void StokesSolver::PrepareStep(double dt) {
  if (dt == dt_) return;
  dt_ = dt;
  rho_over_dt_ = density_ / dt;
  velocity_solver_ = std::make_unique<SeparableHelmholtz>(grid_, vtopo_, rho_over_dt_, nu_, 2);
  double speed = std::max(data_speed_, body_force_.norm() * dt / density_);
  if (polymer_) {
    speed = std::max(speed, polymer_modulus_ * dt / (density_ * grid_.h));
  }
  reference_floor_ = kQuietFlow * speed * std::sqrt(rho_over_dt_ * area_);
  if (flux_) flux_->SetResponses(UnitResponses());
}

// The unit responses u_a of fluid/flux_control.h: A u_a = M_l e_a with zero Dirichlet data, one
// per held axis.
std::vector<FluxControl::UnitResponse> StokesSolver::UnitResponses() const {
  const std::size_t n = grid_.NodeCount();
  std::vector<FluxControl::UnitResponse> responses;
  for (int axis : flux_->axes()) {
    std::vector<double> fu(n, 0.0), fv(n, 0.0);
    FluxControl::UnitResponse r{axis, std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
    std::copy(mass_.begin(), mass_.end(), axis == 0 ? fu.begin() : fv.begin());
    velocity_solver_->SolvePair(fu.data(), r.u.data(), fv.data(), r.v.data());
    vnodes_.SyncPeriodic(r.u.data());
    vnodes_.SyncPeriodic(r.v.data());
    responses.push_back(std::move(r));
  }
  return responses;
}

StokesSolver::~StokesSolver() = default;

void StokesSolver::SolveVelocityPair(const double* fu, const double* fv, double* u, double* v) {
  velocity_solver_->SolvePair(fu, u, fv, v);
}

// g = nu M_p^-1 r + (rho/dt) K_p^-1 r; g is zero on pressure Dirichlet nodes.
void StokesSolver::ApplyPreconditioner(const double* r, double* g) {
  ParallelFill(z_.data(), static_cast<long>(z_.size()), 0.0);  // Dirichlet data p = 0 for the solve
  pressure_solver_.Solve(r, z_.data());
  const long np = static_cast<long>(z_.size());
  const double* minv = pmass_inv_.data();
  const double* z = z_.data();
#pragma omp parallel for schedule(static)
  for (long k = 0; k < np; ++k) g[k] = nu_ * minv[k] * r[k] + rho_over_dt_ * z[k];
  pnodes_.ZeroKnown(g);
  pnodes_.SyncPeriodic(g);
}

void StokesSolver::RemoveMean(double* p) const {
  double mean = 0.0, area = 0.0;
  for (std::size_t k = 0; k < pmass_.size(); ++k) {
    mean += pmass_[k] * p[k];
    area += pmass_[k];
  }
  mean /= area;
  for (std::size_t k = 0; k < pmass_.size(); ++k) p[k] -= pnodes_.IsUnknown(k) ? mean : 0.0;
}

double StokesSolver::PredictDivergence(const double* fx, const double* fy, const double* u,
                                       const double* v) {
  const long n = static_cast<long>(grid_.NodeCount());
  ParallelCopy(u, n, tu_.data());
  ParallelCopy(v, n, tv_.data());
  boundary_data_.Apply(tu_.data(), tv_.data());
  ApplyStiffness(grid_, vtopo_, tu_.data(), fu_.data());
  ApplyStiffness(grid_, vtopo_, tv_.data(), fv_.data());
  const double* m = mass_.data();
  const double* ku = fu_.data();
  const double* kv = fv_.data();
  double* pu = tu_.data();
  double* pv = tv_.data();
  const double bx = body_force_.x(), by = body_force_.y(), nu = nu_;
  const double scale = 1.0 / rho_over_dt_;
  const NodeSet& nodes = vnodes_;
#pragma omp parallel for schedule(static)
  for (long k = 0; k < n; ++k) {
    if (!nodes.IsUnknown(static_cast<std::size_t>(k))) continue;
    pu[k] += scale * (bx + ((fx ? fx[k] : 0.0) - nu * ku[k]) / m[k]);
    pv[k] += scale * (by + ((fy ? fy[k] : 0.0) - nu * kv[k]) / m[k]);
  }
  vnodes_.SyncPeriodic(pu);
  vnodes_.SyncPeriodic(pv);
  ApplyDivergence(grid_, ptopo_, pu, pv, predicted_.data(), diagonals_);
  pnodes_.ZeroKnown(predicted_.data());
  const double* dist = vnodes_.distinct().data();
  return OrderedSum(n, [=](long k) { return dist[k] * m[k] * (pu[k] * pu[k] + pv[k] * pv[k]); });
}

double StokesSolver::ResidualNorm(double dt, const double* u, const double* v) {
  PrepareStep(dt);
  ApplyDivergence(grid_, ptopo_, u, v, r_.data(), diagonals_);
  pnodes_.ZeroKnown(r_.data());
  ApplyPreconditioner(r_.data(), g_.data());
  return std::sqrt(std::max(0.0, pnodes_.Dot(r_.data(), g_.data())));
}

double StokesSolver::WeightedSquareSum(const double* r) const {
  const long np = static_cast<long>(pmass_inv_.size());
  const double* minv = pmass_inv_.data();
  return OrderedSum(np, [=](long k) { return minv[k] * r[k] * r[k]; });
}

double StokesSolver::DivergenceNorm(const double* u, const double* v) {
  ApplyDivergence(grid_, ptopo_, u, v, r_.data(), diagonals_);
  return std::sqrt(WeightedSquareSum(r_.data()));
}

// NOLINTNEXTLINE(readability-function-size): over the limit before it was set; split when changed
StokesReport StokesSolver::Solve(double dt, const double* fx, const double* fy, double* u,
                                 double* v, double* p, std::vector<double>* defect) {
  PrepareStep(dt);
  const long n = static_cast<long>(grid_.NodeCount());
  const double* m = mass_.data();
  const double* dist = vnodes_.distinct().data();
  StokesReport report;

  // Step 1: A u^0 = F + B^T p^0 with the Dirichlet data of t^{n+1}, F = (rho/dt) M u^n + M f_body +
  // (fx, fy). First |u^n|_M^2 for the reference (the warm start's test below uses it too).
  pnodes_.ZeroKnown(p);
  const double energy_old =
      OrderedSum(n, [=](long k) { return dist[k] * m[k] * (u[k] * u[k] + v[k] * v[k]); });
  // The predicted warm start (header block): p -= P^-1 (d + e) with e the last step's defect, where
  // the predicted first residual is above the stopping rule's target (ref estimated from u^n) and
  // above the round-off of d (kQuietFlow of u~'s own scale).
  const long np = static_cast<long>(r_.size());
  if (defect) {
    const double energy_predicted = PredictDivergence(fx, fy, u, v);
    if (defect->size() == r_.size()) {
      const double* d = predicted_.data();
      const double* e = defect->data();
      double* rv = r_.data();
#pragma omp parallel for schedule(static)
      for (long k = 0; k < np; ++k) rv[k] = d[k] + e[k];
      ApplyPreconditioner(r_.data(), g_.data());
      const double predicted = std::sqrt(std::max(0.0, pnodes_.Dot(r_.data(), g_.data())));
      const double ref_estimate = std::max(std::sqrt(rho_over_dt_ * energy_old), reference_floor_);
      const double round_off = kQuietFlow * std::sqrt(rho_over_dt_ * energy_predicted);
      if (predicted > std::max(tolerance_ * ref_estimate, round_off)) {
        const double* gv = g_.data();
#pragma omp parallel for schedule(static)
        for (long k = 0; k < np; ++k) p[k] -= gv[k];
      }
    }
  }
  if (ptopo_.HasNullSpace()) RemoveMean(p);  // p in L2_0: the round-off drift of the warm start
  pnodes_.SyncPeriodic(p);
  ApplyDivergenceTranspose(grid_, ptopo_, p, tu_.data(), tv_.data(), diagonals_);
  {
    double* fu = fu_.data();
    double* fv = fv_.data();
    const double* tu = tu_.data();
    const double* tv = tv_.data();
    const double bx = body_force_.x(), by = body_force_.y(), rho_over_dt = rho_over_dt_;
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      fu[k] = m[k] * (rho_over_dt * u[k] + bx) + (fx ? fx[k] : 0.0) + tu[k];
      fv[k] = m[k] * (rho_over_dt * v[k] + by) + (fy ? fy[k] : 0.0) + tv[k];
    }
  }
  boundary_data_.Apply(u, v);
  SolveVelocityPair(fu_.data(), fv_.data(), u, v);

  const double energy_new =
      OrderedSum(n, [=](long k) { return dist[k] * m[k] * (u[k] * u[k] + v[k] * v[k]); });
  const double ref =
      std::max(std::sqrt(rho_over_dt_ * std::max(energy_old, energy_new)), reference_floor_);
  report.reference = ref;

  // Step 2: r = B u^0, g = P^-1 r, w = g.
  ApplyDivergence(grid_, ptopo_, u, v, r_.data(), diagonals_);
  pnodes_.ZeroKnown(r_.data());
  ApplyPreconditioner(r_.data(), g_.data());
  double rg = pnodes_.Dot(r_.data(), g_.data());
  ParallelCopy(g_.data(), static_cast<long>(g_.size()), w_.data());
  const double target = tolerance_ * ref;

  int it = 0;
  while (std::sqrt(std::max(rg, 0.0)) > target) {
    if (it == max_iterations_) {
      std::ostringstream msg;
      msg << "Stokes step (33), Uzawa/PCG: not converged after " << it
          << " iterations; residual sqrt(r.P^-1 r)/ref = " << std::sqrt(std::max(rg, 0.0)) / ref
          << " > tolerance " << tolerance_
          << " (solvers.stokes_max_iterations, solvers.stokes_tolerance)";
      throw SolverNotConverged(msg.str());
    }
    ++it;
    // A ubar = B^T w (zero Dirichlet data), Sw = B ubar.
    ApplyDivergenceTranspose(grid_, ptopo_, w_.data(), tu_.data(), tv_.data(), diagonals_);
    SolveVelocityPair(tu_.data(), tv_.data(), ubar_.data(), vbar_.data());
    ApplyDivergence(grid_, ptopo_, ubar_.data(), vbar_.data(), sw_.data(), diagonals_);
    pnodes_.ZeroKnown(sw_.data());
    const double wsw = pnodes_.Dot(sw_.data(), w_.data());
    if (!(wsw > 0.0)) {
      std::ostringstream msg;
      msg << "Stokes step (33), Uzawa/PCG: breakdown at iteration " << it << " (w.Sw = " << wsw
          << "); residual sqrt(r.P^-1 r)/ref = " << std::sqrt(std::max(rg, 0.0)) / ref;
      throw SolverNotConverged(msg.str());
    }
    const double step = rg / wsw;
    {
      const double* wv = w_.data();
      const double* swv = sw_.data();
      double* rv = r_.data();
#pragma omp parallel for schedule(static)
      for (long k = 0; k < np; ++k) {
        p[k] -= step * wv[k];
        rv[k] -= step * swv[k];
      }
      const double* ub = ubar_.data();
      const double* vb = vbar_.data();
#pragma omp parallel for schedule(static)
      for (long k = 0; k < n; ++k) {
        u[k] -= step * ub[k];
        v[k] -= step * vb[k];
      }
    }
    ApplyPreconditioner(r_.data(), g_.data());
    const double rg_new = pnodes_.Dot(r_.data(), g_.data());
    const double ratio = rg_new / rg;
    rg = rg_new;
    if (std::sqrt(std::max(rg, 0.0)) <= target) break;
    const double* gv = g_.data();
    double* wv = w_.data();
#pragma omp parallel for schedule(static)
    for (long k = 0; k < np; ++k) wv[k] = gv[k] + ratio * wv[k];
  }
  if (defect) {  // e = r - d for the next step's warm start
    defect->resize(r_.size());
    const double* d = predicted_.data();
    const double* rv = r_.data();
    double* e = defect->data();
#pragma omp parallel for schedule(static)
    for (long k = 0; k < np; ++k) e[k] = rv[k] - d[k];
  }
  report.iterations = it;
  report.residual = ref > 0.0 ? std::sqrt(std::max(rg, 0.0)) / ref : 0.0;
  // r = B u at the unknown nodes, carried by the recursion (equal to a fresh B u up to round-off);
  // M_p^-1 is 0 at the known ones, so this is DivergenceNorm(u, v) without another B.
  report.divergence = std::sqrt(WeightedSquareSum(r_.data()));
  if (flux_) report.mean_pressure_gradient = flux_->Hold(u, v);
  return report;
}

}  // namespace dlmfd
