// Step 4 of the Marchuk-Yanenko scheme: the particle predictor (36), the rigid-body (DLM) step (37)
// and the corrector (38), with the collision forces (14)-(15), and the hydrodynamic force and
// torque.
//
// Equations, in the corrected form of method notes 2, section 1.7 (typos of (36) and (38) fixed):
//   (36) for k = 1..K, free particles (g - C^T nu^n / m_e in place of g with the incremental
//        coupling, below):
//          U*^k = U^{k-1} + (g + F'(X^{k-1}) / m_e) dt/K,  X*^k = X^{k-1} + (U^{k-1} + U*^k)/2
//          dt/K, U^k  = U^{k-1} + (g + (F'(X^{k-1}) + F'(X*^k)) / (2 m_e)) dt/K, X^k  = X^{k-1} +
//          (U^{k-1} + U^k)/2 dt/K;   U^{n+2/4} = U^K, X^{n+2/4} = X^K;
//        omega is not predicted (central forces; other shapes than disks:
//        omega^{n+2/4} = omega^n + dt T'_avg / I_e with the sub-steps' mean collision torque, or
//        T'_avg passed to the fluid by a neutral one); theta^{n+2/4} = theta^n + dt omega^n.
//   (37) particles/rigid_body_constraint.h at X^{n+2/4}.
//   (38) X^{n+1,0} = X^n; for k = 1..K:
//          X*^k = X^{k-1} + (U^n + U^{n+1})/2 dt/K,
//          X^k  = X*^k + (F'(X^{k-1}) + F'(X*^k)) / (2 m_e) dt^2/(2K)     (dt^2/(2K), not
//          (dt/K)^2/2).
//   theta^{n+1} = theta^n + (omega^n + omega^{n+1})/2 dt (the angle; an ellipse's points turn).
//   m_e = (1 - rho_L/rho_d) M, M = rho_d pi R^2, I = M R^2/2 (an ellipse: M = rho_d pi a b,
//   I = M (a^2 + b^2)/4). Fixed particles stay; prescribed ones move at their given velocity;
//   neither feels F'.
//   Force exerted by the fluid (notes 1.6): F_h = -sum nu + rho_L pi R^2 ((U^{n+1} - U^n)/dt - g),
//   T_h = -sum r_perp . nu + (rho_L/rho_d) I (omega^{n+1} - omega^n)/dt. F_h includes the
//   hydrostatic buoyancy -rho_L pi R^2 g, because the fluid steps carry no gravity.
// Solver: see RigidBodyConstraint (CG in the H1 product). After (38): overlap check (d < R_i + R_j,
// or distance to a non-periodic side < R) throws ParticlesOverlap with ids, time and gap.
// Positions are wrapped into the domain across periodic sides after (38).
// Report columns: multiplier_iterations, multiplier_residual (max |E u - U - omega r_perp| at the
// multiplier nodes), multiplier_warm_start, collision_contacts (max over the predictor sub-steps),
// particle_pair_gap (the true smallest surface gap d - R_i - R_j over every pair),
// particle_wall_gap (the smallest distance of a particle's surface to a non-periodic side) and
// particle_min_gap (the smaller of the two); NaN where there is nothing to measure.
// Neutrally buoyant free particles (rho_d = rho_L, m_e = 0): gravity and buoyancy cancel, so (36)
//   keeps U^{n+2/4} = U^n (X^{n+2/4} = X^n + U^n dt), (38) has no push term, and the collision
//   force F'_avg of the predictor goes to the fluid through the constraint sum_k nu_k = F'_avg of
//   (37) (m_e (U - U^n)/dt = m_e g + F'_avg - sum nu with m_e = 0); the force identity below still
//   holds.
// With splitting.constraint = "viscous" the particles also enter the Stokes step (33)
// (CoupleStokes, particles/viscous_constraint.h), which carries their excess weight: then (36)
// has no g, the corrector's U^n is the velocity before (33), and the force adds the C^T nu of (33):
//   F_h = -C^T nu_(33) - C^T nu_(37) + rho_L V [(U^{n+1} - U^n)/dt - g]   (same identity).
// With splitting.constraint = "incremental" the last step's multiplier nu^n acts in (33)
// (LagMultiplier, particles/lagged_multiplier.h; not a neutral particle's) and (37) solves for its
// increment. Its reaction on the heavy free particles, -C^T nu^n / m_e, is a force of the step
// like g: (36) carries g - C^T nu^n / m_e in place of g over its sub-steps, and omega starts from
// omega^n - dt (T^T nu^n) / I_e. The force adds C^T nu^n:
//   F_h = -C^T nu^n - C^T d nu_(37) + rho_L V [(U^{n+1} - U^n)/dt - g]   (same identity).
// Why over the sub-steps, not as a kick at the start of (36): for a disk barely heavier than the
// liquid, C^T nu^n nearly cancels m_e g, and each alone moves U by dt g (18.8 at dt = 0.0192). As a
// kick, the predicted positions X*^k ran ahead of the motion by up to g dt^2 / 2 (0.18, 4.3 h at
// dt = 0.0192 on h = 1/24), met a wall's or a neighbour's collision range that the particle never
// came near, and the collision force over m_e blew the run up; and X^{n+2/4}, where (37) holds the
// particle, lay g dt^2 / 2 from X^{n+1} (1.7 h for Faxen's disk at h = 1/96, dt = 0.006), so the
// lag was spread at one place and its increment found at another. Those were failures 1, 3 and 4
// of docs/evidence/stability.md ("The coupling of the constraint"): with the force over the
// sub-steps X^{n+2/4} lies within dt^2 |dU/dt| / 2 of X^{n+1} and all three runs complete. Not
// supported: free particles with rho_d < rho_L; gamma != 0. References: Glowinski et al., J.
// Comput. Phys. 169 (2001) 363-426; Singh, Joseph, Hesla, Glowinski, Pan, J. Non-Newtonian Fluid
// Mech. 91 (2000) 165-188 (the paper); method notes 2, part 1.
#pragma once

#include <memory>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"
#include "dlmfd/particles/collision_forces.h"
#include "dlmfd/particles/lagged_multiplier.h"
#include "dlmfd/particles/rigid_body_constraint.h"
#include "dlmfd/particles/shape.h"
#include "dlmfd/particles/viscous_constraint.h"

namespace dlmfd {

class ParticleStep {
 public:
  // Throws InvalidParameter (see RigidBodyConstraint).
  ParticleStep(const Params& params, const Grid& grid);

  // Steps (36)-(38) for one time step: u, v hold u^{n+2/4} on entry and u^{n+1} on return;
  // particles hold (X^n, U^n, omega^n) on entry and (X^{n+1}, U^{n+1}, omega^{n+1}, F, T) on
  // return. time is t_n. Throws SolverNotConverged, ParticlesOverlap.
  void Advance(double time, double dt, std::vector<ParticleState>& particles, double* u, double* v,
               StepReport& report);

  // The particles of params at t = 0, with zero multipliers of the right size. Throws
  // InvalidParameter when two particles overlap or one crosses a non-periodic side.
  static std::vector<ParticleState> InitialStates(const Params& params);

  // True with splitting.constraint = "viscous": Simulation solves step (33) by CoupleStokes.
  bool CouplesStokes() const { return viscous_ != nullptr; }
  // Step (33) with the particles in it (particles/viscous_constraint.h), their excess weight
  // included; particles hold (X^n, U^n, omega^n) on entry and the coupled velocities of the free
  // particles on return, which the following Advance takes as U^{n+1/4} (its predictor then adds
  // the collision forces only); Advance's force then includes this step's C^T nu.
  ViscousConstraint::Outcome CoupleStokes(double time, double dt, StokesSolver& stokes,
                                          const double* fx, const double* fy,
                                          std::vector<ParticleState>& particles, double* u,
                                          double* v, double* p);

  // True with splitting.constraint = "incremental": Simulation calls LagMultiplier before (33).
  bool LagsMultiplier() const { return lagged_ != nullptr; }
  // Before (33): the particles' stored multipliers nu^n at X^n onto u, v as dt M^-1 E^T nu^n
  // (particles/lagged_multiplier.h); the following Advance adds their reaction and force.
  void LagMultiplier(double time, double dt, const std::vector<ParticleState>& particles, double* u,
                     double* v);

  // After (33) with the lagged multiplier: u, v hold u^{n+1/4}; the fixed particles' constraint
  // in the following Advance holds on it (particles/lagged_multiplier.h).
  void SampleStokesVelocity(const double* u, const double* v);

  // The sub-step average F'_avg of the collision force in the last predictor (36).
  const std::vector<Vec2>& CollisionForceAverage() const { return collision_average_; }
  const RigidBodyConstraint& constraint() const { return constraint_; }
  CollisionForces& collisions() { return collisions_; }

 private:
  // (36) with this gravity on the heavy free particles (zero after a coupled Stokes step).
  void Predict(double dt, const Vec2& gravity, std::vector<ParticleState>& particles);
  void Correct(double dt, std::vector<ParticleState>& particles);
  // Throws ParticlesOverlap when the gaps at the particles' positions (Gaps of the step's end)
  // are negative.
  void CheckSeparated(double time, const std::vector<ParticleState>& particles,
                      const CollisionForces::SurfaceGaps& gaps);
  // The collision forces see the particles turned to theta^n + elapsed rate (other shapes than
  // disks only), or to their angles.
  void TurnCollisions(double elapsed, const std::vector<double>& rate);
  void TurnTo(const std::vector<ParticleState>& particles);

  Grid grid_;
  Vec2 gravity_;
  double fluid_density_;
  int substeps_;
  bool periodic_x_, periodic_y_;
  RigidBodyConstraint constraint_;
  CollisionForces collisions_;
  std::vector<Shape> shapes_;            // per particle
  std::vector<double> inv_excess_mass_;  // 0 for fixed, prescribed and neutrally buoyant particles
  std::vector<char> predicted_;          // heavy free particles: (36) and (38) carry g and F'/m_e
  // Work arrays, sized once.
  std::vector<Vec2> x_old_, u_old_, x_, x_star_, u_, u_star_, f0_, f1_, collision_average_;
  std::vector<Vec2> lag_accel_;  // -C^T nu^n / m_e of the lagged multiplier (incremental only)
  std::vector<double> omega_old_, angle_old_;
  bool shaped_ = false;  // some particle is not a disk: collisions by the proper distance
  std::vector<double> angles_, torque0_, mean_rate_;
  std::vector<double> torque_average_;  // T'_avg: the predictor's mean collision torque
  int max_contacts_ = 0;
  std::unique_ptr<ViscousConstraint> viscous_;  // splitting.constraint = "viscous" only
  bool coupled_ = false;                        // CoupleStokes ran in this step
  std::vector<Vec2> u_start_;                   // U^n, omega^n before CoupleStokes
  std::vector<double> omega_start_;
  std::unique_ptr<LaggedMultiplier> lagged_;  // splitting.constraint = "incremental" only
  bool lag_applied_ = false;                  // LagMultiplier ran in this step
};

}  // namespace dlmfd
