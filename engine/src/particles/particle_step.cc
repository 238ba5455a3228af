// Predictor (36), DLM step (37), corrector (38) and the hydrodynamic force; see
// particles/particle_step.h.
#include "dlmfd/particles/particle_step.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/side_names.h"
#include "dlmfd/particles/multiplier_points.h"
#include "dlmfd/particles/particle_rules.h"

namespace dlmfd {

namespace {

std::vector<double> Radii(const Params& params) {
  std::vector<double> radii;
  for (const auto& p : params.particles) radii.push_back(p.Radius());
  return radii;
}

}  // namespace

ParticleStep::ParticleStep(const Params& params, const Grid& grid)
    : grid_(grid),
      gravity_(params.gravity),
      fluid_density_(params.fluid.density),
      substeps_(std::max(1, params.collisions.substeps)),
      periodic_x_(params.domain.PeriodicX()),
      periodic_y_(params.domain.PeriodicY()),
      constraint_(params, grid),
      collisions_(params, grid, Radii(params)) {
  const std::size_t n = params.particles.size();
  for (std::size_t p = 0; p < n; ++p) {
    const ParticleParams& pp = params.particles[p];
    shapes_.push_back(Shape::Of(pp));
    const double excess = shapes_[p].Mass(pp.density - fluid_density_);
    const bool heavy_free = pp.motion == Motion::kFree && !constraint_.IsNeutral(p);
    inv_excess_mass_.push_back(heavy_free ? 1.0 / excess : 0.0);
    predicted_.push_back(heavy_free ? 1 : 0);
  }
  for (auto* a : {&x_old_, &u_old_, &x_, &x_star_, &u_, &u_star_, &f0_, &f1_, &collision_average_,
                  &lag_accel_}) {
    a->assign(n, Vec2::Zero());
  }
  omega_old_.assign(n, 0.0);
  angle_old_.assign(n, 0.0);
  for (const Shape& shape : shapes_) shaped_ = shaped_ || !shape.IsDisk();
  if (shaped_) {
    collisions_.SetShapes(shapes_);
    angles_.assign(n, 0.0);
    torque0_.assign(n, 0.0);
    torque_average_.assign(n, 0.0);
    mean_rate_.assign(n, 0.0);
  }
  if (params.splitting.constraint.value() == ConstraintCoupling::kViscous && n > 0) {
    viscous_ = std::make_unique<ViscousConstraint>(params, grid);
    u_start_.assign(n, Vec2::Zero());
    omega_start_.assign(n, 0.0);
  }
  if (params.splitting.constraint.value() == ConstraintCoupling::kIncremental && n > 0) {
    // With the tendency correction the Stokes step's velocity is the field a steady state solves
    // for, so the fixed particles hold their constraint on it (particles/lagged_multiplier.h).
    const bool on_stokes =
        params.splitting.steady_correction.value() == SteadyCorrection::kTendency;
    std::vector<char> held(n, 0);
    for (std::size_t p = 0; p < n; ++p)
      held[p] = on_stokes && params.particles[p].motion == Motion::kFixed;
    lagged_ = std::make_unique<LaggedMultiplier>(constraint_, held);
  }
}

void ParticleStep::LagMultiplier(double time, double dt,
                                 const std::vector<ParticleState>& particles, double* u,
                                 double* v) {
  lagged_->Apply(time, dt, constraint_, particles, u, v);
  lag_applied_ = true;
}

void ParticleStep::SampleStokesVelocity(const double* u, const double* v) {
  lagged_->SampleStokesVelocity(constraint_, u, v);
}

ViscousConstraint::Outcome ParticleStep::CoupleStokes(double time, double dt, StokesSolver& stokes,
                                                      const double* fx, const double* fy,
                                                      std::vector<ParticleState>& particles,
                                                      double* u, double* v, double* p) {
  for (std::size_t k = 0; k < particles.size(); ++k) {
    u_start_[k] = particles[k].velocity;
    omega_start_[k] = particles[k].angular_velocity;
  }
  coupled_ = true;
  return viscous_->Solve(time, dt, gravity_, stokes, fx, fy, particles, u, v, p);
}

void ParticleStep::Predict(double dt, const Vec2& gravity, std::vector<ParticleState>& particles) {
  const std::size_t n = particles.size();
  const double tau = dt / substeps_;
  for (std::size_t p = 0; p < n; ++p) {
    x_[p] = particles[p].position;
    u_[p] = particles[p].velocity;
    collision_average_[p].setZero();
  }
  max_contacts_ = 0;
  if (shaped_) std::fill(torque_average_.begin(), torque_average_.end(), 0.0);
  for (int k = 1; k <= substeps_; ++k) {
    // The angles along the sub-steps: theta^n + omega^n t (omega is not predicted).
    TurnCollisions((k - 1.0) / substeps_ * dt, omega_old_);
    max_contacts_ = std::max(max_contacts_, collisions_.Compute(x_, f0_));
    if (shaped_) torque0_ = collisions_.Torques();
    for (std::size_t p = 0; p < n; ++p) {
      u_star_[p] =
          predicted_[p]
              ? Vec2(u_[p] + (gravity + lag_accel_[p] + inv_excess_mass_[p] * f0_[p]) * tau)
              : u_[p];
      x_star_[p] = x_[p] + 0.5 * (u_[p] + u_star_[p]) * tau;
    }
    TurnCollisions(static_cast<double>(k) / substeps_ * dt, omega_old_);
    collisions_.Compute(x_star_, f1_);
    if (shaped_) {
      for (std::size_t p = 0; p < n; ++p) {
        torque_average_[p] += 0.5 * (torque0_[p] + collisions_.Torques()[p]) / substeps_;
      }
    }
    for (std::size_t p = 0; p < n; ++p) {
      const Vec2 average = 0.5 * (f0_[p] + f1_[p]);
      collision_average_[p] += average / substeps_;
      const Vec2 previous = u_[p];
      // g (when the Stokes step did not carry it) and the lag's reaction (zero unless it ran).
      if (predicted_[p]) u_[p] += (gravity + lag_accel_[p] + inv_excess_mass_[p] * average) * tau;
      x_[p] += 0.5 * (previous + u_[p]) * tau;
    }
  }
  for (std::size_t p = 0; p < n; ++p) {
    particles[p].position = x_[p];
    particles[p].velocity = u_[p];
    // theta^{n+2/4} = theta^n + dt omega^n (omega is not predicted).
    particles[p].angle = angle_old_[p] + dt * omega_old_[p];
    // The collision torque of other shapes than disks: omega* = omega^n + dt T'_avg / I_e.
    if (shaped_ && predicted_[p]) {
      particles[p].angular_velocity +=
          dt * shapes_[p].InverseMomentFromInverseMass(inv_excess_mass_[p]) * torque_average_[p];
    }
  }
}

void ParticleStep::TurnTo(const std::vector<ParticleState>& particles) {
  if (!shaped_) return;
  for (std::size_t p = 0; p < angles_.size(); ++p) angles_[p] = particles[p].angle;
  collisions_.SetAngles(angles_);
}

void ParticleStep::TurnCollisions(double elapsed, const std::vector<double>& rate) {
  if (!shaped_) return;
  for (std::size_t p = 0; p < angles_.size(); ++p) angles_[p] = angle_old_[p] + elapsed * rate[p];
  collisions_.SetAngles(angles_);
}

void ParticleStep::Correct(double dt, std::vector<ParticleState>& particles) {
  const std::size_t n = particles.size();
  const double tau = dt / substeps_;
  const double push = dt * dt / (2.0 * substeps_);
  for (std::size_t p = 0; p < n; ++p) x_[p] = x_old_[p];
  // The angles along the sub-steps: theta^n + (omega^n + omega^{n+1})/2 t.
  if (shaped_) {
    for (std::size_t p = 0; p < n; ++p) {
      mean_rate_[p] = 0.5 * (omega_old_[p] + particles[p].angular_velocity);
    }
  }
  for (int k = 1; k <= substeps_; ++k) {
    TurnCollisions((k - 1.0) / substeps_ * dt, mean_rate_);
    collisions_.Compute(x_, f0_);
    for (std::size_t p = 0; p < n; ++p) {
      x_star_[p] = x_[p] + 0.5 * (u_old_[p] + particles[p].velocity) * tau;
    }
    TurnCollisions(static_cast<double>(k) / substeps_ * dt, mean_rate_);
    collisions_.Compute(x_star_, f1_);
    for (std::size_t p = 0; p < n; ++p) {
      x_[p] = x_star_[p] + inv_excess_mass_[p] * 0.5 * (f0_[p] + f1_[p]) * push;
    }
  }
  for (std::size_t p = 0; p < n; ++p) {
    Vec2 x = x_[p];
    if (periodic_x_) x.x() -= grid_.Width() * std::floor((x.x() - grid_.x0) / grid_.Width());
    if (periodic_y_) x.y() -= grid_.Height() * std::floor((x.y() - grid_.y0) / grid_.Height());
    particles[p].position = x;
    // theta^{n+1} = theta^n + (omega^n + omega^{n+1})/2 dt, the trapezoid rule of X's corrector.
    particles[p].angle = angle_old_[p] + 0.5 * (omega_old_[p] + particles[p].angular_velocity) * dt;
  }
}

void ParticleStep::CheckSeparated(double time, const std::vector<ParticleState>& particles,
                                  const CollisionForces::SurfaceGaps& gaps) {
  int first = -10, second = -10;
  gaps.Closest(&first, &second);
  const double gap = gaps.Min();
  if (!(gap < 0.0)) return;  // NaN: nothing to measure
  std::ostringstream what;
  what.precision(10);
  if (second >= 0) {
    what << "particles " << particles[first].id << " and " << particles[second].id
         << " overlap at t = " << time << " (gap = " << gap << ")";
  } else {
    what << "particle " << particles[first].id << " overlaps the " << SideName(-1 - second)
         << " side at t = " << time << " (gap = " << gap << ")";
  }
  throw ParticlesOverlap(what.str());
}

void ParticleStep::Advance(double time, double dt, std::vector<ParticleState>& particles, double* u,
                           double* v, StepReport& report) {
  const std::size_t n = particles.size();
  // U^n, omega^n: the velocities at the start of the step (before a coupled Stokes step).
  for (std::size_t p = 0; p < n; ++p) {
    x_old_[p] = particles[p].position;
    u_old_[p] = coupled_ ? u_start_[p] : particles[p].velocity;
    omega_old_[p] = coupled_ ? omega_start_[p] : particles[p].angular_velocity;
    angle_old_[p] = particles[p].angle;
  }
  // The reaction of the lagged multiplier nu^n, which acted on the fluid in (33) (D^-1 = 0 but
  // for the heavy free particles): a force over the predictor's sub-steps beside g, so that the
  // predicted positions follow the motion (the particle header); omega, not predicted, starts
  // from omega^n - dt (T^T nu^n) / I_e.
  for (std::size_t p = 0; p < n; ++p) {
    lag_accel_[p].setZero();
    if (!lag_applied_) continue;
    const double inv_inertia = shapes_[p].InverseMomentFromInverseMass(inv_excess_mass_[p]);
    lag_accel_[p] = -inv_excess_mass_[p] * lagged_->ForceSum(p);
    particles[p].angular_velocity -= dt * inv_inertia * lagged_->TorqueSum(p);
  }
  // Gravity acts in the coupled Stokes step when there is one, so that the excess weight meets
  // the viscous drag in the same solve; the predictor then carries the collision forces only.
  Predict(dt, coupled_ ? Vec2(Vec2::Zero()) : gravity_, particles);
  const double* shift = lag_applied_ ? lagged_->AdvectionShift(constraint_, u, v) : nullptr;
  const RigidBodyConstraint::Outcome outcome =
      constraint_.Enforce(time + dt, dt, particles, u, v, collision_average_.data(), lag_applied_,
                          shaped_ ? torque_average_.data() : nullptr, shift);
  Correct(dt, particles);

  for (std::size_t p = 0; p < n; ++p) {
    ParticleState& particle = particles[p];
    const double displaced_mass = shapes_[p].Mass(fluid_density_);
    const double inertia = shapes_[p].MomentOfInertia(particle.density);
    // The forces the particle exerted on the fluid nodes in (37), and in (33) when coupled there.
    Vec2 nodal_force = constraint_.NodalForceSum(p);
    double nodal_torque = constraint_.NodalTorqueSum(p);
    if (coupled_) {
      nodal_force += viscous_->NodalForceSum(p);
      nodal_torque += viscous_->NodalTorqueSum(p);
    }
    if (lag_applied_) {
      nodal_force += lagged_->ForceSum(p);
      nodal_torque += lagged_->TorqueSum(p);
    }
    particle.force =
        -nodal_force + displaced_mass * ((particle.velocity - u_old_[p]) / dt - gravity_);
    particle.torque = -nodal_torque + (fluid_density_ / particle.density) * inertia *
                                          (particle.angular_velocity - omega_old_[p]) / dt;
  }
  coupled_ = false;
  lag_applied_ = false;

  for (std::size_t p = 0; p < n; ++p) x_[p] = particles[p].position;
  TurnTo(particles);
  report.Set("multiplier_iterations", outcome.iterations);
  report.Set("multiplier_residual", outcome.residual);
  report.Set("multiplier_warm_start", outcome.warm_start ? 1.0 : 0.0);
  report.Set("collision_contacts", max_contacts_);
  const CollisionForces::SurfaceGaps gaps = collisions_.Gaps(x_);
  report.Set("particle_min_gap", gaps.Min());
  report.Set("particle_pair_gap", gaps.pair);
  report.Set("particle_wall_gap", gaps.wall);
  CheckSeparated(time + dt, particles, gaps);
}

std::vector<ParticleState> ParticleStep::InitialStates(const Params& params) {
  std::vector<ParticleState> states;
  const Grid grid = params.domain.VelocityGrid();
  // The scene rules of the particles (inside the domain, apart, DLM well posed), defined once in
  // particles/particle_rules.h and applied by the scene validation too.
  ValidateParticles(params, grid);
  // Cut cells (particles/cut_cell_step.h) have no multipliers.
  const bool multipliers = params.particle_mesh.kind != ParticleMeshKind::kCutCell;
  const MultiplierPoints points = multipliers
                                      ? MultiplierPoints::ForScene(params)
                                      : MultiplierPoints(params.particle_mesh, params.domain.h);
  for (std::size_t p = 0; p < params.particles.size(); ++p) {
    const ParticleParams& pp = params.particles[p];
    ParticleState s;
    s.id = static_cast<int>(p);
    s.position = pp.center;
    s.velocity = pp.velocity;
    s.angular_velocity = pp.angular_velocity;
    s.radius = pp.Radius();
    s.density = pp.density;
    s.angle = pp.angle;
    s.shape = pp.shape;
    s.semi_axes = pp.shape == ShapeKind::kDisk ? Vec2(pp.Radius(), pp.Radius()) : pp.semi_axes;
    s.motion = pp.motion;
    if (multipliers) s.multiplier.assign(2 * static_cast<std::size_t>(points.Count(p)), 0.0);
    states.push_back(std::move(s));
  }
  return states;
}

}  // namespace dlmfd
