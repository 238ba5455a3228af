#include "dlmfd/conformation/conformation_step.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "../mesh/grid_kernels.h"
#include "dlmfd/conformation/conformation_representation.h"
#include "dlmfd/conformation/inflow_state.h"
#include "dlmfd/conformation/model_pointwise_update.h"
#include "dlmfd/conformation/pointwise_update.h"
#include "dlmfd/conformation/velocity_gradient.h"
#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

// More advection sub-steps than this mean a velocity no fluid step could have produced stably.
constexpr int kMaxConformationSubsteps = 1000;

double CheckedRelaxationTime(const Params& params) {
  if (params.fluid.IsNewtonian()) {
    std::ostringstream value;
    value << params.fluid.relaxation_time;
    throw InvalidParameter(
        "fluid.relaxation_time", value.str(),
        "> 0 with solvent_ratio < 1 for a conformation step (Newtonian scenes have none)");
  }
  return params.fluid.relaxation_time;
}

}  // namespace

ConformationStep::ConformationStep(const Params& params, const Grid& grid)
    : grid_(grid),
      lambda_(CheckedRelaxationTime(params)),
      model_(MakeRelaxationModel(params.fluid)),
      oldroyd_b_(params.fluid.model == ConstitutiveModel::kOldroydB),
      representation_(params.fluid.conformation),
      max_courant_(params.conformation.max_courant),
      periodic_x_(params.domain.PeriodicX()),
      periodic_y_(params.domain.PeriodicY()),
      diagonals_(params.domain.diagonals),
      advection_(grid, params.domain.PeriodicX(), params.domain.PeriodicY(),
                 params.conformation.blend_kappa) {
  const DomainParams& domain = params.domain;
  struct SideWalk {
    Side side;
    int i0, j0, di, dj, count;
    double nx, ny;
  };
  const SideWalk walks[4] = {{Side::kLeft, 0, 0, 0, 1, grid.ny + 1, -1.0, 0.0},
                             {Side::kRight, grid.nx, 0, 0, 1, grid.ny + 1, 1.0, 0.0},
                             {Side::kBottom, 0, 0, 1, 0, grid.nx + 1, 0.0, -1.0},
                             {Side::kTop, 0, grid.ny, 1, 0, grid.nx + 1, 0.0, 1.0}};
  for (const SideWalk& w : walks) {
    if (domain.side(w.side).type != SideType::kVelocity) continue;
    for (int k = 0; k < w.count; ++k) {
      const SymTensor inflow = InflowConformation(grid, domain, w.side, k, lambda_, *model_);
      Mat2 l{0.0, 0.0, 0.0, 0.0};
      InflowGradient(grid, domain, w.side, k, &l);
      boundary_.push_back(BoundaryNode{w.i0 + k * w.di, w.j0 + k * w.dj, w.nx, w.ny, inflow,
                                       ToRepresentation(representation_, inflow),
                                       SymTensor{l.m11, 0.5 * (l.m12 + l.m21), l.m22}});
    }
  }
  const std::size_t n = grid.NodeCount();
  inflow_.assign(n, 0);
  l11_.assign(n, 0.0);
  l12_.assign(n, 0.0);
  l21_.assign(n, 0.0);
  l22_.assign(n, 0.0);
  if (representation_ != ConformationRepresentation::kStandard) {
    // Psi or B need not be SPD: exp(Psi) and B^2 are, so the advection runs without the blend.
    advection_.SetSpdBlend(false);
    r11_.assign(n, 0.0);
    r12_.assign(n, 0.0);
    r22_.assign(n, 0.0);
  }
}

void ConformationStep::FindInflow(const double* u, const double* v) {
  for (const BoundaryNode& b : boundary_) inflow_[grid_.Index(b.i, b.j)] = 0;
  for (BoundaryNode& b : boundary_) {
    const std::size_t k = grid_.Index(b.i, b.j);
    b.active = u[k] * b.nx + v[k] * b.ny < 0.0;
    if (b.active) inflow_[k] = 1;
  }
}

void ConformationStep::SetInflowState(const double* u, const double* v, double* a11, double* a12,
                                      double* a22) {
  FindInflow(u, v);
  WriteAtInflowNodes(&BoundaryNode::inflow, a11, a12, a22);
}

void ConformationStep::CheckField(double time, const char* when, const double* a11,
                                  const double* a12, const double* a22) const {
  const long n = static_cast<long>(grid_.NodeCount());
  long first_bad = n;
#pragma omp parallel for schedule(static) reduction(min : first_bad)
  for (long k = 0; k < n; ++k) {
    const SymTensor a{a11[k], a12[k], a22[k]};
    if (GershgorinLowerBound(a) > 0.0 && IsFinite(a)) continue;  // SPD without the eigenvalues
    if (!IsFinite(a) || !(MinEigenvalue(a) > 0.0)) first_bad = std::min(first_bad, k);
  }
  if (first_bad < n)
    ThrowBadNode(time, when, first_bad, SymTensor{a11[first_bad], a12[first_bad], a22[first_bad]});
}

void ConformationStep::ThrowBadNode(double time, const char* when, long k,
                                    const SymTensor& a) const {
  const auto [i, j] = kernels::NodeAt(grid_, static_cast<std::size_t>(k));
  std::ostringstream msg;
  msg.precision(6);
  const bool finite = IsFinite(a);
  msg << (finite ? "conformation tensor A not positive definite"
                 : "conformation tensor A not finite")
      << " " << when << " step (35) at t = " << time << ": node (" << i << ", " << j
      << ") at (x, y) = (" << grid_.X(i) << ", " << grid_.Y(j) << "): ";
  if (finite) msg << "lambda_min(A) = " << MinEigenvalue(a) << ", ";
  msg << "A11 = " << a.a11 << ", A12 = " << a.a12 << ", A22 = " << a.a22;
  if (finite) throw ConformationNotPositiveDefinite(msg.str());
  throw NumericalBlowUp(msg.str());
}

// NOLINTNEXTLINE(readability-function-size): predates the limit; split it when you change it
void ConformationStep::Advance(double time, double dt, const double* u, const double* v,
                               const unsigned char* inside_particle, double* a11, double* a12,
                               double* a22, StepReport& report) {
  CheckField(time, "before", a11, a12, a22);

  NodeVelocityGradient(grid_, periodic_x_, periodic_y_, u, v, l11_.data(), l12_.data(), l21_.data(),
                       l22_.data(), diagonals_);
  const long n = static_cast<long>(grid_.NodeCount());
  double max_speed = 0.0, max_gradient = 0.0;
  long first_bad_velocity = n;
#pragma omp parallel for schedule(static) reduction(max                        \
                                                    : max_speed, max_gradient) \
    reduction(min                                                              \
              : first_bad_velocity)
  for (long k = 0; k < n; ++k) {
    const double speed = std::abs(u[k]) + std::abs(v[k]);
    const double gradient = FrobeniusNorm(Mat2{l11_[k], l12_[k], l21_[k], l22_[k]});
    if (!std::isfinite(speed) || !std::isfinite(gradient))
      first_bad_velocity = std::min(first_bad_velocity, k);
    max_speed = std::max(max_speed, speed);
    max_gradient = std::max(max_gradient, gradient);
  }
  if (first_bad_velocity < n) {
    const auto [i, j] = kernels::NodeAt(grid_, static_cast<std::size_t>(first_bad_velocity));
    std::ostringstream msg;
    msg << "velocity or its gradient not finite in step (35) at t = " << time << ": node (" << i
        << ", " << j << ") at (x, y) = (" << grid_.X(i) << ", " << grid_.Y(j)
        << "): u = " << u[first_bad_velocity] << ", v = " << v[first_bad_velocity];
    throw NumericalBlowUp(msg.str());
  }

  // 1. Advection, sub-cycled so that (|u| + |v|) tau / h <= max_courant.
  // The 1e-12 slack keeps a Courant ratio of exactly 3 (up to round-off) at 3 sub-steps.
  const double courant_ratio = dt * max_speed / (grid_.h * max_courant_);
  if (courant_ratio > kMaxConformationSubsteps) {
    std::ostringstream msg;
    msg << "advective Courant number " << dt * max_speed / grid_.h
        << " in step (35) at t = " << time << " (max |u| + |v| = " << max_speed
        << ") would need more than " << kMaxConformationSubsteps
        << " conformation sub-steps: the velocity is beyond any bound the time step can follow";
    throw NumericalBlowUp(msg.str());
  }
  const int substeps = std::max(1, static_cast<int>(std::ceil(courant_ratio * (1.0 - 1e-12))));
  const double tau = dt / substeps;
  FindInflow(u, v);
  advection_.ClearFixed();
  for (const BoundaryNode& b : boundary_) {
    if (b.active) advection_.AddFixed(b.i, b.j, b.inflow_advected);
  }
  const bool standard = representation_ == ConformationRepresentation::kStandard;
  if (standard) {
    advection_.Load(a11, a12, a22);
  } else {
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      const SymTensor x = ToRepresentation(representation_, SymTensor{a11[k], a12[k], a22[k]});
      r11_[k] = x.a11;
      r12_[k] = x.a12;
      r22_[k] = x.a22;
    }
    advection_.Load(r11_.data(), r12_.data(), r22_.data());
  }
  long blended = 0;
  for (int s = 0; s < substeps; ++s) blended += advection_.SubStep(tau, u, v);
  if (!standard) {
    // Back to A at every node: the advected A of the pointwise update.
#pragma omp parallel for schedule(static)
    for (int j = 0; j <= grid_.ny; ++j) {
      for (int i = 0; i <= grid_.nx; ++i) {
        const std::size_t k = grid_.Index(i, j);
        const SymTensor a = FromRepresentation(representation_, advection_.At(i, j));
        r11_[k] = a.a11;
        r12_[k] = a.a12;
        r22_[k] = a.a22;
      }
    }
  }

  // 2. The exact pointwise update (a vectorised one-panel row kernel, the general rule where it
  // does not apply); 3. A = I inside particles. Then the result is checked row by row.
  const int nx = grid_.nx, ny = grid_.ny;
  const ExponentialIntegrator integrator(dt, lambda_);
  const OnePanelConstants constants = integrator.Constants();
  long first_bad = n, first_outside = n;
  double min_eig = std::numeric_limits<double>::infinity();
  double max_trace = -std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(static) reduction(min                                  \
                                                    : first_bad, first_outside, min_eig) \
    reduction(max                                                                        \
              : max_trace)
  for (int j = 0; j <= ny; ++j) {
    const std::size_t row = grid_.Index(0, j);
    // The advected A of row j (the advection's own rows in the standard representation).
    const double* adv11 = standard ? advection_.Row(0, j) : r11_.data() + row;
    const double* adv12 = standard ? advection_.Row(1, j) : r12_.data() + row;
    const double* adv22 = standard ? advection_.Row(2, j) : r22_.data() + row;
    if (oldroyd_b_) {
      OnePanelRow(nx + 1, constants, adv11, adv12, adv22, l11_.data() + row, l12_.data() + row,
                  l21_.data() + row, l22_.data() + row, a11 + row, a12 + row, a22 + row);
    }
    for (int i = 0; i <= nx; ++i) {
      const std::size_t k = row + i;
      if (inflow_[k]) continue;  // A_L, set below
      SymTensor a{a11[k], a12[k], a22[k]};
      const Mat2 l{l11_[k], l12_[k], l21_[k], l22_[k]};
      if (inside_particle != nullptr && inside_particle[k] != 0) {
        a = SymTensor{};
      } else if (!oldroyd_b_) {
        const SymTensor advected{adv11[i], adv12[i], adv22[i]};
        if (!model_->Admits(advected) ||
            !ModelPointwiseStep(*model_, advected, l, dt, lambda_, &a)) {
          first_outside = std::min(first_outside, static_cast<long>(k));
        }
      } else if (!OnePanelApplies(constants, l)) {
        a = integrator.Apply(SymTensor{adv11[i], adv12[i], adv22[i]}, l);
      }
      a11[k] = a.a11;
      a12[k] = a.a12;
      a22[k] = a.a22;
      // min over nodes of lambda_min: Gershgorin's min(A11, A22) - |A12| <= lambda_min, so a node
      // whose bound is not below min_eig cannot lower it (min(A11, A22) is an upper bound).
      const double bound = GershgorinLowerBound(a);
      const bool spd = bound > 0.0 && IsFinite(a);
      if (!spd || bound < min_eig) {
        const double m = MinEigenvalue(a);
        if (!IsFinite(a) || !(m > 0.0)) first_bad = std::min(first_bad, static_cast<long>(k));
        min_eig = std::min(min_eig, m);
      }
      max_trace = std::max(max_trace, Trace(a));
    }
  }
  if (first_outside < n) {
    const auto [i, j] = kernels::NodeAt(grid_, static_cast<std::size_t>(first_outside));
    const std::size_t k = static_cast<std::size_t>(first_outside);
    const SymTensor advected =
        standard ? advection_.At(i, j) : SymTensor{r11_[k], r12_[k], r22_[k]};
    std::ostringstream msg;
    msg << "conformation tensor A left the states of the " << model_->Name()
        << " model in step (35) at t = " << time << ": node (" << i << ", " << j
        << ") at (x, y) = (" << grid_.X(i) << ", " << grid_.Y(j)
        << "): after advection A11 = " << advected.a11 << ", A12 = " << advected.a12
        << ", A22 = " << advected.a22
        << " (fene_p: tr A < fluid.extensibility; ptt_linear: 1 + epsilon tr(A - I) > 0)";
    throw NumericalBlowUp(msg.str());
  }
  if (first_bad < n) {
    ThrowBadNode(time + dt, "after", first_bad,
                 SymTensor{a11[first_bad], a12[first_bad], a22[first_bad]});
  }
  // 3. A = A_L on inflow nodes (SPD by construction); periodic duplicates equal to the first node.
  WriteAtInflowNodes(&BoundaryNode::inflow, a11, a12, a22);
  for (const BoundaryNode& b : boundary_) {
    if (!b.active) continue;
    min_eig = std::min(min_eig, MinEigenvalue(b.inflow));
    max_trace = std::max(max_trace, Trace(b.inflow));
  }
  if (periodic_x_) {
    for (int j = 0; j <= ny; ++j) {
      const std::size_t first = grid_.Index(0, j), last = grid_.Index(nx, j);
      a11[last] = a11[first];
      a12[last] = a12[first];
      a22[last] = a22[first];
    }
  }
  if (periodic_y_) {
    std::copy_n(a11 + grid_.Index(0, 0), nx + 1, a11 + grid_.Index(0, ny));
    std::copy_n(a12 + grid_.Index(0, 0), nx + 1, a12 + grid_.Index(0, ny));
    std::copy_n(a22 + grid_.Index(0, 0), nx + 1, a22 + grid_.Index(0, ny));
  }

  report.Set("min_eig_A", min_eig);
  report.Set("max_trA", max_trace);
  report.Set("elastic_courant", lambda_ * max_gradient * dt);
  report.Set("blended_nodes", static_cast<double>(blended));
  report.Set("conformation_substeps", substeps);
}

void ConformationStep::StrainRate(const unsigned char* inside_particle, double* d11, double* d12,
                                  double* d22) const {
  const long n = static_cast<long>(grid_.NodeCount());
#pragma omp parallel for schedule(static)
  for (long k = 0; k < n; ++k) {
    const bool rigid = inside_particle != nullptr && inside_particle[k] != 0;
    d11[k] = rigid ? 0.0 : l11_[k];
    d12[k] = rigid ? 0.0 : 0.5 * (l12_[k] + l21_[k]);
    d22[k] = rigid ? 0.0 : l22_[k];
  }
  // Inflow nodes: the strain rate of the profile that A_L is the steady state of.
  WriteAtInflowNodes(&BoundaryNode::inflow_strain_rate, d11, d12, d22);
}

void ConformationStep::WriteAtInflowNodes(SymTensor BoundaryNode::*value, double* t11, double* t12,
                                          double* t22) const {
  for (const BoundaryNode& b : boundary_) {
    if (!b.active) continue;
    const std::size_t k = grid_.Index(b.i, b.j);
    const SymTensor& t = b.*value;
    t11[k] = t.a11;
    t12[k] = t.a12;
    t22[k] = t.a22;
  }
}

}  // namespace dlmfd
