// The validated parameter tree of a scene (design.md 3.1). Built only by scene/scene_file.h, which
// checks every value; the engine may assume what the comments state. Units are the user's. Each
// member a scene sets is declared once as a scene key, with its default, range and description, in
// engine/src/scene/scene_keys.cc (scene/scene_keys.h); the enums' scene words are
// core/param_words.h.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dlmfd/core/grid.h"

namespace dlmfd {

using Vec2 = Eigen::Vector2d;

enum class SideType { kWall, kVelocity, kOutflow, kPeriodic };
enum class Profile { kUniform, kPoiseuille, kQuartic };

// One side of the rectangle. A wall is a velocity side with value 0.
struct BoundarySide {
  SideType type = SideType::kWall;
  Profile profile = Profile::kUniform;
  Vec2 value = Vec2::Zero();  // uniform profile: the velocity on the side
  Vec2 max = Vec2::Zero();    // poiseuille, quartic: the velocity at mid-side (zero at the corners)
  double ramp_time = 0.0;     // > 0: the data times the tanh ramp of fluid/boundary_profile.h
};

enum class Side { kLeft = 0, kRight = 1, kBottom = 2, kTop = 3 };

// Which triangles the fluid's forms integrate on (domain.diagonals): kSwNe, the paper's mesh, every
// square cut along its SW-NE diagonal; kBoth, the mean of the forms on that mesh and on its mirror
// image (every square cut along its NW-SE diagonal): the divergence B of step (33) and the
// wave-like step's K_V and N(V, .) of step (34). The mesh is not mirror-symmetric (x -> -x or y ->
// -y maps it onto the other diagonal's), so a flow symmetric in the domain's mid-line is not quite
// symmetric on it; the mean is (mesh/grid_kernels.h, Diagonal; docs/evidence/particle_boundary.md
// (e), "The lift's mirror bias"). The default is kBoth, numerics.preset's word
// (scene/numerics_preset.h: the lift's sign right, Schaefer-Turek Cd +0.79 % at D/h = 20).
enum class MeshDiagonals { kSwNe, kBoth };

struct DomainParams {
  Vec2 size = Vec2(1.0, 1.0);  // width, height; size / h even integers
  double h = 1.0 / 32;         // velocity mesh size
  BoundarySide sides[4];       // indexed by Side
  MeshDiagonals diagonals = MeshDiagonals::kBoth;
  // domain.flow_rate: in a channel periodic in one direction (the other two sides Dirichlet), the
  // volume flux per unit depth through a cross-section that a uniform mean pressure gradient
  // holds each step (fluid/flux_control.h); 0 for sedimentation without end walls. In a box
  // periodic in both directions only 0: the rates along x and y held at zero (a periodic
  // suspension's frame). Absent: no control (the body force drives the flow).
  std::optional<double> flow_rate;
  const BoundarySide& side(Side s) const { return sides[static_cast<int>(s)]; }
  bool PeriodicX() const { return side(Side::kLeft).type == SideType::kPeriodic; }
  bool PeriodicY() const { return side(Side::kBottom).type == SideType::kPeriodic; }
  // The velocity grid of the domain: round(size / h) cells of side h from the origin (the one
  // definition used by Simulation, the particle step and the scene validation).
  Grid VelocityGrid() const {
    return Grid{static_cast<int>(std::lround(size.x() / h)),
                static_cast<int>(std::lround(size.y() / h)), h, 0.0, 0.0};
  }
};

// The constitutive model of the polymer (conformation/relaxation_model.h has the equations).
enum class ConstitutiveModel { kOldroydB, kGiesekus, kFeneP, kPttLinear, kPttExponential };
// How step (35) carries the conformation tensor through its advection: A itself (standard), its
// matrix logarithm (log) or its symmetric square root (sqrt).
enum class ConformationRepresentation { kStandard, kLog, kSqrt };
// How the polymer stress tau_p enters the momentum equation (fluid.stress_splitting):
//   kExplicit: all of tau_p^n explicitly in step (33), the paper's scheme;
//   kDevss:    the share w of its viscous part, w eta_p 2 D(u), implicitly with the solvent's
//              viscosity in the fluid steps, and the rest, tau_p^n - w eta_p 2 D_h, explicitly,
//              D_h being the nodal strain rate that step (35) used for A^n. This is DEVSS-G
//              (Guenette & Fortin 1995; Liu, Bornside, Armstrong & Brown 1998) with D_h the lumped
//              L2 projection of the P1 gradient and alpha = w eta_p, w = 1 / (1 + El_h), where
//              El_h = lambda eta_p / (rho h^2) is the elasticity number of one cell: the polymer is
//              viscous on the grid's scale when El_h << 1 (w -> 1) and elastic when El_h >> 1
//              (w -> 0, the paper's scheme). As lambda -> 0 the explicit rest vanishes and the step
//              is the Newtonian step of viscosity eta, so the drag is continuous in lambda on every
//              grid; w does not depend on dt, so neither does a steady state
//              (conformation/oldroyd_b_polymer.h; docs/evidence/validation.md, "The viscosity
//              rule").
enum class StressSplitting { kExplicit, kDevss };

struct FluidParams {
  double density = 1.0;          // rho_L > 0
  double viscosity = 0.01;       // zero-shear eta = eta_s + eta_p > 0
  double relaxation_time = 0.0;  // lambda_r >= 0; 0 = Newtonian
  double solvent_ratio = 1.0;    // beta = eta_s / eta in (0, 1]
  Vec2 body_force =
      Vec2::Zero();  // force per unit volume on the liquid (e.g. a mean pressure gradient)
  ConstitutiveModel model = ConstitutiveModel::kOldroydB;
  ConformationRepresentation conformation = ConformationRepresentation::kStandard;
  StressSplitting stress_splitting = StressSplitting::kDevss;
  // Model parameters, each given only for its model (scene validation): Giesekus mobility alpha in
  // [0, 0.5]; FENE-P extensibility L^2 > 2 (tr A < L^2); PTT epsilon >= 0.
  std::optional<double> mobility;
  std::optional<double> extensibility;
  std::optional<double> ptt_epsilon;
  // The one viscosity rule (design.md 4): the polymer is modelled only when lambda > 0 and
  // beta < 1; then the Newtonian part of the momentum equation carries eta_s = beta eta and the
  // polymer stress carries eta_p = (1 - beta) eta. A Newtonian liquid has no polymer stress, so
  // its Newtonian part carries the whole eta, whatever solvent_ratio says. The two always sum to
  // eta, which keeps the drag continuous as beta -> 1 (and, with stress_splitting = kDevss, as
  // lambda -> 0 on a fixed grid too: ImplicitViscosity).
  bool IsNewtonian() const { return relaxation_time == 0.0 || solvent_ratio == 1.0; }
  bool Devss() const { return !IsNewtonian() && stress_splitting == StressSplitting::kDevss; }
  // eta_s, or the whole eta without a modelled polymer.
  double NewtonianViscosity() const {
    return IsNewtonian() ? viscosity : solvent_ratio * viscosity;
  }
  // w = 1 / (1 + lambda eta_p / (rho h^2)), the share of eta_p that kDevss treats implicitly on
  // the velocity mesh of size h; 0 without kDevss.
  double DevssWeight(double h) const { return Devss() ? 1.0 / (1.0 + CellElasticity(h)) : 0.0; }
  // The viscosity of the term 2 eta D(u) that steps (33)-(34) treat implicitly on the velocity mesh
  // of size h: eta_N, plus w eta_p with kDevss (the polymer stress then subtracts w eta_p 2 D_h).
  double ImplicitViscosity(double h) const {
    return NewtonianViscosity() + DevssWeight(h) * PolymerViscosity();
  }
  // The viscosity the polymer stress carries: 0 when no polymer is modelled.
  double PolymerViscosity() const {
    return IsNewtonian() ? 0.0 : (1.0 - solvent_ratio) * viscosity;
  }
  // The polymer's modulus G = eta_p / lambda, tau_p = G T(A) (conformation/relaxation_model.h);
  // only where a polymer is modelled (lambda > 0).
  double PolymerModulus() const { return PolymerViscosity() / relaxation_time; }
  // El_h = lambda eta_p / (rho h^2), the elasticity number of one cell of size h (0 without a
  // polymer): the polymer is viscous on the grid's scale when El_h << 1, elastic when El_h >> 1.
  double CellElasticity(double h) const {
    return relaxation_time * PolymerViscosity() / (density * h * h);
  }
  // c = sqrt(eta_p / (rho lambda)) = sqrt(G / rho), the speed of the polymer's shear waves, the
  // bound of the elastic Courant number c dt / h (scene/accuracy_envelope.h); only where a polymer
  // is modelled (lambda > 0).
  double ElasticWaveSpeed() const {
    return std::sqrt(PolymerViscosity() / (density * relaxation_time));
  }
  // De = lambda U / L, the Deborah number of a flow of speed U on the length L (0 without a
  // polymer): a particle's diameter (io/run_statistics.h), a cell (scene/accuracy_envelope.h).
  double Deborah(double speed, double length) const {
    return IsNewtonian() ? 0.0 : relaxation_time * speed / length;
  }
};

struct TimeParams {
  double dt = 1e-3;  // > 0
  double end = 1.0;  // >= 0
};

// Step (34): kLeastSquares, the paper's least-squares CG; kWave, the explicit wave-like scheme. The
// default is kWave, numerics.preset's word (scene/numerics_preset.h: 3.5-4.5 times cheaper and as
// accurate or more on every problem of docs/evidence/work_precision.md, "Which settings" 1).
enum class AdvectionScheme { kLeastSquares, kWave };

// What the advection step (34) does about the splitting's steady-state error: kNone, nothing (the
// paper's scheme: the fixed point of the Lie splitting carries an extra streamline diffusion,
// (dt/2) (u.grad)^2 u with the wave-like step, twice that with the backward-Euler least-squares
// step); kTaylor, the step subtracts that term wherever it is at most half the Newtonian viscosity
// (fluid/advection_wave.h, fluid/advection_least_squares.h). The default (numerics.preset's word)
// is "tendency" in a Newtonian liquid and "none" with a polymer (SplittingParams): with the
// polymer's stress explicit the removed diffusion is damping the elastic
// coupling needs (the Waters-King start-up at dt = 0.04 failed earlier with it;
// docs/evidence/splitting.md, "The splitting's steady-state error"). kTendency: the step integrates
// the whole frozen tendency (its own advection and the Stokes step's (u^{n+1/4} - u^n) / dt) and
// subtracts the Stokes part, so every higher-order term vanishes at a steady state, and snapshots
// write u^{n+1/4}: a steady answer is the discrete steady solution whatever dt
// (docs/evidence/splitting.md, "The splitting's fixed point"; opt-in).
enum class SteadyCorrection { kNone, kTaylor, kTendency };

// Where the rigid-body constraint meets the fluid: kPaper, only in the DLM step (37), without
// viscosity (gamma = 0); kViscous, also in the Stokes step (33), which is then solved with the
// particles in it (particles/viscous_constraint.h), so the constraint meets the implicit viscosity;
// kIncremental, the last step's multiplier in (33) and its increment in (37)
// (particles/lagged_multiplier.h).
enum class ConstraintCoupling { kPaper, kViscous, kIncremental };

// Marchuk-Yanenko weights of the viscous term: alpha in (33), beta in (34), gamma = 1 - alpha -
// beta in (37). The engine supports gamma = 0 only (the paper's choice), which validation enforces;
// with constraint = kViscous or kIncremental also beta = 0 (all the viscosity in the step that sees
// the particles). The constraint is absent by default, as a scene's is "auto": ParseScene and the
// Simulation resolve it from the scene's numbers (scene::ResolveDefaults, scene/auto_coupling.h),
// so the engine's steps read a value. alpha and beta follow the constraint: 1 and 0, or the
// paper's 1/2 and 1/2 with constraint = "paper" (DefaultWeights; a Params that leaves the
// constraint to "auto" and its weights at 1 and 0 gets the weights of what "auto" picks, as a scene
// that names neither does).
struct SplittingParams {
  double alpha = 1.0;
  double beta = 0.0;
  AdvectionScheme advection = AdvectionScheme::kWave;
  std::optional<ConstraintCoupling> constraint;  // absent: "auto" (see above)
  // Absent: numerics.preset's word for the liquid, which depends on the other keys; ParseScene and
  // the Simulation set it (scene::ResolveDefaults), so the engine's steps read a value.
  std::optional<SteadyCorrection> steady_correction;

  // alpha and beta of a scene that names only its constraint.
  static SplittingParams DefaultWeights(ConstraintCoupling constraint) {
    SplittingParams s;
    s.constraint = constraint;
    if (constraint == ConstraintCoupling::kPaper) s.alpha = s.beta = 0.5;
    return s;
  }
};

enum class MultiplierPreconditioning { kBlocks, kGram };

// Stopping rules and limits of the iterative solvers. The defaults are the loosest level of the
// work-precision study (docs/evidence/work_precision.md, "Ladders": the tol ladders: 1e-2 ... 1e-8)
// whose answers differ from the tightest by at most 0.6 % of the discretisation error on all four
// reference problems; on the paper's 5.2 pair they move particle velocities by 2e-5 relative to t =
// 1 against 1e-6 (docs/evidence/performance.md, "Stopping rules").
struct SolverParams {
  double stokes_tolerance = 1e-4;  // Uzawa/PCG, relative to a fixed reference residual
  int stokes_max_iterations = 200;
  double advection_tolerance = 1e-2;  // LS-CG, ratio of gradient norms
  int advection_max_iterations = 50;
  double wave_max_courant = 0.5;       // wave-like scheme: sub-steps so that |u| tau / h <= this
  double multiplier_tolerance = 1e-4;  // DLM CG (37), relative
  // DLM CG (37) and the viscous coupling's PCG (particles/viscous_constraint.h). 2000: the cold
  // first step of a fixed disk with collocation points in creeping flow took 430 / 884 iterations
  // at R/h = 24 with its centre on a node / h/4 off it (the confined cylinder at rho = 0.01; 500
  // failed at step 1; docs/evidence/validation_particles.md, "Creeping flow at a time step set by
  // the motion").
  int multiplier_max_iterations = 2000;
  // The preconditioner of the DLM CG (37): the product G alone (gram, the paper's CG) or each
  // particle's block factored (blocks); particles/multiplier_preconditioner.h.
  MultiplierPreconditioning multiplier_preconditioner = MultiplierPreconditioning::kGram;
};

enum class Motion { kFree, kFixed, kPrescribed };

// The kind of a particle's shape (particles/shape.h has the geometry).
enum class ShapeKind { kDisk, kEllipse };

struct ParticleParams {
  Vec2 center = Vec2::Zero();
  // Disk: its diameter > 0. Ellipse: the diameter of the disk of the same area, 2 sqrt(a b) (set by
  // SetEllipse; the scene declares semi_axes instead).
  double diameter = 0.2;
  double density = 1.0;  // > 0 (free particles: != fluid density)
  Vec2 velocity = Vec2::Zero();
  double angular_velocity = 0.0;
  Motion motion = Motion::kFree;
  ShapeKind shape = ShapeKind::kDisk;
  Vec2 semi_axes = Vec2::Zero();  // ellipse: (a, b) along the body's x and y axes, > 0
  double angle = 0.0;             // orientation at t = 0: the body's x axis from the domain's x
  // The radius of the smallest circle about the centre that holds the particle: D / 2 for a disk,
  // max(a, b) for an ellipse.
  double Radius() const {
    if (shape == ShapeKind::kDisk) return 0.5 * diameter;
    return semi_axes.x() > semi_axes.y() ? semi_axes.x() : semi_axes.y();
  }
  void SetEllipse(double a, double b) {
    shape = ShapeKind::kEllipse;
    semi_axes = Vec2(a, b);
    diameter = 2.0 * std::sqrt(a * b);
  }
};

// The multiplier points of the DLM step (37): the H1 ring mesh of each disk (paper (24), method
// notes 2, section 1.1) or collocation points on the true circle plus interior points
// (particle-coupling.md section 3; particles/collocation_points.h). kCutCell has no multipliers:
// fixed bodies are cut out of the mesh and step (33) imposes their no-slip condition by Nitsche's
// method (particles/cut_cell_step.h; fixed particles in a Newtonian liquid only, issue 33).
enum class ParticleMeshKind { kRing, kCollocation, kCutCell };
// How E evaluates the fluid velocity at a collocation boundary point: the 6-node P2 basis of the
// 2h macro-triangle that holds it, P1 on the h-triangle, or the 9-node biquadratic (Q2) basis of
// the 2h macro-square that holds it, which is mirror-symmetric where the triangles are not.
enum class BoundaryInterpolation { kQuadratic, kLinear, kBiquadratic };

// The paper's particle mesh against its fluid mesh, h_p / h = (1/70) / (1/96) (section 5). Without
// particle_mesh.h, h_p = kPaperParticleMeshRatio domain.h (ParticleMeshParams::RingMeshSize):
// the ratio of every accuracy study (docs/evidence/work_precision.md (c), (d)) and inside the
// multiplier CG's well-conditioned range h_p / h >= 1.1 ("The particle mesh against the fluid
// mesh"), on any mesh; the paper's h_p = 1/70 at its h = 1/96.
inline constexpr double kPaperParticleMeshRatio = 96.0 / 70.0;

struct ParticleMeshParams {
  // The default since issue 32: collocation points (docs/evidence/particle_boundary.md (e):
  // Schaefer-Turek Cd +0.78 % at D/h = 20 against the ring's +2.23 %, the lift's sign right from
  // D/h = 40 on, and a multiplier CG of about one iteration a step against 12).
  ParticleMeshKind kind = ParticleMeshKind::kCollocation;
  // ring: multiplier mesh size > 0; absent: it follows domain.h (RingMeshSize), and
  // scene::ResolveDefaults names the value.
  std::optional<double> h;
  double spacing = 2.0;  // collocation: boundary point spacing in units of domain.h, in [0.5, 4]
  BoundaryInterpolation interpolation = BoundaryInterpolation::kQuadratic;  // collocation
  // cut_cell, free bodies: the coupling matrix K of Newton's law (particles/cut_cell_free_bodies.h)
  // is made anew once a body has moved this far (in units of domain.h) since it was made; 0:
  // every step. In between a step makes one solve at the new velocity instead of 3N unit solves.
  // 1 (docs/evidence/cut_cell_boundary.md, "A free body"): Faxen's fall speed moves by 2e-8, the
  // 5.2 pair's velocities over its first second by 1.1e-4 (a tenth of the grid's error: 7.9e-4),
  // at a quarter of the CPU a step.
  double rigid_modes_refresh = 1.0;
  // h_p of the ring mesh on the velocity mesh of size domain_h: h, or kPaperParticleMeshRatio
  // domain_h when absent.
  double RingMeshSize(double domain_h) const {
    return h.value_or(kPaperParticleMeshRatio * domain_h);
  }
};

struct CollisionParams {
  double range = 1.5;                // rho, in units of the velocity mesh size h
  double wall_stiffness = 1e-5;      // epsilon_w > 0
  double particle_stiffness = 2e-5;  // epsilon_p > 0
  int substeps = 10;                 // K of (36) and (38), >= 1
};

enum class ConformationForm { kA };

// The velocity step (35) freezes (conformation.velocity): kAdvected, u^{n+2/4} after step (34),
// the paper's; kStokes, the Stokes step's u^{n+1/4}, which is discretely divergence-free, meets the
// particles' constraint where (33) holds it, and at a fixed point of the splitting solves the
// steady equations. u^{n+2/4} = u^{n+1/4} - dt (u.grad) u + O(dt^2) whatever the density, so with
// kAdvected a steady stress carries an O(dt U / L) error even in creeping flow; kStokes removes
// that term (the Lie splitting of (35) itself, advection then pointwise, stays first order). The
// confined cylinder at Wi = 0.9, R/h = 16: K moves by 1.2 % from dt = lambda / 120 to lambda / 480
// with kAdvected, and kStokes at lambda / 120 lies 0.7 % below kAdvected at lambda / 480;
// docs/evidence/splitting.md, "The velocity the conformation step sees"). A scene's default is
// "auto" in a polymer liquid (scene/auto_conformation_velocity.h: kStokes without particles and
// around fixed disks cut out of the mesh, kAdvected with multiplier points). The struct leaves it
// absent, as a scene that names none: ParseScene and the Simulation resolve it
// (scene::ResolveDefaults), so a Params built in code runs the velocity of the scene from a file.
enum class ConformationVelocity { kAdvected, kStokes };

struct ConformationParams {
  ConformationForm form = ConformationForm::kA;
  // Absent: numerics.preset's word for the liquid ("auto" in a polymer liquid); set by
  // scene::ResolveDefaults before the engine's steps read it.
  std::optional<ConformationVelocity> velocity;
  double max_courant = 0.4;  // advection sub-cycling: |u| tau / h <= this
  double blend_kappa = 0.5;  // SPD blend: lambda_min(A) >= kappa lambda_min(A_low)
};

struct OutputParams {
  double fields_every = 0.1;      // simulated time between field snapshots; 0 = none
  double particles_every = 0.01;  // between particle records; 0 = every step
  double checkpoint_every = 1.0;  // between checkpoints; 0 = none
};

// numerics.preset: the configuration the scene's numerics keys default to
// (scene/numerics_preset.h): kDefault, the configuration measured best (issue 32); kPaper, all of
// the paper's choices.
enum class NumericsPreset { kDefault, kPaper };

// What a scene key's "auto" became at the start of a run (scene/auto_coupling.h): the key, the
// scene word chosen, the rule that chose it and the dimensionless numbers that rule read.
struct ResolvedChoice {
  std::string key;                                      // "splitting.constraint"
  std::string value;                                    // "incremental"
  std::string rule;                                     // why, in words
  std::vector<std::pair<std::string, double>> numbers;  // {"nu dt / h^2", 0.092}, ...
};

struct NumericsParams {
  NumericsPreset preset = NumericsPreset::kDefault;
  // Not a scene key: filled by ParseScene, one entry per "auto" it resolved (the scene as run
  // names the values chosen, so reading it back resolves nothing).
  std::vector<ResolvedChoice> resolved;
};

// How a run treats the accuracy envelope (scene/accuracy_envelope.h): warn (default) or reject.
struct AccuracyParams {
  bool strict = false;  // a setting outside the envelope is an invalid scene
};

struct Params {
  std::string title;
  DomainParams domain;
  FluidParams fluid;
  Vec2 gravity = Vec2::Zero();
  TimeParams time;
  SplittingParams splitting;
  SolverParams solvers;
  std::vector<ParticleParams> particles;
  ParticleMeshParams particle_mesh;
  CollisionParams collisions;
  ConformationParams conformation;
  OutputParams output;
  AccuracyParams accuracy;
  NumericsParams numerics;
  int threads = 0;  // not a scene key: set by the program (0 = OpenMP default)
};

}  // namespace dlmfd
