// The DLM step (37), composed of its coupling operator, rigid modes and CG; see
// particles/rigid_body_constraint.h.
#include "dlmfd/particles/rigid_body_constraint.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "dlmfd/core/errors.h"
#include "dlmfd/particles/particle_rules.h"

namespace dlmfd {

namespace {

// Relative round-off level of a converged mismatch, in units of the velocity scale.
constexpr double kRoundOffFloor = 1e-11;

}  // namespace

RigidBodyConstraint::RigidBodyConstraint(const Params& params, const Grid& grid)
    : tolerance_(params.solvers.multiplier_tolerance) {
  // The parameter rules of (37) (particles/particle_rules.h, which the scene validation applies
  // too): the grid that E can index, and the particles that the CG can solve for.
  RequireIndexableGrid(params, grid);
  const double fluid_density = params.fluid.density;
  const std::size_t n = params.particles.size();
  points_ = MultiplierPoints(params.particle_mesh, params.domain.h);
  std::vector<RigidModes::Body> bodies(n);
  for (std::size_t p = 0; p < n; ++p) {
    const ParticleParams& pp = params.particles[p];
    const Shape shape = Shape::Of(pp);
    points_.Add(shape);
    const double excess_mass = shape.Mass(pp.density - fluid_density);
    const bool free = pp.motion == Motion::kFree;
    const bool neutral = free && pp.density == fluid_density;
    bodies[p].neutral = neutral;
    if (free && !neutral) {
      RequireNotLighterThanLiquid(params, p);
      bodies[p].inv_excess_mass = 1.0 / excess_mass;
      bodies[p].inv_excess_inertia = shape.InverseMomentOfInertia(excess_mass);
    }
  }
  modes_ = RigidModes(points_, bodies);
  coupling_ = CouplingOperator(params, grid, points_.Total());
  cg_ =
      MultiplierCg(points_, coupling_.MaxSlots(), params.solvers.multiplier_max_iterations,
                   params.solvers.multiplier_preconditioner == MultiplierPreconditioning::kBlocks);
  force_sum_.assign(n, Vec2::Zero());
  torque_sum_.assign(n, 0.0);
}

RigidBodyConstraint::Outcome RigidBodyConstraint::Enforce(double time, double dt,
                                                          std::vector<ParticleState>& particles,
                                                          double* u, double* v) {
  return Enforce(time, dt, particles, u, v, nullptr);
}

RigidBodyConstraint::Outcome RigidBodyConstraint::Enforce(
    double time, double dt, std::vector<ParticleState>& particles, double* u, double* v,
    const Vec2* net_force, bool increment, const double* net_torque, const double* mismatch_shift) {
  Outcome outcome;
  const std::size_t n = particles.size();
  if (n == 0) return outcome;
  Orient(particles);
  coupling_.Build(time, dt, points_, particles);
  const ConstraintOperators op{points_, coupling_, modes_};
  cg_.Start(particles);

  // Cold-start mismatch (unprojected for the report); its projection, after the particular forces
  // of the neutral particles, is the absolute reference of the stopping rule.
  cg_.Mismatch(op, u, v);
  if (mismatch_shift) cg_.ShiftMismatch(mismatch_shift);
  outcome.cold_residual = cg_.MaxMismatch();
  double scale = 0.0, floor_weight = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    const ParticleState& particle = particles[p];
    scale = std::max(scale, particle.velocity.norm() +
                                std::abs(particle.angular_velocity) * points_.BoundingRadius(p));
    floor_weight += points_.RoundOffWeight(p);
  }
  scale = std::max(scale, outcome.cold_residual);
  cg_.ProjectMismatch(op);
  cg_.AddParticularForces(op, dt, net_force, net_torque, u, v);
  const double cold = cg_.MismatchNorm2(op);
  // An increment is solved to the tolerance of the mismatch the stored multiplier holds, as the
  // whole multiplier would be, not of its own cold mismatch, which shrinks as the lag settles.
  const double reference =
      increment ? std::max(cold, cg_.StoredResponseNorm2(op, dt, particles)) : cold;
  const double threshold = std::max(tolerance_ * tolerance_ * reference,
                                    kRoundOffFloor * kRoundOffFloor * scale * scale * floor_weight);

  double gg = cold;
  // The stored multiplier is a warm start for nu, not for an increment of it.
  if (cold > threshold && !increment) {
    outcome.warm_start = cg_.WarmStart(op, dt, particles, u, v, gg);
  }
  outcome.iterations = cg_.Solve(op, time, dt, threshold, gg, u, v);
  coupling_.CopyPeriodicDuplicates(u, v);
  cg_.RecoverNeutralMotion(op, u, v);

  // The true residual, the new particle velocities, and the nodal force sums.
  cg_.Mismatch(op, u, v);
  if (mismatch_shift) cg_.ShiftMismatch(mismatch_shift);
  outcome.residual = cg_.MaxMismatch();
  for (std::size_t p = 0; p < n; ++p) {
    ParticleState& particle = particles[p];
    if (particle.motion == Motion::kFree) {
      particle.velocity = cg_.Velocity(p);
      particle.angular_velocity = cg_.AngularVelocity(p);
    }
    const double* nu = cg_.Forces() + 2 * points_.Begin(p);
    if (increment && !IsNeutral(p) && particle.multiplier.size() == MultiplierSize(p)) {
      for (std::size_t k = 0; k < MultiplierSize(p); ++k) particle.multiplier[k] += nu[k];
    } else {
      particle.multiplier.assign(nu, nu + MultiplierSize(p));  // allocates only on the first step
    }
    modes_.NetForceAndTorque(points_, p, nu, force_sum_[p], torque_sum_[p]);
  }
  return outcome;
}

void RigidBodyConstraint::Locate(double time, double dt,
                                 const std::vector<ParticleState>& particles) {
  Orient(particles);
  coupling_.Build(time, dt, points_, particles);
}

void RigidBodyConstraint::Orient(const std::vector<ParticleState>& particles) {
  for (std::size_t p = 0; p < particles.size(); ++p) {
    if (points_.Turn(p, particles[p].angle)) modes_.Refresh(points_, points_.SetIndex(p));
  }
}

int RigidBodyConstraint::SolveResponse(double time, double dt,
                                       const std::vector<ParticleState>& particles,
                                       const double* mismatch, double tolerance, double* forces,
                                       double* scratch_u, double* scratch_v) {
  const ConstraintOperators op{points_, coupling_, modes_};
  cg_.Start(particles);
  cg_.SetMismatch(mismatch);
  cg_.ProjectMismatch(op);
  double gg = cg_.MismatchNorm2(op);
  const int iterations =
      cg_.Solve(op, time, dt, tolerance * tolerance * gg, gg, scratch_u, scratch_v);
  std::copy(cg_.Forces(), cg_.Forces() + 2 * points_.Total(), forces);
  return iterations;
}

}  // namespace dlmfd
