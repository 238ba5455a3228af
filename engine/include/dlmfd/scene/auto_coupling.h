// splitting.constraint = "auto", the default since issue 32: the coupling of the rigid-body
// constraint with viscosity (core/params.h, ConstraintCoupling) chosen at the start of a run from
// the scene's dimensionless numbers, where no single coupling is the best everywhere
// (docs/evidence/constraint_coupling.md, "Coupling the constraint with viscosity";
// docs/accuracy.md).
//
// The rules are tried in order and the first that applies decides; each is one function in
// scene/auto_coupling.cc with its evidence beside it, and one test pins it
// (tests/unit/auto_coupling_test.cc). The last rule always applies. A rule never picks a coupling
// that ValidateScene would refuse for the scene (viscous with a neutrally buoyant free particle).
//   1. No particles: "incremental" (nothing to couple; its weights alpha = 1, beta = 0 put all
//      the viscosity in the Stokes step (33)).
//   2. Particles that cross a good part of a cell a step, U_p dt / h > 0.3, where the paper's leak
//      is small, nu dt / h^2 <= 0.195: "paper".
//   3. Creeping flow, nu dt / h^2 > 18.5, unless a free particle is neutrally buoyant: "viscous"
//      (the lagged multiplier would take more steps to settle than the flow takes).
//   4. Otherwise: "incremental". A particle that turns (an ellipse) included: until 2026-12-07 a
//      rule gave a free heavy one "paper", since the lagged multiplier blew up on such particles
//      when their interior points were a lattice turned against the grid; the points that cannot
//      pair up in a cell (particles/collocation_points.h) removed the cause, and the lagged
//      multiplier on them is stable, more accurate in dt and as cheap
//      (docs/evidence/validation_particles.md, "The lagged multiplier on a turning shape").
// The choice, the rule and the numbers it read go to the run's log, summary.json (`numerics`),
// the daemon's job record and `dlmfd show`; the scene as run (scene.toml) names the coupling
// chosen, so a resume or a rerun of it uses the same one.
//
// The numbers (CouplingNumbers), with U_p the particles' velocity scale (ParticleVelocityScale of
// scene/accuracy_envelope.h: initial speeds and an upper estimate of the fall speed of free
// particles), D the largest diameter and rho_p the densest particle:
//   nu dt / h^2 (nu = eta / rho), the viscous diffusion across a cell in one step;
//   U_p dt / h, the particles' Courant number;
//   Re_p = rho U_p D / eta, the particle Reynolds number;
//   St = (rho_p / rho) Re_p / 9, the particle Stokes number (its response time rho_p D^2 / (18 eta)
//   over D / U_p);
//   rho_p / rho, smallest and largest over the free particles;
//   whether a free particle is neutrally buoyant, whether the liquid has a polymer.
#pragma once

#include <string>

#include "dlmfd/core/params.h"
#include "dlmfd/scene/accuracy_envelope.h"  // the rules' bounds

namespace dlmfd {

struct CouplingNumbers {
  bool particles = false;
  bool neutral_free_particle = false;  // a free particle as dense as the liquid
  bool polymer = false;
  double viscous_number = 0.0;     // nu dt / h^2
  double particle_speed = 0.0;     // U_p
  double particle_courant = 0.0;   // U_p dt / h
  double particle_reynolds = 0.0;  // Re_p
  double stokes_number = 0.0;      // St
  double min_density_ratio = 0.0;  // rho_p / rho over free particles (0 without free particles)
  double max_density_ratio = 0.0;
};

CouplingNumbers ComputeCouplingNumbers(const Params& params);

// The coupling "auto" stands for in this scene, with the rule that chose it and the numbers it
// read (key "splitting.constraint", value the coupling's scene word).
ResolvedChoice ResolveConstraintCoupling(const Params& params);

// One line for the log and `dlmfd show`: splitting.constraint = "paper" (auto: RULE; nu dt / h^2 =
// 0.092, U_p dt / h = 1.19, ...).
std::string ResolvedChoiceText(const ResolvedChoice& choice);

// "incremental", "paper", "viscous": the scene word of a coupling.
const char* ConstraintCouplingName(ConstraintCoupling coupling);

}  // namespace dlmfd
