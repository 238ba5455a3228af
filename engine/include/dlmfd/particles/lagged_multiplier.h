// The incremental coupling of the rigid-body constraint with viscosity (splitting.constraint =
// "incremental", issue 13 point 2): the multiplier of the last DLM step (37) acts in the Stokes
// step (33) of this one, and (37) solves only for its increment, as an incremental projection
// lags the pressure (Van Kan 1986) where the paper's scheme is non-incremental.
//
// Why: with gamma = 0 the paper's steps (33)-(34) diffuse momentum through a particle for a whole
// step before (37) resets its velocity, so the drag falls as nu dt / h^2 grows
// (particle-coupling.md, section 1). Here (33) carries the force nu^n that held the particles rigid
// at the end of the last step:
//   (rho/dt) M (u - u^n) + alpha eta K u - B^T p = f + E(X^n)^T nu^n,   B u = 0,
// (entered as the velocity increment dt M^-1 E^T nu^n on u^n, the fast solver's data), and the
// heavy free particles its reaction -D^-1 C^T nu^n as a force over the sub-steps of (36), beside g
// (particles/particle_step.h, "Why over the sub-steps"). Then (34)-(36)
// as in the paper, and (37) finds the increment d nu with the same CG from a zero start; the
// particles store nu^{n+1} = nu^n + d nu for the next step (and in the checkpoint), and the
// hydrodynamic force is that of nu^{n+1}.
// Error: at a steady state d nu = 0, so the flow solves the coupled steady problem whatever dt: the
// leak is gone, and what remains is the advection splitting's O(dt). In a transient nu lags one
// step: the lag e^n = nu^n - nu_coupled obeys e^{n+1} = (I - P^-1 S) e^n with P the inviscid Schur
// complement of (37) and S the viscous one of particles/viscous_constraint.h, whose spectrum lies
// in (0, 1]: for fixed particles no oscillation, and the force modes of wavelength l converge in
// about 1 + nu dt / l^2 steps. The failures once measured beyond that argument came from the
// reaction given as a kick at the start of (36), not from the lag (docs/evidence/stability.md,
// "The coupling of the constraint"; tests/convergence/lagged_reaction_test.cc). The accuracy
// envelope bounds nu dt / h^2 for the transient's accuracy (scene/accuracy_envelope.h).
// Where: at X^n, because the advection step (34) that follows (33) carries the liquid inside a
// particle, and the push nu^n gave it, by U dt to X^{n+1}, where (37) holds the particle (the
// viscous coupling puts the particles at X^n in (33) for the same reason). Spreading nu^n at
// X^n + dt U^n instead was tried and not taken: it failed a case that completes here and carried
// more of the dt error (docs/evidence/stability.md, "The coupling of the constraint", failure 2).
// Where the constraint holds, for a fixed particle under the tendency correction
// (splitting.steady_correction = "tendency", the Newtonian default): on the Stokes step's velocity
// u^{n+1/4}, not on the advected u^{n+2/4}. (37) finds d nu from the mismatch E u^{n+1/4} - U,
// with E u^{n+1/4} sampled after (33), and adds dt M^-1 E^T d nu to u^{n+2/4} as before. At a
// steady state d nu = 0, so E u^{n+1/4} = U exactly, and u^{n+1/4} is the field whose equations the
// splitting's fixed point solves (fluid/advection_wave.h, the tendency correction); held on
// u^{n+2/4} = u^{n+1/4} + dt L u^{n+1/4} instead, the constraint was off by dt E L u at the points,
// so the steady drag moved with dt (docs/evidence/splitting.md, "The splitting's fixed point").
// A moving particle keeps it on u^{n+2/4} at X^{n+1}, where (34) has carried its liquid; so does
// every particle under the other corrections, whose fixed point no single field solves (held on
// u^{n+1/4} there, a fixed disk's steady drag moved away from the viscous coupling's:
// docs/evidence/splitting.md, "The fixed particle's constraint on the Stokes velocity").
// Cost: one E at X^n and one spreading a step (no extra fast solve); two interpolations of u at a
// fixed particle's points.
// Neutrally buoyant free particles are not lagged: their stored multiplier stays the paper's nu of
// (37) (RigidBodyConstraint::Enforce assigns it), so they keep the paper's coupling. Lagged,
// their rotation drifted without end (docs/evidence/constraint_coupling.md, "The lagged
// multiplier"): (37) leaves the rigid part of their mismatch to their motion, so nothing corrects
// what the lag does to it.
// Not supported: the viscous coupling's fully coupled solve (this is its first iterate, warm
// started by the total multiplier, without the PCG that follows).
// References: J. van Kan, SIAM J. Sci. Stat. Comput. 7 (1986) 870-891 (incremental pressure
// correction); Guermond, Minev, Shen, CMAME 195 (2006) 6011-6045 (its error analysis); Glowinski,
// Pan, Hesla, Joseph, Periaux, J. Comput. Phys. 169 (2001) 363-426 (the DLM step).
#pragma once

#include <cstddef>
#include <vector>

#include "dlmfd/core/state.h"
#include "dlmfd/particles/rigid_body_constraint.h"

namespace dlmfd {

class LaggedMultiplier {
 public:
  // held[p]: particle p holds its constraint on the Stokes step's velocity (a fixed particle under
  // the tendency correction; see "Where the constraint holds").
  LaggedMultiplier(const RigidBodyConstraint& constraint, const std::vector<char>& held);

  // Before (33): locates E at the particles' positions X^n (constraint.Locate) and adds dt M^-1
  // E^T nu^n to u, v (nu^n: each particle's stored multiplier); records C^T nu^n per particle.
  // time names the step in errors. Throws ParticlesOverlap.
  void Apply(double time, double dt, RigidBodyConstraint& constraint,
             const std::vector<ParticleState>& particles, double* u, double* v);

  // After (33), before (34): E(X^n) u^{n+1/4} at the points of the held particles (u, v: the
  // Stokes step's velocity; E as Apply located it).
  void SampleStokesVelocity(const RigidBodyConstraint& constraint, const double* u,
                            const double* v);
  // Before (37), with u, v = u^{n+2/4}: the shift E u^{n+1/4} - E u^{n+2/4} at the held
  // particles' points (zero elsewhere; E still the one Apply located), for Enforce's
  // mismatch_shift; nullptr when no particle is held.
  const double* AdvectionShift(const RigidBodyConstraint& constraint, const double* u,
                               const double* v);

  // C^T nu^n of the last Apply for particle p: the force and torque it put on the fluid in (33).
  Vec2 ForceSum(std::size_t p) const { return force_sum_[p]; }
  double TorqueSum(std::size_t p) const { return torque_sum_[p]; }

 private:
  template <class Visit>
  void ForHeldPoints(const RigidBodyConstraint& constraint, const double* u, const double* v,
                     Visit visit) const;

  std::vector<double> stacked_;  // nu^n of every particle, stacked
  std::vector<char> held_;       // per particle: its constraint held on u^{n+1/4}
  bool any_held_ = false;
  std::vector<double> shift_;    // E u^{n+1/4} at the held particles' points, then the shift
  std::vector<double> slot_uv_;  // the spreading, by slot (u and v side by side)
  std::vector<Vec2> force_sum_;
  std::vector<double> torque_sum_;
};

}  // namespace dlmfd
