// The last step's multiplier in the Stokes step (33); see particles/lagged_multiplier.h.
#include "dlmfd/particles/lagged_multiplier.h"

#include <algorithm>

namespace dlmfd {

LaggedMultiplier::LaggedMultiplier(const RigidBodyConstraint& constraint,
                                   const std::vector<char>& held)
    : held_(held) {
  const MultiplierPoints& points = constraint.Points();
  stacked_.assign(2 * points.Total(), 0.0);
  slot_uv_.assign(constraint.coupling().SlotFieldSize(), 0.0);
  force_sum_.assign(points.ParticleCount(), Vec2::Zero());
  torque_sum_.assign(points.ParticleCount(), 0.0);
  for (char h : held_) any_held_ = any_held_ || h != 0;
  shift_.assign(any_held_ ? 2 * points.Total() : 0, 0.0);
}

void LaggedMultiplier::Apply(double time, double dt, RigidBodyConstraint& constraint,
                             const std::vector<ParticleState>& particles, double* u, double* v) {
  constraint.Locate(time, dt, particles);
  const MultiplierPoints& points = constraint.Points();
  const CouplingOperator& coupling = constraint.coupling();
  for (std::size_t p = 0; p < particles.size(); ++p) {
    double* block = stacked_.data() + 2 * points.Begin(p);
    const std::vector<double>& nu = particles[p].multiplier;
    if (constraint.IsNeutral(p)) {
      std::fill(block, block + nu.size(), 0.0);  // not lagged (see the header)
    } else {
      std::copy(nu.begin(), nu.end(), block);
    }
    constraint.modes().NetForceAndTorque(points, p, block, force_sum_[p], torque_sum_[p]);
  }
  coupling.Spread(stacked_.data(), slot_uv_.data());
  coupling.AddAtSlots(slot_uv_.data(), u, v);
  coupling.CopyPeriodicDuplicates(u, v);
}

// E u at every point of the held particles: visit(q, eu, ev) with q the stacked point.
template <class Visit>
void LaggedMultiplier::ForHeldPoints(const RigidBodyConstraint& constraint, const double* u,
                                     const double* v, Visit visit) const {
  const MultiplierPoints& points = constraint.Points();
  const CouplingOperator& coupling = constraint.coupling();
  for (std::size_t p = 0; p < held_.size(); ++p) {
    if (!held_[p]) continue;
    for (int k = 0; k < points.Count(p); ++k) {
      const std::size_t q = points.Begin(p) + k;
      double eu, ev;
      coupling.Interpolate(q, u, v, eu, ev);
      visit(q, eu, ev);
    }
  }
}

void LaggedMultiplier::SampleStokesVelocity(const RigidBodyConstraint& constraint, const double* u,
                                            const double* v) {
  ForHeldPoints(constraint, u, v, [&](std::size_t q, double eu, double ev) {
    shift_[2 * q] = eu;
    shift_[2 * q + 1] = ev;
  });
}

const double* LaggedMultiplier::AdvectionShift(const RigidBodyConstraint& constraint,
                                               const double* u, const double* v) {
  if (!any_held_) return nullptr;
  ForHeldPoints(constraint, u, v, [&](std::size_t q, double eu, double ev) {
    shift_[2 * q] -= eu;
    shift_[2 * q + 1] -= ev;
  });
  return shift_.data();
}

}  // namespace dlmfd
