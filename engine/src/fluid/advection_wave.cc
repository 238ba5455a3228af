#include "dlmfd/fluid/advection_wave.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/parallel_copy.h"
#include "dlmfd/mesh/fem_operators.h"
#include "mean_wave_rows.h"

namespace dlmfd {

// Stability (tests/unit/advection_wave_stability_test.cc): for a constant V one call multiplies a
// Fourier mode by G = cos(Q phi) - i c sigma sin(Q phi) / sin(phi), cos(phi) = 1 - c^2 kappa / 2
// (c = tau |V| / h; i sigma, kappa the symbols of M^-1 C and M^-1 K_V), so |G| <= 1 iff
// sigma^2 <= kappa (1 - c^2 kappa / 4) and c^2 kappa <= 4, whatever Q. Because K_V is not
// C^T M^-1 C (C, by vertex quadrature, has a wider stencil) the limit is c = sqrt(2/3) along x or
// y, 2/sqrt(3) along y = x and 1/sqrt(2) along y = -x (the minimum over directions), not
// the 1.02-1.04 of the method notes, which came from M^-1 K_V alone on nearly vertical fields. The
// implementation matches this analysis to the power iteration's accuracy, so no bug was found. The
// bound holds for Q = 1 (the Taylor start alone, a Lax-Wendroff step) as for Q >= 2 (the stability
// test checks Q = 1 and 2), and both are second order in tau; Q = 1 costs one K_V product per call
// instead of two. The splitting's first-order error dominates the difference
// (docs/evidence/performance.md).
constexpr int kMinSubsteps = 1;
// The tendency correction's cap (header): with the wide form L(L u) in place of the compact K_V,
// the step with the implicit viscosity of (33) is stable while |V|^4 dt^3 / (nu h^2) <= 13.8 (von
// Neumann, constant V in every direction, both diagonals, Courant numbers 0.2-0.8 with the
// sub-steps of max_courant 0.5: bench/wave_tendency_stability.py); half of it is used.
constexpr double kWideFormBound = 13.8;
constexpr double kWideFormShare = 0.5;
// A velocity that would need more sub-steps than this is a blow-up (step (35) has the same bound):
// without it a diverging run would spend hours sub-cycling one step instead of ending FAILED.
constexpr int kMaxAdvectionSubsteps = 1000;

namespace {

// A cell (ci, cj) of the grid: its corners a = (ci, cj), b = (ci + 1, cj), c = (ci + 1, cj + 1),
// d = (ci, cj + 1), its index among the cells and among the padded cells (one ghost layer).
struct CellAt {
  std::size_t a, b, c, d, cell, padded;
};

std::size_t PaddedCell(const Grid& grid, int ci, int cj) {
  return std::size_t(cj + 1) * (grid.nx + 2) + (ci + 1);
}

// Calls fn(CellAt) for every cell, rows of cells in parallel.
template <typename CellFn>
void ForEachCell(const Grid& grid, CellFn&& fn) {
  const int nx = grid.nx, ny = grid.ny;
#pragma omp parallel for schedule(static)
  for (int cj = 0; cj < ny; ++cj) {
    for (int ci = 0; ci < nx; ++ci) {
      fn(CellAt{grid.Index(ci, cj), grid.Index(ci + 1, cj), grid.Index(ci + 1, cj + 1),
                grid.Index(ci, cj + 1), std::size_t(cj) * nx + ci, PaddedCell(grid, ci, cj)});
    }
  }
}

// A node (i, j) and the padded cells whose corner it is: a of (i, j), b of (i - 1, j), c of
// (i - 1, j - 1), d of (i, j - 1).
struct NodeCorners {
  std::size_t id, as_a, as_b, as_c, as_d;
};

// Calls fn(NodeCorners) for every node, rows in parallel: the gather of the cells' shares.
template <typename NodeFn>
void ForEachNodeCorners(const Grid& grid, NodeFn&& fn) {
#pragma omp parallel for schedule(static)
  for (int j = 0; j <= grid.ny; ++j) {
    for (int i = 0; i <= grid.nx; ++i) {
      fn(NodeCorners{grid.Index(i, j), PaddedCell(grid, i, j), PaddedCell(grid, i - 1, j),
                     PaddedCell(grid, i - 1, j - 1), PaddedCell(grid, i, j - 1)});
    }
  }
}

}  // namespace

AdvectionWave::AdvectionWave(const Grid& grid, const DomainParams& domain, const FluidParams& fluid,
                             double beta, SteadyCorrection correction, const SolverParams& solvers,
                             const BoundaryData& boundary_data)
    : grid_(grid),
      topo_(BoundaryTopology::ForVelocity(domain)),
      diagonals_(domain.diagonals),
      nodes_(grid_, topo_),
      density_(fluid.density),
      nu_b_(beta * fluid.ImplicitViscosity(grid.h)),
      max_courant_(solvers.wave_max_courant),
      taylor_viscosity_(SteadyCorrectionCap(correction, fluid, grid.h)),
      boundary_data_(boundary_data) {
  for (int s = 0; s < 4; ++s) outflow_[s] = domain.sides[s].type == SideType::kOutflow;
  const std::size_t n = grid_.NodeCount();
  const std::size_t cells = std::size_t(grid_.nx) * grid_.ny;
  const std::size_t padded = std::size_t(grid_.nx + 2) * (grid_.ny + 2);
  mass_.assign(n, 0.0);
  LumpedMassDiagonal(grid_, topo_, mass_.data());
  for (auto* a : {&out_mass_, &vx_, &vy_, &u0_, &v0_, &u1_, &v1_, &ku_, &kv_, &gx_, &gy_})
    a->assign(n, 0.0);
  tendency_ = correction == SteadyCorrection::kTendency;
  if (tendency_) {
    for (auto* a : {&ru_, &rv_, &srcu_, &srcv_, &epsu_, &epsv_}) a->assign(n, 0.0);
    wide_viscosity_ = kWideFormShare * kWideFormBound * fluid.ImplicitViscosity(grid.h) /
                      fluid.density * grid.h * grid.h;
  }
  if (taylor_viscosity_ > 0.0) {
    utt_u_.assign(n, 0.0);
    utt_v_.assign(n, 0.0);
  }
  if (diagonals_ == MeshDiagonals::kBoth) {
    CellMatrix& m = mean_;
    for (auto* a : {&m.bb, &m.bc, &m.bd, &m.cc, &m.cd, &m.dd}) a->assign(cells, 0.0);
    for (auto& a : corners_) a.assign(padded, 0.0);
  } else {
    TriangleWeights& w = weights_;
    for (auto* a : {&w.w11a, &w.w12a, &w.w22a, &w.w11b, &w.w12b, &w.w22b}) a->assign(cells, 0.0);
    for (auto* a : {&f1xu_, &f1yu_, &f2xu_, &f2yu_, &f1xv_, &f1yv_, &f2xv_, &f2yv_})
      a->assign(padded, 0.0);
  }
}

AdvectionWave::~AdvectionWave() = default;

void AdvectionWave::PrepareStep(double dt) {
  if (dt == dt_) return;
  dt_ = dt;
  rho_over_dt_ = density_ / dt;
  if (nu_b_ > 0.0) {
    helmholtz_ = std::make_unique<SeparableHelmholtz>(grid_, topo_, rho_over_dt_, nu_b_, 2);
  }
}

// W_T / h^2 = (1/24)(sum_k V_k V_k^T + S S^T) over the vertices of T, for |T| = h^2 / 2 and
// unscaled gradients. The products V_k V_k^T of the cell's four corners are formed once and shared
// by its two (or, on both diagonals, four) triangles; on both diagonals the cell's matrix M of
// mean_wave_rows.h, a row of cells a call.
void AdvectionWave::ComputeWeights(const double* vx, const double* vy) {
  if (diagonals_ == MeshDiagonals::kBoth) {
    CellMatrix& m = mean_;
    const int nx = grid_.nx;
#pragma omp parallel for schedule(static)
    for (int cj = 0; cj < grid_.ny; ++cj) {
      const std::size_t low = grid_.Index(0, cj), high = grid_.Index(0, cj + 1);
      const std::size_t cell = std::size_t(cj) * nx;
      double* const out[6] = {m.bb.data() + cell, m.bc.data() + cell, m.bd.data() + cell,
                              m.cc.data() + cell, m.cd.data() + cell, m.dd.data() + cell};
      wave_rows::CellMatrixRow(nx, vx + low, vx + high, vy + low, vy + high, out);
    }
    return;
  }
  TriangleWeights& w = weights_;
  ForEachCell(grid_, [&](const CellAt& k) {
    const wave_rows::CellCorners c(vx[k.a], vx[k.b], vx[k.c], vx[k.d], vy[k.a], vy[k.b], vy[k.c],
                                   vy[k.d]);
    const std::size_t cell = k.cell;
    c.Triangle(0, 1, 2, w.w11a[cell], w.w12a[cell], w.w22a[cell]);  // T1 = (a, b, c)
    c.Triangle(0, 2, 3, w.w11b[cell], w.w12b[cell], w.w22b[cell]);  // T2 = (a, c, d)
  });
}

void AdvectionWave::FreezeVelocity(const double* u, const double* v) {
  const int nx = grid_.nx, ny = grid_.ny;
  ParallelCopy(u, static_cast<long>(vx_.size()), vx_.data());
  ParallelCopy(v, static_cast<long>(vy_.size()), vy_.data());
  const double* vx = vx_.data();
  const double* vy = vy_.data();
  ComputeWeights(vx, vy);
  // (V.n)^+ times the lumped boundary mass on outflow sides.
  ParallelFill(out_mass_.data(), static_cast<long>(out_mass_.size()), 0.0);
  for (int s = 0; s < 4; ++s) {
    if (!outflow_[s]) continue;
    const Side side = static_cast<Side>(s);
    const bool vertical = (side == Side::kLeft || side == Side::kRight);
    const int count = vertical ? ny : nx;
    const bool wraps =
        vertical ? topo_.y.low == EndKind::kPeriodic : topo_.x.low == EndKind::kPeriodic;
    for (int k = 0; k <= count; ++k) {
      const int i = vertical ? (side == Side::kLeft ? 0 : nx) : k;
      const int j = vertical ? k : (side == Side::kBottom ? 0 : ny);
      const std::size_t id = grid_.Index(i, j);
      if (!nodes_.IsUnknown(id)) continue;
      const double length = (!wraps && (k == 0 || k == count)) ? 0.5 * grid_.h : grid_.h;
      const double vn = vx[id] * outflow_normal_[s][0] + vy[id] * outflow_normal_[s][1];
      out_mass_[id] += std::max(vn, 0.0) * length;
    }
  }
}

void AdvectionWave::ApplyWaveStiffness(const double* u, const double* v, double* ku, double* kv) {
  if (diagonals_ == MeshDiagonals::kBoth) {
    ApplyMeanWaveStiffness(u, v, ku, kv);
  } else {
    ApplyMeshWaveStiffness(u, v, ku, kv);
  }
}

void AdvectionWave::FillPeriodicGhosts(std::vector<double>* const* cells, int count) {
  const int nx = grid_.nx, ny = grid_.ny;
  if (topo_.x.low == EndKind::kPeriodic) {
    for (int k = 0; k < count; ++k) {
      std::vector<double>& f = *cells[k];
      for (int cj = 0; cj < ny; ++cj)
        f[PaddedCell(grid_, -1, cj)] = f[PaddedCell(grid_, nx - 1, cj)];
    }
  }
  if (topo_.y.low == EndKind::kPeriodic) {
    for (int k = 0; k < count; ++k) {
      std::vector<double>& f = *cells[k];
      for (int ci = -1; ci < nx; ++ci)
        f[PaddedCell(grid_, ci, -1)] = f[PaddedCell(grid_, ci, ny - 1)];
    }
  }
}

void AdvectionWave::ApplyMeshWaveStiffness(const double* u, const double* v, double* ku,
                                           double* kv) {
  const TriangleWeights& wt = weights_;
  std::vector<double>* fluxes[8] = {&f1xu_, &f1yu_, &f2xu_, &f2yu_, &f1xv_, &f1yv_, &f2xv_, &f2yv_};
  // Per-triangle fluxes F_T = W_T grad u_T (unscaled differences), both components of u then v.
  ForEachCell(grid_, [&](const CellAt& k) {
    const std::size_t a = k.a, b = k.b, c = k.c, d = k.d, cell = k.cell, pc = k.padded;
    const double w11 = wt.w11a[cell], w12 = wt.w12a[cell], w22 = wt.w22a[cell];
    const double z11 = wt.w11b[cell], z12 = wt.w12b[cell], z22 = wt.w22b[cell];
    for (int comp = 0; comp < 2; ++comp) {
      const double* f = comp == 0 ? u : v;
      std::vector<double>* const* out = fluxes + 4 * comp;
      double gx = f[b] - f[a], gy = f[c] - f[b];  // T1 (a, b, c)
      (*out[0])[pc] = w11 * gx + w12 * gy;
      (*out[1])[pc] = w12 * gx + w22 * gy;
      gx = f[c] - f[d];  // T2 (a, c, d)
      gy = f[d] - f[a];
      (*out[2])[pc] = z11 * gx + z12 * gy;
      (*out[3])[pc] = z12 * gx + z22 * gy;
    }
  });
  FillPeriodicGhosts(fluxes, 8);
  // Gather: h grad phi of the node is (-1, 0) on T1 and (0, -1) on T2 as a, (1, -1) on T1 as b,
  // (0, 1) on T1 and (1, 0) on T2 as c, (-1, 1) on T2 as d.
  ForEachNodeCorners(grid_, [&](const NodeCorners& n) {
    const std::size_t own = n.as_a, w = n.as_b, sw = n.as_c, s = n.as_d;
    ku[n.id] = -f1xu_[own] - f2yu_[own] + f1xu_[w] - f1yu_[w] + f1yu_[sw] + f2xu_[sw] - f2xu_[s] +
               f2yu_[s];
    kv[n.id] = -f1xv_[own] - f2yv_[own] + f1xv_[w] - f1yv_[w] + f1yv_[sw] + f2xv_[sw] - f2xv_[s] +
               f2yv_[s];
  });
}

// The mean of K_V on the four triangles of each cell: each cell's shares of the rows of its
// corners a, b, c, d (half the SW-NE pair's plus half the NW-SE pair's), then one gather of four
// shares a node. With F_T = W_T grad u_T and h grad phi of each corner on each triangle
// (grid_kernels.h), the shares are
//   a: -F1x - F2y  and  -F3x - F3y;      b: F1x - F1y  and  F3x - F4y;
//   c:  F1y + F2x  and   F4x + F4y;      d: F2y - F2x  and  F3y - F4x,
// linear in the differences e = (u_b - u_a, u_c - u_a, u_d - u_a): (b, c, d) = M e and a = -(b + c
// + d), with M the cell's symmetric matrix of ComputeWeights (mean_wave_rows.h).
void AdvectionWave::ApplyMeanWaveStiffness(const double* u, const double* v, double* ku,
                                           double* kv) {
  const CellMatrix& mc = mean_;
  const int nx = grid_.nx, ny = grid_.ny;
  std::vector<double>* shares[8];
  for (int k = 0; k < 8; ++k) shares[k] = &corners_[k];
#pragma omp parallel for schedule(static)
  for (int cj = 0; cj < ny; ++cj) {
    const std::size_t low = grid_.Index(0, cj), high = grid_.Index(0, cj + 1);
    const std::size_t cell = std::size_t(cj) * nx, pc = PaddedCell(grid_, 0, cj);
    const double* const m[6] = {mc.bb.data() + cell, mc.bc.data() + cell, mc.bd.data() + cell,
                                mc.cc.data() + cell, mc.cd.data() + cell, mc.dd.data() + cell};
    for (int comp = 0; comp < 2; ++comp) {
      const double* f = comp == 0 ? u : v;
      std::vector<double>* const* s = shares + 4 * comp;
      double* const out[4] = {s[0]->data() + pc, s[1]->data() + pc, s[2]->data() + pc,
                              s[3]->data() + pc};
      wave_rows::CellSharesRow(nx, m, f + low, f + high, out);
    }
  }
  FillPeriodicGhosts(shares, 8);
  // Node (i, j) is corner a of padded cell (i, j), b of (i - 1, j), c of (i - 1, j - 1), d of
  // (i, j - 1).
#pragma omp parallel for schedule(static)
  for (int j = 0; j <= ny; ++j) {
    const std::size_t id = grid_.Index(0, j);
    const std::size_t as_a = PaddedCell(grid_, 0, j), as_b = PaddedCell(grid_, -1, j),
                      as_c = PaddedCell(grid_, -1, j - 1), as_d = PaddedCell(grid_, 0, j - 1);
    for (int comp = 0; comp < 2; ++comp) {
      const std::vector<double>* s = corners_ + 4 * comp;
      wave_rows::GatherRow(nx + 1, s[0].data() + as_a, s[1].data() + as_b, s[2].data() + as_c,
                           s[3].data() + as_d, (comp == 0 ? ku : kv) + id);
    }
  }
}

void AdvectionWave::RemoveTaylorTerm() {
  const long n = static_cast<long>(mass_.size());
  const double* unknown = nodes_.unknown().data();
  const double *vx = vx_.data(), *vy = vy_.data(), *tu = utt_u_.data(), *tv = utt_v_.data();
  double *u = u1_.data(), *v = v1_.data();
  const double half_dt2 = 0.5 * dt_ * dt_, half_dt = 0.5 * dt_, cap = taylor_viscosity_;
#pragma omp parallel for schedule(static)
  for (long k = 0; k < n; ++k) {
    if (unknown[k] == 0.0) continue;
    const double streamline = half_dt * (vx[k] * vx[k] + vy[k] * vy[k]);  // dt |V|^2 / 2
    const double theta = SteadyCorrectionShare(streamline, cap);
    u[k] -= theta * half_dt2 * tu[k];
    v[k] -= theta * half_dt2 * tv[k];
  }
  nodes_.SyncPeriodic(u);
  nodes_.SyncPeriodic(v);
}

void AdvectionWave::BeginStep(const double* u, const double* v) {
  if (!tendency_) return;
  ParallelCopy(u, static_cast<long>(ru_.size()), ru_.data());
  ParallelCopy(v, static_cast<long>(rv_.size()), rv_.data());
  entry_set_ = true;
}

void AdvectionWave::Record(const AdvectionReport& result, StepReport& report) const {
  report.Set("wave_substeps", result.iterations);
}

// NOLINTNEXTLINE(readability-function-size): over the limit before it was set; split when changed
AdvectionReport AdvectionWave::Solve(double dt, double* u, double* v) {
  PrepareStep(dt);
  AdvectionReport report;
  const long n = static_cast<long>(mass_.size());
  FreezeVelocity(u, v);
  const double vmax = nodes_.MaxNorm(vx_.data(), vy_.data());
  const double courant_ratio = vmax * dt_ / (grid_.h * max_courant_);
  // (NaN velocities are Simulation::CheckFinite's.)
  if (!(courant_ratio <= kMaxAdvectionSubsteps)) {
    std::ostringstream msg;
    msg << "advective Courant number " << vmax * dt_ / grid_.h
        << " in step (34) (max |u| = " << vmax << ") would need more than " << kMaxAdvectionSubsteps
        << " wave sub-steps: the velocity is beyond any bound the time step can follow";
    throw NumericalBlowUp(msg.str());
  }
  const int substeps = std::max(kMinSubsteps, static_cast<int>(std::ceil(courant_ratio - 1e-12)));
  const double tau = dt_ / substeps;
  report.iterations = substeps;

  const double* m = mass_.data();
  const double* mo = out_mass_.data();
  const double* unknown = nodes_.unknown().data();
  const double* vx = vx_.data();
  const double* vy = vy_.data();
  ParallelCopy(u, n, u0_.data());
  ParallelCopy(v, n, v0_.data());
  if (tendency_) {
    // r = (u^{n+1/4} - u^n) / dt at the unknowns (0 without a BeginStep since the last Solve);
    // src = M_out r - N(V, r).
    const double inv_dt = entry_set_ ? 1.0 / dt_ : 0.0;
    entry_set_ = false;
    for (int c = 0; c < 2; ++c) {
      const double* x0 = c == 0 ? u0_.data() : v0_.data();
      double* r = c == 0 ? ru_.data() : rv_.data();
      double* src = c == 0 ? srcu_.data() : srcv_.data();
#pragma omp parallel for schedule(static)
      for (long k = 0; k < n; ++k) r[k] = unknown[k] == 0.0 ? 0.0 : (x0[k] - r[k]) * inv_dt;
      nodes_.SyncPeriodic(r);
      ApplyIntegratedGradient(grid_, topo_, r, gx_.data(), gy_.data(), diagonals_);
      const double* gx = gx_.data();
      const double* gy = gy_.data();
#pragma omp parallel for schedule(static)
      for (long k = 0; k < n; ++k) src[k] = mo[k] * r[k] - (vx[k] * gx[k] + vy[k] * gy[k]);
    }
  }
  // Start: u^1 = u^0 + tau u_t + tau^2/2 u_tt, u_t = -M^-1 N(V, u^0), u_tt = -M^-1 (K_V u^0 + M_out
  // u_t).
  ApplyWaveStiffness(u0_.data(), v0_.data(), ku_.data(), kv_.data());
  for (int c = 0; c < 2 && tendency_; ++c) {
    const double* x0 = c == 0 ? u0_.data() : v0_.data();
    double* x1 = c == 0 ? u1_.data() : v1_.data();
    const double* kx = c == 0 ? ku_.data() : kv_.data();
    const double* r = c == 0 ? ru_.data() : rv_.data();
    const double* src = c == 0 ? srcu_.data() : srcv_.data();
    double* eps = c == 0 ? epsu_.data() : epsv_.data();
    // eps first holds L u^0 = -M^-1 N(V, u^0) (0 at the Dirichlet nodes), then phi eps.
    ApplyIntegratedGradient(grid_, topo_, x0, gx_.data(), gy_.data(), diagonals_);
    {
      const double* gx = gx_.data();
      const double* gy = gy_.data();
#pragma omp parallel for schedule(static)
      for (long k = 0; k < n; ++k)
        eps[k] = unknown[k] == 0.0 ? 0.0 : -(vx[k] * gx[k] + vy[k] * gy[k]) / m[k];
    }
    nodes_.SyncPeriodic(eps);
    ApplyIntegratedGradient(grid_, topo_, eps, gx_.data(), gy_.data(), diagonals_);
    const double* gx = gx_.data();
    const double* gy = gy_.data();
    const double dt3 = dt_ * dt_ * dt_, wide = wide_viscosity_;
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      if (unknown[k] == 0.0) {
        x1[k] = x0[k];
        eps[k] = 0.0;
        continue;
      }
      const double ut = eps[k];
      const double compact = -(kx[k] + mo[k] * ut) / m[k];
      const double wide_form = -(vx[k] * gx[k] + vy[k] * gy[k]) / m[k];
      const double utt = compact + (src[k] - mo[k] * r[k]) / m[k];  // + L r
      x1[k] = x0[k] + tau * (ut + r[k]) + 0.5 * tau * tau * utt;
      const double v2 = vx[k] * vx[k] + vy[k] * vy[k];
      const double reach = dt3 * v2 * v2;  // dt^3 |V|^4
      const double phi = reach > wide ? wide / reach : 1.0;
      eps[k] = phi * (compact - wide_form);
    }
  }
  for (int c = 0; c < 2 && !tendency_; ++c) {
    const double* x0 = c == 0 ? u0_.data() : v0_.data();
    double* x1 = c == 0 ? u1_.data() : v1_.data();
    const double* kx = c == 0 ? ku_.data() : kv_.data();
    double* kept = taylor_viscosity_ > 0.0 ? (c == 0 ? utt_u_.data() : utt_v_.data()) : nullptr;
    ApplyIntegratedGradient(grid_, topo_, x0, gx_.data(), gy_.data(), diagonals_);
    const double* gx = gx_.data();
    const double* gy = gy_.data();
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      if (unknown[k] == 0.0) {
        x1[k] = x0[k];
        continue;
      }
      const double ut = -(vx[k] * gx[k] + vy[k] * gy[k]) / m[k];
      const double utt = -(kx[k] + mo[k] * ut) / m[k];
      x1[k] = x0[k] + tau * ut + 0.5 * tau * tau * utt;
      if (kept) kept[k] = utt;
    }
  }
  nodes_.SyncPeriodic(u1_.data());
  nodes_.SyncPeriodic(v1_.data());
  // Centred steps: (M/tau^2 + M_out/(2 tau)) u^{q+1} = M/tau^2 (2u^q - u^{q-1}) + M_out/(2 tau)
  // u^{q-1} - K_V u^q.
  for (int q = 1; q < substeps; ++q) {
    ApplyWaveStiffness(u1_.data(), v1_.data(), ku_.data(), kv_.data());
    const double it2 = 1.0 / (tau * tau), i2t = 0.5 / tau;
    double *u0 = u0_.data(), *v0 = v0_.data();
    const double *u1 = u1_.data(), *v1 = v1_.data(), *ku = ku_.data(), *kv = kv_.data();
    const double* srcu = tendency_ ? srcu_.data() : nullptr;
    const double* srcv = tendency_ ? srcv_.data() : nullptr;
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      if (unknown[k] == 0.0) {
        u0[k] = u1[k];
        v0[k] = v1[k];
        continue;
      }
      const double lhs = m[k] * it2 + mo[k] * i2t;
      const double su = srcu ? srcu[k] : 0.0, sv = srcv ? srcv[k] : 0.0;
      u0[k] = (m[k] * it2 * (2.0 * u1[k] - u0[k]) + mo[k] * i2t * u0[k] - ku[k] + su) / lhs;
      v0[k] = (m[k] * it2 * (2.0 * v1[k] - v0[k]) + mo[k] * i2t * v0[k] - kv[k] + sv) / lhs;
    }
    nodes_.SyncPeriodic(u0);
    nodes_.SyncPeriodic(v0);
    std::swap(u0_, u1_);
    std::swap(v0_, v1_);
  }
  if (taylor_viscosity_ > 0.0) RemoveTaylorTerm();
  if (tendency_) {
    double *u1 = u1_.data(), *v1 = v1_.data();
    const double *ru = ru_.data(), *rv = rv_.data(), *eu = epsu_.data(), *ev = epsv_.data();
    const double half_dt2 = 0.5 * dt_ * dt_;
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      u1[k] -= dt * ru[k] + half_dt2 * eu[k];
      v1[k] -= dt * rv[k] + half_dt2 * ev[k];
    }
  }
  // Diffusion: (rho/dt) M u + nu_b K u = (rho/dt) M u_adv, Dirichlet data of t^{n+1}.
  if (helmholtz_) {
    double *fu = u0_.data(), *fv = v0_.data();
    const double *ua = u1_.data(), *va = v1_.data();
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      fu[k] = rho_over_dt_ * m[k] * ua[k];
      fv[k] = rho_over_dt_ * m[k] * va[k];
      u[k] = ua[k];
      v[k] = va[k];
    }
    boundary_data_.Apply(u, v);
    helmholtz_->SolvePair(fu, u, fv, v);
    report.fast_solves = 2;
  } else {
    ParallelCopy(u1_.data(), n, u);
    ParallelCopy(v1_.data(), n, v);
    boundary_data_.Apply(u, v);
  }
  return report;
}

}  // namespace dlmfd
