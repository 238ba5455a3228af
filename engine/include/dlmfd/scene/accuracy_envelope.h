// The accuracy envelope of a scene (issue 13 point 5; method note particle-coupling.md section 4):
// the dimensionless settings that govern a run's error, computed before it starts, and a warning
// for each one that lies outside the range in which docs/evidence/work_precision.md measured the
// part of the error it governs below 1 %. A warning names the scene key to change and a value of it
// that satisfies the bound. With `accuracy.strict = true` ValidateScene rejects such a scene
// instead.
//
// The bounds, each the edge of what the study measured (docs/evidence/work_precision.md, "Warnings"
// lists which paper cases lie outside):
// - D / h >= 120 for every particle (D its diameter, h = domain.h): problem (d), the fixed disk,
//   converges at first order in h (drag error 12, 6, 3, 1.5 % at D/h = 10 to 78); "Which settings",
//   item 3: 1 % in the drag takes D/h of about 120. The light disk (c) needs less (1.5 % at 51.2).
//   Measured with the ring mesh. For particle_mesh.kind = "collocation" under a coupling that
//   keeps the constraint in the Stokes step (incremental, viscous) the bound is D / h >= 19.2:
//   every measured case from 19.2 up was below 1 % (Faxen's disk in creeping flow at D/h = 19.2,
//   -0.33 % and -0.16 %; Schaefer-Turek at 19.5 off the nodes, 0.31 %, and at 20 on them, +0.78 %;
//   docs/evidence/particle_boundary.md (e), docs/evidence/validation_paper.md Faxen), and D/h
//   = 9.76 was not (4.5 %). With the paper's coupling the collocation points need D / h >= 39 (1.49
//   % at 19.5, 0.14 % at 39).
// - nu dt / h^2 <= 0.195 in a scene with particles (nu = eta / rho, eta the zero-shear viscosity):
//   problem (d)'s dt ladder at D/h = 19.5, where nu dt / h^2 = 0.195 (dt = h) is the largest
//   value whose halving moved Cd by at most 1 % (0.5 % wave, 1.0 % least squares; 0.39 -> 0.195
//   moved it 1.15 %); (c)'s dt ladder at 0.32-1.28 moved the fall speed 4.8-8.5 % per halving.
//   The bound is necessary, not sufficient: issue 13 measured a 4 % change of the drag between
//   0.1 and 0.02 at nu = 0.1 (the constraint step (37) split from viscosity, gamma = 0).
//   With splitting.constraint = "viscous" (the constraint inside the Stokes step) the bound is
//   nu dt / h^2 <= 922: Faxen's disk in creeping flow (rho_f = 0.01, h = 1/96) at dt = 0.01,
//   whose fall speed lies within 0.25 % of dt = 0.0025 at every time sampled, with the ring mesh
//   and the collocation points; at 3686 its first step, which holds the whole start-up, is 2.4 %
//   off (docs/evidence/constraint_coupling.md, "Coupling the constraint with viscosity"; 40 before
//   2026-12-04, the Schaefer-Turek geometry at nu = 0.1, D/h = 20, dt = 1e-2, within 0.05 % of dt =
//   1e-3). With splitting.constraint = "incremental" (the default: the last step's multiplier in
//   the Stokes step) the bound is nu dt / h^2 <= 2.05: the test channel (a fixed disk D = 0.4, h =
//   1/16) at dt = 8e-3 (2.05) is 0.52 % below the dt -> 0 drag during its transient (t = 0.5; 0.06
//   % at 1.02), and a free disk of rho_d / rho_L = 1.01 (Faxen's disk, h = 1/96) settles at the
//   same speed within 0.02 % from 1.4 to 9.2, 0.21 % at 18.4 (unstable from 5.5 until the lag's
//   reaction became a force over the predictor's sub-steps, 2026-12-03, particles/particle_step.h);
//   at a steady state the drag does not depend on nu dt / h^2 (Schaefer-Turek at nu = 0.1: 0.38 %
//   between 40 and 0.04, a lag still decaying).
// - nu dt / h^2 <= 10.24 without particles: the largest value among the runs with errors below
//   1 % (Waters-King (a), ny = 128, dt = 0.0025: 1.3e-3; the cavity (b) reached 0.82 at 128 cells).
// - U dt / h <= 0.64 (advective Courant number): every run of the study had at most 0.64, and the
//   cavity (b) at 0.64 (128 cells, dt = 0.005) had 0.68 % of the lid speed.
// - c dt / h <= 0.3017 with c = sqrt(eta_p / (rho lambda)) (elastic shear-wave Courant number, the
//   one docs/evidence/stability.md tabulates), and dt / lambda <= 0.01: the Oldroyd-B runs of (a)
//   with errors below 1 % (largest: h = 1/32, dt = 0.01, lambda = 1, eta_p = 8/9: error 5.2e-3).
//   These two bounds do not apply to a polymer that is viscous on the grid's scale under
//   fluid.stress_splitting = "devss": El_h = lambda eta_p / (rho h^2) <= 0.105 and lambda U / h <=
//   0.016. There the step carries all but El_h / (1 + El_h) of eta_p implicitly, and the drag on
//   the viscosity rule's channel (cases/verification/viscosity_rule_channel.toml, h = 1/16, U = 1)
//   lies 0.98 % / 0.106 % / 0.011 % below its lambda -> 0 limit at lambda = 1e-3 / 1e-4 / 1e-5
//   (El_h = 0.105 / 0.0105 / 0.00105, lambda U / h = 0.016 / 0.0016 / 0.00016;
//   docs/evidence/validation.md, "The viscosity rule"), whatever c dt / h (up to 20) and dt /
//   lambda (up to 2000) say. The elastic warnings would suggest dt = 1e-8 for a sweep of lambda
//   through 0.
//
// U, the velocity scale of the scene, is the largest of: the boundary data (|value| of uniform
// sides, |max| of Poiseuille ones); each particle's initial |velocity| + |angular_velocity| D / 2;
// for each free particle denser or lighter than the liquid an upper estimate of its fall speed,
// min(sqrt(pi/2 |rho_p - rho| / rho g D) (drag coefficient 1), |rho_p - rho| g D^2 / eta); for a
// body force across walls (not periodic in the direction across it) the plane Poiseuille peak
// |f| H^2 / (8 eta), H the height across. It is an estimate: the run's own Courant number is in
// diagnostics.csv.
//
// - U_p dt / h <= 0.3 with splitting.constraint = "incremental" and particles, U_p their velocity
//   scale (ParticleVelocityScale: the particles' part of U below): the lagged multiplier acts where
//   a particle was a step ago, and diverged on the paper's case 5.1 (a disk of rho_p / rho = 1.5,
//   h = 1/96, collocation points, wave advection) at U_p dt / h = 0.60 and 1.19; it completed at
//   0.30 (docs/evidence/constraint_coupling.md, "The automatic coupling"). "auto" picks the paper's
//   coupling there (scene/auto_coupling.h); the warning is for a scene that names "incremental".
// - h_p / h >= 1.1 for the ring mesh (particle_mesh.h against domain.h): the accuracy studies (c)
//   and (d) ran at h_p / h = 96 / 70 = 1.37 throughout, and a finer particle mesh makes the DLM
//   multiplier CG (37) ill-conditioned: bench/multiplier_conditioning.sh
//   (docs/evidence/work_precision.md, "The particle mesh against the fluid mesh"; a disk of D =
//   0.62 in a periodic box, h = 1/64) took 60-135 iterations a step from h_p / h = 1.1 up, 284-420
//   at 0.5-0.75, and did not converge at 1.0. The suggestion is the studies' ratio, h_p = 96 / 70
//   h.
//
// Not warned on, because the study did not vary it: D / h_p (reported among the settings, with
// h_p = c h, the boundary point spacing, for collocation points), the splitting weights, the solver
// tolerances (their "tol" ladders give the defaults, docs/evidence/work_precision.md "Which
// settings" 2), the collision parameters. Values below the bounds' lower side (smaller dt, finer h)
// are never warned on. Each suggestion keeps the other keys as they are (refining domain.h raises
// nu dt / h^2: apply the time-step suggestions after the mesh one, or run the scene again).
#pragma once

#include <string>
#include <vector>

#include "dlmfd/core/params.h"

namespace dlmfd {

inline constexpr double kMinDiskResolution = 120.0;                 // D / h, ring mesh
inline constexpr double kMinDiskResolutionCollocation = 19.2;       // collocation, default coupling
inline constexpr double kMinDiskResolutionCollocationPaper = 39.0;  // collocation, paper coupling
inline constexpr double kMaxViscousNumberWithParticles = 0.195;     // nu dt / h^2
inline constexpr double kMaxViscousNumberViscousCoupling = 922.0;  // splitting.constraint = viscous
inline constexpr double kMaxViscousNumberIncrementalCoupling = 2.05;  // ... = incremental
inline constexpr double kMaxViscousNumberWithoutParticles = 10.24;
inline constexpr double kMaxAdvectiveCourant = 0.64;       // U dt / h
inline constexpr double kMaxElasticCourant = 0.3017;       // sqrt(eta_p / (rho lambda)) dt / h
inline constexpr double kMaxStepPerRelaxationTime = 0.01;  // dt / lambda
inline constexpr double kMinParticleMeshRatio = 1.1;       // h_p / h, ring mesh
inline constexpr double kMaxLaggedParticleCourant = 0.3;   // U_p dt / h, incremental coupling
// nu dt / h^2 above which auto picks viscous: just above Faxen's disk at rho_f = 0.5 (18.43),
// where the lagged multiplier settled as fast as the liquid; at 36.9 it took 70 steps more
// (docs/evidence/validation_particles.md, "Creeping flow at a time step set by the motion")
inline constexpr double kMaxViscousNumberLaggedSettles = 18.5;
// A polymer viscous on the grid's scale (devss only): no elastic bounds.
inline constexpr double kMaxGridElasticity = 0.105;  // El_h = lambda eta_p / (rho h^2)
inline constexpr double kMaxGridDeborah = 0.016;     // lambda U / h

// One dimensionless setting of the scene, for the log ("nu dt / h^2", 0.44).
struct AccuracySetting {
  std::string name;
  double value = 0.0;
};

// A setting outside the envelope: the scene key to change, its value now and a value that
// satisfies the bound; `allowed` is the bound ("<= 0.195"), `source` the study row it comes from.
struct AccuracyWarning {
  std::string setting;  // "nu dt / h^2", "D / h (particles.3, the smallest of 11 below the bound)"
  double value = 0.0;
  std::string allowed;
  std::string key;        // "time.dt", "domain.h"
  std::string current;    // the key's value now, as scene text
  std::string suggested;  // a value of `key` inside the bound, as scene text
  std::string source;
  std::string Message() const;  // one line: setting, value, bound, what to change, source
};

// The settings in a fixed order: nu dt / h^2, U dt / h, U, then with a polymer c dt / h and
// dt / lambda, then D / h and D / h_p of each particle.
std::vector<AccuracySetting> AccuracySettings(const Params& params);
// The warnings in the same order; empty inside the envelope. At most one D / h warning: the
// smallest particle's (it names how many particles are below the bound).
std::vector<AccuracyWarning> AccuracyWarnings(const Params& params);
// The scene's velocity scale U (see above).
double VelocityScale(const Params& params);
// The particles' part of it: initial speeds and the fall-speed estimate of free particles.
double ParticleVelocityScale(const Params& params);

}  // namespace dlmfd
