#include "dlmfd/conformation/oldroyd_b_polymer.h"

#include <algorithm>
#include <cmath>

#include "../mesh/grid_kernels.h"
#include "dlmfd/conformation/polymer_force.h"
#include "dlmfd/core/parallel_copy.h"

namespace dlmfd {

OldroydBPolymer::OldroydBPolymer(const Params& params, const Grid& grid)
    : grid_(grid),
      domain_(params.domain),
      lambda_(params.fluid.relaxation_time),
      devss_(params.fluid.Devss()),
      devss_weight_(params.fluid.DevssWeight(grid.h)),
      step_(params, grid),
      fx_(grid.NodeCount(), 0.0),
      fy_(grid.NodeCount(), 0.0) {
  // After step_: its constructor rejects a Newtonian liquid (lambda = 0) first.
  modulus_ = params.fluid.PolymerModulus();
  if (!params.particles.empty()) inside_particle_.assign(grid.NodeCount(), 0);
  if (!step_.model().StressIsAMinusI() || devss_) {
    s11_.assign(grid.NodeCount(), 1.0);
    s12_.assign(grid.NodeCount(), 0.0);
    s22_.assign(grid.NodeCount(), 1.0);
  }
}

void OldroydBPolymer::SetInitialState(FlowState& state) {
  state.a11.assign(grid_.NodeCount(), 1.0);
  state.a12.assign(grid_.NodeCount(), 0.0);
  state.a22.assign(grid_.NodeCount(), 1.0);
  step_.SetInflowState(state.u.data(), state.v.data(), state.a11.data(), state.a12.data(),
                       state.a22.data());
  if (devss_) {
    state.d11.assign(grid_.NodeCount(), 0.0);
    state.d12.assign(grid_.NodeCount(), 0.0);
    state.d22.assign(grid_.NodeCount(), 0.0);
  }
}

NodeForce OldroydBPolymer::MomentumForce(const FlowState& state) {
  ParallelFill(fx_.data(), static_cast<long>(fx_.size()), 0.0);
  ParallelFill(fy_.data(), static_cast<long>(fy_.size()), 0.0);
  // tau_p = G (S - I): S = A, or T(A) + I for the models whose T(A) is not A - I, and with devss
  // S - 2 w lambda D_h; the force reads S as it reads A.
  const RelaxationModel& model = step_.model();
  const long n = static_cast<long>(grid_.NodeCount());
  const double *s11 = state.a11.data(), *s12 = state.a12.data(), *s22 = state.a22.data();
  if (!model.StressIsAMinusI()) {
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      const SymTensor t = model.Stress(SymTensor{state.a11[k], state.a12[k], state.a22[k]});
      s11_[k] = t.a11 + 1.0;
      s12_[k] = t.a12;
      s22_[k] = t.a22 + 1.0;
    }
    s11 = s11_.data(), s12 = s12_.data(), s22 = s22_.data();
  }
  if (devss_) {
    const double two_lambda = 2.0 * devss_weight_ * lambda_;
    const double *d11 = state.d11.data(), *d12 = state.d12.data(), *d22 = state.d22.data();
#pragma omp parallel for schedule(static)
    for (long k = 0; k < n; ++k) {
      s11_[k] = s11[k] - two_lambda * d11[k];
      s12_[k] = s12[k] - two_lambda * d12[k];
      s22_[k] = s22[k] - two_lambda * d22[k];
    }
    s11 = s11_.data(), s12 = s12_.data(), s22 = s22_.data();
  }
  AddPolymerForce(grid_, domain_, modulus_, s11, s12, s22, fx_.data(), fy_.data());
  return NodeForce{fx_.data(), fy_.data(), s11, s12, s22, modulus_};
}

void OldroydBPolymer::Update(double dt, FlowState& state, StepReport& report,
                             const unsigned char* inside_nodes) {
  const unsigned char* inside = inside_nodes;
  if (inside == nullptr && !inside_particle_.empty()) {
    MarkParticleNodes(state.particles);
    inside = inside_particle_.data();
  }
  step_.Advance(state.time, dt, state.u.data(), state.v.data(), inside, state.a11.data(),
                state.a12.data(), state.a22.data(), report);
  if (devss_) step_.StrainRate(inside, state.d11.data(), state.d12.data(), state.d22.data());
}

void OldroydBPolymer::MarkParticleNodes(const std::vector<ParticleState>& particles) {
  std::fill(inside_particle_.begin(), inside_particle_.end(), 0);
  const bool px = domain_.PeriodicX(), py = domain_.PeriodicY();
  for (const ParticleState& q : particles) {
    const double r = q.radius;
    int i_lo, i_hi, j_lo, j_hi;
    kernels::CoveredNodes(q.position.x() - r, q.position.x() + r, grid_.x0, grid_.h, grid_.nx, px,
                          &i_lo, &i_hi);
    kernels::CoveredNodes(q.position.y() - r, q.position.y() + r, grid_.y0, grid_.h, grid_.ny, py,
                          &j_lo, &j_hi);
    for (int jj = j_lo; jj <= j_hi; ++jj) {
      const double dy = grid_.Y(jj) - q.position.y();
      const int j = py ? kernels::Wrap(jj, grid_.ny) : jj;
      for (int ii = i_lo; ii <= i_hi; ++ii) {
        const double dx = grid_.X(ii) - q.position.x();
        if (dx * dx + dy * dy >= r * r) continue;
        // An ellipse: inside in its body frame, (dx, dy) turned back by its angle.
        if (q.shape == ShapeKind::kEllipse) {
          const double c = std::cos(q.angle), s = std::sin(q.angle);
          const double bx = (c * dx + s * dy) / q.semi_axes.x();
          const double by = (c * dy - s * dx) / q.semi_axes.y();
          if (bx * bx + by * by >= 1.0) continue;
        }
        const int i = px ? kernels::Wrap(ii, grid_.nx) : ii;
        inside_particle_[grid_.Index(i, j)] = 1;
        // The repeated last node of a periodic line mirrors the first.
        if (px && i == 0) inside_particle_[grid_.Index(grid_.nx, j)] = 1;
        if (py && j == 0) inside_particle_[grid_.Index(i, grid_.ny)] = 1;
        if (px && py && i == 0 && j == 0) inside_particle_[grid_.Index(grid_.nx, grid_.ny)] = 1;
      }
    }
  }
}

}  // namespace dlmfd
