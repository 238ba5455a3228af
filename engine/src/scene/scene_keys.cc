// The tables of scene keys (scene/scene_keys.h): every key of a scene declared once, in the order
// the writer writes them (scene.toml's text is the one checkpoints compare: do not reorder).
#include "dlmfd/scene/scene_keys.h"

#include <algorithm>
#include <string>

#include "dlmfd/particles/collocation_points.h"
#include "dlmfd/scene/auto_conformation_velocity.h"
#include "dlmfd/scene/auto_coupling.h"
#include "dlmfd/scene/auto_particle_mesh.h"
#include "scene_key_builders.h"

namespace dlmfd {
namespace scene {
namespace {

using P = Params;

constexpr KeyRange kRangeAny{KeyRange::kAny};
constexpr KeyRange kRangeFinite{KeyRange::kFinite};
constexpr KeyRange kRangePositive{KeyRange::kPositive};
constexpr KeyRange kRangeNonNegative{KeyRange::kNonNegative};
constexpr KeyRange kRangeOpenUnit{KeyRange::kOpenUnit};
constexpr KeyRange kRangeHalfOpenUnit{KeyRange::kHalfOpenUnit};
constexpr KeyRange kRangeAtLeastOne{KeyRange::kAtLeastOne};
constexpr KeyRange kRangeUnit{KeyRange::kClosed, 0.0, 1.0};

template <typename Record>
SceneKey<Record> Derived(SceneKey<Record> k, std::string text,
                         std::function<void(Params&)> derive) {
  k.default_kind = DefaultKind::kDerived;
  k.default_text = std::move(text);
  k.derive = std::move(derive);
  return k;
}

template <typename Record, typename Written>
SceneKey<Record> WrittenWhen(SceneKey<Record> k, Written written) {
  k.written = written;
  return k;
}

void AddTopAndDomain(std::vector<SceneKey<P>>& keys) {
  keys.push_back(StringKey<P>(
      "title", [](auto& p) -> auto& { return p.title; }, "name of the case"));
  SceneKey<P> gravity = VectorKey<P>(
      "gravity", [](auto& p) -> auto& { return p.gravity; }, "gravitational acceleration");
  gravity.alias = "fluid.gravity";
  keys.push_back(gravity);
  keys.push_back(
      WrittenWhen(ChoiceKey<NumericsPreset, P>(
                      "numerics.preset", [](auto& p) -> auto& { return p.numerics.preset; },
                      "the configuration the numerics keys default to (a key the "
                      "scene sets wins; scene/numerics_preset.h)"),
                  [](const P& p) { return p.numerics.preset != NumericsPreset::kDefault; }));
  keys.push_back(Allowed(VectorKey<P>(
                             "domain.size", [](auto& p) -> auto& { return p.domain.size; },
                             "the rectangle [0, w] x [0, h]"),
                         "both > 0; each an even number >= 4 of cells of `domain.h`"));
  keys.push_back(Allowed(RealKey<P>(
                             "domain.h", [](auto& p) -> auto& { return p.domain.h; },
                             kRangePositive, "velocity mesh size; the pressure mesh is 2h"),
                         "at most 2e7 velocity nodes"));
  keys.push_back(FromPreset(ChoiceKey<MeshDiagonals, P>(
      "domain.diagonals", [](auto& p) -> auto& { return p.domain.diagonals; },
      "which triangles the fluid's forms integrate on: the paper's SW-NE mesh, or the mean over "
      "both diagonals of every square")));
  keys.push_back(Allowed(
      OptionalRealKey<P>(
          "domain.flow_rate", [](auto& p) -> auto& { return p.domain.flow_rate; }, kRangeAny,
          "volume flux per unit depth along the periodic direction (in a box periodic in "
          "both: along x and y), held by a uniform mean pressure gradient "
          "(fluid/flux_control.h); absent: none"),
      "finite in a channel periodic in one direction whose other sides are `wall` or "
      "`velocity`; 0 in a box periodic in both directions"));
}

// The parameters of the constitutive models (conformation/relaxation_model.h): each required with
// its model and refused with any other.
void AddModelParameters(std::vector<SceneKey<P>>& keys) {
  const auto model_is = [](std::vector<ConstitutiveModel> models) {
    return [models](const P& p) {
      return std::find(models.begin(), models.end(), p.fluid.model) != models.end();
    };
  };
  keys.push_back(Required(OnlyWhere(
      Because(OptionalRealKey<P>(
                  "fluid.mobility", [](auto& p) -> auto& { return p.fluid.mobility; },
                  KeyRange{KeyRange::kClosed, 0.0, 0.5}, "Giesekus alpha"),
              "Giesekus alpha; above 0.5 the steady shear stress is not monotone in the shear "
              "rate"),
      model_is({ConstitutiveModel::kGiesekus}), "fluid.model = \"giesekus\"")));
  keys.push_back(Required(OnlyWhere(
      Because(OptionalRealKey<P>(
                  "fluid.extensibility", [](auto& p) -> auto& { return p.fluid.extensibility; },
                  KeyRange{KeyRange::kAbove, 2.0}, "FENE-P L^2"),
              "FENE-P L^2 with tr A < L^2; the rest state A = I has tr A = 2"),
      model_is({ConstitutiveModel::kFeneP}), "fluid.model = \"fene_p\"")));
  keys.push_back(Required(OnlyWhere(
      Because(OptionalRealKey<P>(
                  "fluid.ptt_epsilon", [](auto& p) -> auto& { return p.fluid.ptt_epsilon; },
                  KeyRange{KeyRange::kAtLeast, 0.0}, "PTT epsilon"),
              "PTT epsilon; 0 is Oldroyd-B"),
      model_is({ConstitutiveModel::kPttLinear, ConstitutiveModel::kPttExponential}),
      "fluid.model = \"ptt_linear\" or \"ptt_exponential\"")));
}

void AddFluid(std::vector<SceneKey<P>>& keys) {
  keys.push_back(RealKey<P>(
      "fluid.density", [](auto& p) -> auto& { return p.fluid.density; }, kRangePositive, "rho_L"));
  keys.push_back(RealKey<P>(
      "fluid.viscosity", [](auto& p) -> auto& { return p.fluid.viscosity; }, kRangePositive,
      "zero-shear viscosity eta = eta_s + eta_p"));
  keys.push_back(
      Allowed(RealKey<P>(
                  "fluid.relaxation_time", [](auto& p) -> auto& { return p.fluid.relaxation_time; },
                  kRangeNonNegative, "lambda_r; 0 is a Newtonian liquid"),
              "with `solvent_ratio` < 1, a steady inflow state on every velocity side"));
  keys.push_back(RealKey<P>(
      "fluid.solvent_ratio", [](auto& p) -> auto& { return p.fluid.solvent_ratio; },
      kRangeHalfOpenUnit,
      "beta = eta_s / eta; the polymer carries eta_p = (1 - beta) eta when lambda_r > 0"));
  keys.push_back(VectorKey<P>(
      "fluid.body_force", [](auto& p) -> auto& { return p.fluid.body_force; },
      "force per unit volume on the liquid"));
  keys.push_back(Allowed(
      ChoiceKey<ConstitutiveModel, P>(
          "fluid.model", [](auto& p) -> auto& { return p.fluid.model; },
          "constitutive model of the polymer "
          "(conformation/relaxation_model.h)"),
      "other than `oldroyd_b` only with a polymer (`relaxation_time` > 0, `solvent_ratio` < 1)"));
  keys.push_back(
      Allowed(ChoiceKey<ConformationRepresentation, P>(
                  "fluid.conformation", [](auto& p) -> auto& { return p.fluid.conformation; },
                  "the variable step (35) advects: A, log A or A^(1/2)"),
              "other than `standard` only with a polymer"));
  keys.push_back(FromPreset(ChoiceKey<StressSplitting, P>(
      "fluid.stress_splitting", [](auto& p) -> auto& { return p.fluid.stress_splitting; },
      "how the polymer stress enters the momentum equation: all explicit, or DEVSS-G")));
  AddModelParameters(keys);
}

void AddTimeAndSplitting(std::vector<SceneKey<P>>& keys) {
  keys.push_back(Allowed(
      RealKey<P>(
          "time.dt", [](auto& p) -> auto& { return p.time.dt; }, kRangePositive, "time step"),
      "<= `time.end`; at most 2^53 steps"));
  keys.push_back(Because(RealKey<P>(
                             "time.end", [](auto& p) -> auto& { return p.time.end; },
                             kRangePositive, "end time; the run makes round(end / dt) steps"),
                         "a run to t = 0 makes no step"));
  keys.push_back(Because(
      Derived(RealKey<P>(
                  "splitting.alpha", [](auto& p) -> auto& { return p.splitting.alpha; },
                  kRangeHalfOpenUnit, "viscosity weight of the Stokes step (33)"),
              "`1`, or `0.5` with `constraint = \"paper\"`",
              [](Params& p) {  // once "auto" has chosen the coupling
                if (!p.splitting.constraint) return;
                p.splitting.alpha = SplittingParams::DefaultWeights(*p.splitting.constraint).alpha;
              }),
      "the Stokes step (33) carries viscosity for its fast solver; with alpha = 0 it has "
      "none"));
  keys.push_back(Allowed(
      Derived(RealKey<P>(
                  "splitting.beta", [](auto& p) -> auto& { return p.splitting.beta; }, kRangeUnit,
                  "viscosity weight of the advection step (34)"),
              "`0`, or `0.5` with `constraint = \"paper\"`",
              [](Params& p) {  // once "auto" has chosen the coupling
                if (!p.splitting.constraint) return;
                p.splitting.beta = SplittingParams::DefaultWeights(*p.splitting.constraint).beta;
              }),
      "alpha + beta = 1; 0 with particles unless `constraint = \"paper\"`"));
  keys.push_back(FromPreset(ChoiceKey<AdvectionScheme, P>(
      "splitting.advection", [](auto& p) -> auto& { return p.splitting.advection; },
      "step (34): the paper's least-squares CG or the explicit wave-like scheme")));
  SceneKey<P> constraint = FromPreset(ChoiceKey<ConstraintCoupling, P>(
      "splitting.constraint", [](auto& p) -> auto& { return p.splitting.constraint; },
      "where the rigid-body constraint meets the fluid; `auto` picks one from the scene's numbers "
      "(scene/auto_coupling.h)",
      ResolveConstraintCoupling));
  // Absent in the struct: "auto", which depends on the rest of the scene.
  constraint.unset = [](const P& p) { return !p.splitting.constraint; };
  constraint.get = [](const P& p) -> KeyValue {
    const auto& c = p.splitting.constraint;
    return c ? std::string(WordOf(*c)) : ResolveConstraintCoupling(p).value;
  };
  keys.push_back(constraint);
  SceneKey<P> correction = FromPreset(ChoiceKey<SteadyCorrection, P>(
      "splitting.steady_correction", [](auto& p) -> auto& { return p.splitting.steady_correction; },
      "what step (34) does about the splitting's steady-state error"));
  // Absent in the struct: the preset's word depends on the liquid.
  correction.unset = [](const P& p) { return !p.splitting.steady_correction; };
  correction.get = [](const P& p) -> KeyValue {
    const auto& c = p.splitting.steady_correction;
    return c ? std::string(WordOf(*c))
             : PresetWord(p.numerics.preset, "splitting.steady_correction", p);
  };
  keys.push_back(correction);
}

void AddSolvers(std::vector<SceneKey<P>>& keys) {
  keys.push_back(RealKey<P>(
      "solvers.stokes_tolerance", [](auto& p) -> auto& { return p.solvers.stokes_tolerance; },
      kRangeOpenUnit, "Uzawa/PCG, relative to a fixed reference residual"));
  keys.push_back(IntegerKey<P>(
      "solvers.stokes_max_iterations",
      [](auto& p) -> auto& { return p.solvers.stokes_max_iterations; }, kRangeAtLeastOne,
      "of the Uzawa/PCG"));
  keys.push_back(RealKey<P>(
      "solvers.advection_tolerance", [](auto& p) -> auto& { return p.solvers.advection_tolerance; },
      kRangeOpenUnit, "LS-CG, ratio of gradient norms"));
  keys.push_back(IntegerKey<P>(
      "solvers.advection_max_iterations",
      [](auto& p) -> auto& { return p.solvers.advection_max_iterations; }, kRangeAtLeastOne,
      "of the LS-CG"));
  keys.push_back(RealKey<P>(
      "solvers.wave_max_courant", [](auto& p) -> auto& { return p.solvers.wave_max_courant; },
      kRangeHalfOpenUnit, "wave-like scheme: sub-steps with abs(u) tau / h below this"));
  keys.push_back(RealKey<P>(
      "solvers.multiplier_tolerance",
      [](auto& p) -> auto& { return p.solvers.multiplier_tolerance; }, kRangeOpenUnit,
      "DLM CG of (37), relative"));
  keys.push_back(IntegerKey<P>(
      "solvers.multiplier_max_iterations",
      [](auto& p) -> auto& { return p.solvers.multiplier_max_iterations; }, kRangeAtLeastOne,
      "of the DLM CG (37) and the viscous coupling's PCG"));
  keys.push_back(FromPreset(ChoiceKey<MultiplierPreconditioning, P>(
      "solvers.multiplier_preconditioner",
      [](auto& p) -> auto& { return p.solvers.multiplier_preconditioner; },
      "DLM CG (37): the product G alone (the paper's), or each particle's block factored")));
}

void AddParticleMeshAndCollisions(std::vector<SceneKey<P>>& keys) {
  keys.push_back(FromPreset(ChoiceKey<ParticleMeshKind, P>(
      "particle_mesh.kind", [](auto& p) -> auto& { return p.particle_mesh.kind; },
      "the multiplier points of (37): the paper's ring mesh, collocation points on the true "
      "circle, or no multipliers (cut cells: fixed, prescribed or free disks and fixed ellipses, "
      "with or without a polymer, and prescribed or free ellipses in a Newtonian liquid; any "
      "sides); "
      "`auto` picks cut cells for fixed disks (in a Newtonian, Oldroyd-B or Giesekus liquid) and "
      "fixed ellipses (in a Newtonian liquid) over a run of at least " +
          std::to_string(kMinCutCellSteps) +
          " steps, collocation points otherwise (scene/auto_particle_mesh.h)",
      ResolveParticleMeshKind)));
  SceneKey<P> ring_h = Allowed(
      Derived(RealKey<P>(
                  "particle_mesh.h", [](auto& p) -> auto& { return p.particle_mesh.h; },
                  kRangePositive, "multiplier mesh size h_p of the ring mesh"),
              "`96/70 domain.h` (the paper's ratio), following `domain.h`",
              [](Params& p) { p.particle_mesh.h = p.particle_mesh.RingMeshSize(p.domain.h); }),
      "`ring`: at most the smallest particle's radius; at most 2e7 multiplier nodes");
  // Absent in the struct: it follows domain.h (ParticleMeshParams::RingMeshSize).
  ring_h.unset = [](const P& p) { return !p.particle_mesh.h; };
  ring_h.get = [](const P& p) -> KeyValue { return p.particle_mesh.RingMeshSize(p.domain.h); };
  keys.push_back(ring_h);
  keys.push_back(RealKey<P>(
      "particle_mesh.spacing", [](auto& p) -> auto& { return p.particle_mesh.spacing; },
      {KeyRange::kClosed, kMinCollocationSpacing, kMaxCollocationSpacing},
      "boundary point spacing in units of domain.h"));
  keys.push_back(ChoiceKey<BoundaryInterpolation, P>(
      "particle_mesh.interpolation", [](auto& p) -> auto& { return p.particle_mesh.interpolation; },
      "`collocation`: how E evaluates the velocity at the boundary points"));
  keys.push_back(RealKey<P>(
      "particle_mesh.rigid_modes_refresh",
      [](auto& p) -> auto& { return p.particle_mesh.rigid_modes_refresh; }, kRangeNonNegative,
      "`cut_cell`, free bodies: Newton's law's matrix K (3 unit Stokes solves a body) is made anew "
      "once a body has moved this far since it was made, in units of h (0: every step); in "
      "between a step makes one more Stokes solve, at the new velocity. At 1 the 5.2 pair's "
      "velocities move by 1e-4 of their largest and a step costs a quarter of K every step's "
      "(docs/evidence/cut_cell_boundary.md, \"A free body\")"));
  keys.push_back(RealKey<P>(
      "collisions.range", [](auto& p) -> auto& { return p.collisions.range; }, kRangePositive,
      "rho of (14)-(15), in units of h"));
  keys.push_back(RealKey<P>(
      "collisions.wall_stiffness", [](auto& p) -> auto& { return p.collisions.wall_stiffness; },
      kRangePositive, "epsilon_w"));
  keys.push_back(RealKey<P>(
      "collisions.particle_stiffness",
      [](auto& p) -> auto& { return p.collisions.particle_stiffness; }, kRangePositive,
      "epsilon_p"));
  keys.push_back(IntegerKey<P>(
      "collisions.substeps", [](auto& p) -> auto& { return p.collisions.substeps; },
      kRangeAtLeastOne, "K of (36) and (38)"));
}

void AddConformationOutputAccuracy(std::vector<SceneKey<P>>& keys) {
  keys.push_back(ChoiceKey<ConformationForm, P>(
      "conformation.form", [](auto& p) -> auto& { return p.conformation.form; },
      "the conformation tensor is stored as A itself"));
  SceneKey<P> velocity = FromPreset(ChoiceKey<ConformationVelocity, P>(
      "conformation.velocity", [](auto& p) -> auto& { return p.conformation.velocity; },
      "the velocity step (35) freezes: the advected u^{n+2/4} (the paper's) or the Stokes step's "
      "u^{n+1/4}; `auto` (the default in a polymer liquid) picks the Stokes step's without "
      "particles and around fixed and free disks cut out of the mesh, the paper's with multiplier "
      "points (scene/auto_conformation_velocity.h)",
      ResolveConformationVelocity));
  // Absent in the struct: the preset's word depends on the liquid, and "auto" on the particles.
  velocity.unset = [](const P& p) { return !p.conformation.velocity; };
  velocity.get = [](const P& p) -> KeyValue {
    const auto& v = p.conformation.velocity;
    if (v) return std::string(WordOf(*v));
    const std::string word = PresetWord(p.numerics.preset, "conformation.velocity", p);
    return word == "auto" ? ResolveConformationVelocity(p).value : word;
  };
  keys.push_back(velocity);
  keys.push_back(RealKey<P>(
      "conformation.max_courant", [](auto& p) -> auto& { return p.conformation.max_courant; },
      kRangeHalfOpenUnit, "advection sub-cycling of (35)"));
  keys.push_back(RealKey<P>(
      "conformation.blend_kappa", [](auto& p) -> auto& { return p.conformation.blend_kappa; },
      kRangeHalfOpenUnit, "SPD blend: lambda_min(A) >= kappa lambda_min(A_low)"));
  const char* const kPeriod = "when > 0, at least `time.end` / 2^53";
  keys.push_back(
      Allowed(RealKey<P>(
                  "output.fields_every", [](auto& p) -> auto& { return p.output.fields_every; },
                  kRangeNonNegative, "simulated time between field snapshots; 0 = none"),
              kPeriod));
  keys.push_back(Allowed(
      RealKey<P>(
          "output.particles_every", [](auto& p) -> auto& { return p.output.particles_every; },
          kRangeNonNegative, "between records of particles.h5; 0 = every step"),
      kPeriod));
  keys.push_back(Allowed(
      RealKey<P>(
          "output.checkpoint_every", [](auto& p) -> auto& { return p.output.checkpoint_every; },
          kRangeNonNegative, "between checkpoints; 0 = none"),
      kPeriod));
  keys.push_back(
      WrittenWhen(BooleanKey<P>(
                      "accuracy.strict", [](auto& p) -> auto& { return p.accuracy.strict; },
                      "a setting outside the accuracy envelope is an invalid scene, not a warning"),
                  [](const P& p) { return p.accuracy.strict; }));
}

// The rules that check a key together with other keys (a range or a choice of one key is its
// table entry's; these need several): the key by its docs name, and the function, by its file.
// ValidateScene (scene_validation.cc) calls each; docs/scenes.md's allowed column names them.
struct CrossKeyRule {
  const char* key;
  const char* rule;
};
constexpr CrossKeyRule kCrossKeyRules[] = {
    {"domain.size", "RequireEvenCells (scene/scene_validation.cc)"},
    {"domain.h", "ValidateDomain (scene/scene_validation.cc)"},
    {"domain.flow_rate", "ValidateFlowRate (scene/scene_validation.cc)"},
    {"domain.boundary.SIDE.profile", "ValidateBoundaryProfiles (fluid/boundary_profile.h)"},
    {"domain.boundary.SIDE.ramp_time", "ValidateBoundaryProfiles (fluid/boundary_profile.h)"},
    {"fluid.relaxation_time", "ValidateInflowStates (conformation/inflow_state.h)"},
    {"fluid.model", "ValidateConstitutiveModel (conformation/relaxation_model.h)"},
    {"fluid.conformation", "ValidateConstitutiveModel (conformation/relaxation_model.h)"},
    {"time.dt", "ValidateTimeSteps (core/time_stepping.h)"},
    {"splitting.alpha", "ValidateSplitting (core/time_stepping.h)"},
    {"splitting.beta", "ValidateSplitting (core/time_stepping.h)"},
    {"particle_mesh.h", "ValidateRingMesh (scene/scene_validation.cc)"},
    {"output.fields_every", "ValidateOutputPeriods (core/time_stepping.h)"},
    {"output.particles_every", "ValidateOutputPeriods (core/time_stepping.h)"},
    {"output.checkpoint_every", "ValidateOutputPeriods (core/time_stepping.h)"},
    {"particles.N.center", "ValidateParticles (particles/particle_rules.h)"},
    {"particles.N.shape", "ValidateParticles (particles/particle_rules.h)"},
    {"particles.N.semi_axes", "RequireEllipseAxes (scene/scene_validation.cc)"},
    {"particles.N.density", "ValidateParticles (particles/particle_rules.h)"},
};

// Names each key's cross-key rule (kCrossKeyRules); `prefix` makes the docs name of a record's key.
template <typename Record>
std::vector<SceneKey<Record>> WithRules(std::vector<SceneKey<Record>> keys,
                                        const std::string& prefix) {
  for (SceneKey<Record>& k : keys) {
    for (const CrossKeyRule& r : kCrossKeyRules) {
      if (prefix + k.name == r.key) k.rule = r.rule;
    }
  }
  return keys;
}

std::vector<SceneKey<P>> MakeSceneKeys() {
  std::vector<SceneKey<P>> keys;
  AddTopAndDomain(keys);
  AddFluid(keys);
  AddTimeAndSplitting(keys);
  AddSolvers(keys);
  AddParticleMeshAndCollisions(keys);
  AddConformationOutputAccuracy(keys);
  return WithRules(std::move(keys), "");
}

using S = BoundarySide;

bool IsVelocity(const S& s) { return s.type == SideType::kVelocity; }

std::vector<SceneKey<S>> MakeSideKeys() {
  std::vector<SceneKey<S>> keys;
  keys.push_back(Required(ChoiceKey<SideType, S>(
      "type", [](auto& s) -> auto& { return s.type; },
      "wall: zero velocity; velocity: given velocity; outflow: zero traction; periodic: with "
      "the opposite side")));
  keys.push_back(Allowed(Where(ChoiceKey<Profile, S>(
                                   "profile", [](auto& s) -> auto& { return s.profile; },
                                   "velocity sides: the data along the side "
                                   "(fluid/boundary_profile.h)"),
                               IsVelocity),
                         "`quartic` with a tangential `max` only"));
  keys.push_back(Required(Where(
      VectorKey<S>(
          "value", [](auto& s) -> auto& { return s.value; }, "the velocity on a uniform side"),
      [](const S& s) { return IsVelocity(s) && s.profile == Profile::kUniform; })));
  keys.push_back(
      Required(Where(VectorKey<S>(
                         "max", [](auto& s) -> auto& { return s.max; },
                         "poiseuille, quartic: the velocity at mid-side"),
                     [](const S& s) { return IsVelocity(s) && s.profile != Profile::kUniform; })));
  keys.push_back(
      Allowed(Where(RealKey<S>(
                        "ramp_time", [](auto& s) -> auto& { return s.ramp_time; }, kRangeAny,
                        "0: steady data; T > 0: the data times (1 + tanh(4 (t/T - 1)))/2"),
                    IsVelocity),
              ">= 0; other than 0 only for tangential data (no liquid enters)"));
  return keys;
}

using Q = ParticleParams;

bool IsDisk(const Q& q) { return q.shape == ShapeKind::kDisk; }

std::vector<SceneKey<Q>> MakeParticleKeys() {
  std::vector<SceneKey<Q>> keys;
  keys.push_back(
      Allowed(Required(VectorKey<Q>(
                  "center", [](auto& q) -> auto& { return q.center; }, "position at t = 0")),
              "inside the domain; its bounding circle crossing no non-periodic side "
              "and no other particle's at t = 0"));
  keys.push_back(WrittenWhen(ChoiceKey<ShapeKind, Q>(
                                 "shape", [](auto& q) -> auto& { return q.shape; },
                                 "`ellipse` needs `particle_mesh.kind = \"collocation\"`"),
                             [](const Q& q) { return !IsDisk(q); }));
  SceneKey<Q> diameter = Where(RealKey<Q>(
                                   "diameter", [](auto& q) -> auto& { return q.diameter; },
                                   kRangePositive, "a disk's diameter (a disk only)"),
                               IsDisk);
  diameter.refused = "absent for an ellipse (give semi_axes = [a, b]), or shape = \"disk\"";
  keys.push_back(diameter);
  SceneKey<Q> axes =
      Required(Where(VectorKey<Q>(
                         "semi_axes", [](auto& q) -> auto& { return q.semi_axes; },
                         "an ellipse's semi-axes along the body's x and y axes (an ellipse only)"),
                     [](const Q& q) { return !IsDisk(q); }));
  axes.read = [](TableReader& t, const std::string& leaf, Q& q) {
    const Vec2 a = t.Vector(leaf, std::nullopt);
    q.SetEllipse(a.x(), a.y());
  };
  axes.refused = "absent for a disk (give diameter), or shape = \"ellipse\"";
  axes.allowed_note = "both > 0, max / min <= 8";
  keys.push_back(axes);
  keys.push_back(
      WrittenWhen(RealKey<Q>(
                      "angle", [](auto& q) -> auto& { return q.angle; }, kRangeFinite,
                      "orientation at t = 0 (radians): the body's x axis from the domain's"),
                  [](const Q& q) { return q.angle != 0.0; }));
  keys.push_back(
      Allowed(RealKey<Q>(
                  "density", [](auto& q) -> auto& { return q.density; }, kRangePositive, "rho_d"),
              ">= `fluid.density` for a free particle (equal: neutrally buoyant), any with "
              "`particle_mesh.kind = \"cut_cell\"`"));
  keys.push_back(VectorKey<Q>(
      "velocity", [](auto& q) -> auto& { return q.velocity; }, "initial (or prescribed) velocity"));
  keys.push_back(RealKey<Q>(
      "angular_velocity", [](auto& q) -> auto& { return q.angular_velocity; }, kRangeFinite,
      "initial (or prescribed) angular velocity"));
  keys.push_back(ChoiceKey<Motion, Q>(
      "motion", [](auto& q) -> auto& { return q.motion; },
      "prescribed: velocity held at the given values"));
  return keys;
}

// numerics.preset's table: key = word, for one liquid or both (scene/numerics_preset.h).
enum class PresetLiquid { kAny, kNewtonian, kPolymer };
struct PresetEntry {
  NumericsPreset preset;
  const char* key;
  const char* word;
  PresetLiquid liquid;
};

constexpr PresetEntry kPresets[] = {
    {NumericsPreset::kDefault, "particle_mesh.kind", "auto", PresetLiquid::kAny},
    {NumericsPreset::kDefault, "domain.diagonals", "both", PresetLiquid::kAny},
    {NumericsPreset::kDefault, "splitting.advection", "wave", PresetLiquid::kAny},
    {NumericsPreset::kDefault, "splitting.constraint", "auto", PresetLiquid::kAny},
    {NumericsPreset::kDefault, "fluid.stress_splitting", "devss", PresetLiquid::kAny},
    {NumericsPreset::kDefault, "splitting.steady_correction", "tendency", PresetLiquid::kNewtonian},
    {NumericsPreset::kDefault, "splitting.steady_correction", "none", PresetLiquid::kPolymer},
    {NumericsPreset::kDefault, "solvers.multiplier_preconditioner", "gram", PresetLiquid::kAny},
    {NumericsPreset::kDefault, "conformation.velocity", "advected", PresetLiquid::kNewtonian},
    {NumericsPreset::kDefault, "conformation.velocity", "auto", PresetLiquid::kPolymer},
    {NumericsPreset::kPaper, "particle_mesh.kind", "ring", PresetLiquid::kAny},
    {NumericsPreset::kPaper, "domain.diagonals", "sw_ne", PresetLiquid::kAny},
    {NumericsPreset::kPaper, "splitting.advection", "least_squares", PresetLiquid::kAny},
    {NumericsPreset::kPaper, "splitting.constraint", "paper", PresetLiquid::kAny},
    {NumericsPreset::kPaper, "fluid.stress_splitting", "explicit", PresetLiquid::kAny},
    {NumericsPreset::kPaper, "splitting.steady_correction", "none", PresetLiquid::kAny},
    {NumericsPreset::kPaper, "solvers.multiplier_preconditioner", "gram", PresetLiquid::kAny},
    {NumericsPreset::kPaper, "conformation.velocity", "advected", PresetLiquid::kAny},
};

}  // namespace

const std::vector<SceneKey<Params>>& SceneKeys() {
  static const std::vector<SceneKey<Params>> keys = MakeSceneKeys();
  return keys;
}

const std::vector<SceneKey<BoundarySide>>& SideKeys() {
  static const std::vector<SceneKey<BoundarySide>> keys =
      WithRules(MakeSideKeys(), "domain.boundary.SIDE.");
  return keys;
}

const std::vector<SceneKey<ParticleParams>>& ParticleKeys() {
  static const std::vector<SceneKey<ParticleParams>> keys =
      WithRules(MakeParticleKeys(), "particles.N.");
  return keys;
}

std::string PresetWord(NumericsPreset preset, const std::string& key, const Params& params) {
  const PresetLiquid liquid =
      params.fluid.IsNewtonian() ? PresetLiquid::kNewtonian : PresetLiquid::kPolymer;
  for (const PresetEntry& e : kPresets) {
    if (e.preset == preset && key == e.key &&
        (e.liquid == PresetLiquid::kAny || e.liquid == liquid)) {
      return e.word;
    }
  }
  return "";
}

std::string SectionOf(const std::string& name) {
  const auto dot = name.rfind('.');
  return dot == std::string::npos ? std::string() : name.substr(0, dot);
}

std::string LeafOf(const std::string& name) {
  const auto dot = name.rfind('.');
  return dot == std::string::npos ? name : name.substr(dot + 1);
}

std::string AllowedWords(const std::vector<std::string>& words) {
  std::string allowed = "one of";
  for (std::size_t i = 0; i < words.size(); ++i) {
    allowed += std::string(i > 0 ? ", " : " ") + "\"" + words[i] + "\"";
  }
  return allowed;
}

}  // namespace scene
}  // namespace dlmfd
