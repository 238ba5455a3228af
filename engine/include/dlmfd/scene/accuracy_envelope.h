// The accuracy envelope of a scene (issue 13 point 5; docs/method/particle-coupling.md section 4):
// the dimensionless settings that govern a run's error, computed before it starts, and a warning
// for each one that lies outside the range in which the studies measured the part of the error it
// governs below 1 %. A warning names the scene key to change and a value of it that satisfies the
// bound. With `accuracy.strict = true` ValidateScene rejects such a scene instead.
//
// The bounds are the constants below, each the edge of what a study measured: D / h, nu dt / h^2
// (with and without particles, per coupling of the constraint; cut cells, which have no
// multiplier, their own), U dt / h, the elastic Courant
// number c dt / h with c = sqrt(eta_p / (rho lambda)), dt / lambda (neither applies to a polymer
// viscous on the grid's scale under devss), U_p dt / h under the lagged multiplier and h_p / h for
// the ring mesh. The measurements behind each, and the paper's cases that lie outside, are in
// docs/evidence/work_precision.md, "Warnings: the accuracy envelope".
//
// U, the velocity scale of the scene, is the largest of: the boundary data (|value| of uniform
// sides, |max| of Poiseuille ones); each particle's initial |velocity| + |angular_velocity| D / 2;
// for each free particle denser or lighter than the liquid an upper estimate of its fall speed,
// min(sqrt(pi/2 |rho_p - rho| / rho g D) (drag coefficient 1), |rho_p - rho| g D^2 / eta); for a
// body force across walls (not periodic in the direction across it) the plane Poiseuille peak
// |f| H^2 / (8 eta), H the height across. It is an estimate: the run's own Courant number is in
// diagnostics.csv. U_p (ParticleVelocityScale) is the particles' part of U.
//
// Not warned on, because no study varied it: D / h_p (reported among the settings), the splitting
// weights, the solver tolerances, the collision parameters. Values below the bounds' lower side
// (smaller dt, finer h) are never warned on. Each suggestion keeps the other keys as they are
// (refining domain.h raises nu dt / h^2: apply the time-step suggestions after the mesh one, or
// run the scene again).
#pragma once

#include <string>
#include <vector>

#include "dlmfd/core/params.h"

namespace dlmfd {

inline constexpr double kMinDiskResolution = 120.0;                 // D / h, ring mesh
inline constexpr double kMinDiskResolutionCollocation = 19.2;       // collocation, default coupling
inline constexpr double kMinDiskResolutionCollocationPaper = 39.0;  // collocation, paper coupling
// particle_mesh.kind = cut_cell: Schaefer-Turek at D/h = 9.76 within 0.85 % at eight sub-grid
// positions, the creeping fixed disk at D/h = 10 within 0.93 % (docs/evidence/cut_cell_boundary.md,
// "The pressure ghost penalty's scale", "A second-order boundary: the engine's cut cells").
inline constexpr double kMinDiskResolutionCutCells = 9.75;
inline constexpr double kMaxViscousNumberWithParticles = 0.195;    // nu dt / h^2
inline constexpr double kMaxViscousNumberViscousCoupling = 922.0;  // splitting.constraint = viscous
inline constexpr double kMaxViscousNumberIncrementalCoupling = 2.05;  // ... = incremental
// particle_mesh.kind = cut_cell: the creeping fixed disk in a channel at 480 (+0.17 %;
// docs/evidence/cut_cell_boundary.md, "`auto` picks cut cells for fixed disks"), above the liquid's
inline constexpr double kMaxViscousNumberCutCells = 480.0;
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
