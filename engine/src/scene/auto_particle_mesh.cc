// particle_mesh.kind = "auto": the rules, one function each, tried in order
// (scene/auto_particle_mesh.h). A rule returns the kind it picks, or nothing when it does not
// apply; the evidence for each is beside it. To add a rule: write its function, put it in kRules at
// its place in the order, pin it with a test in tests/unit/auto_particle_mesh_test.cc and list it
// in the header and in the key's description (docs/scenes.md is generated from it).
#include "dlmfd/scene/auto_particle_mesh.h"

#include <cmath>
#include <optional>
#include <string>

#include "dlmfd/core/param_words.h"
#include "dlmfd/particles/particle_rules.h"

namespace dlmfd {
namespace mesh_rules {  // named: the unity build puts auto_coupling.cc's rules beside these
namespace {

struct Pick {
  ParticleMeshKind kind;
  std::string rule;  // why, in words; the numbers follow it in the record
};

using Rule = std::optional<Pick> (*)(const Params&);

// round(end / dt), the run's steps, as a double: "auto" is resolved before ValidateScene bounds
// the step count (StepCount, core/time_stepping.h, wants a validated time).
double Steps(const Params& p) { return std::round(p.time.end / p.time.dt); }

// 1. Nothing to hold: the kind is not used; the struct's default names it.
std::optional<Pick> NoParticles(const Params& p) {
  if (!p.particles.empty()) return std::nullopt;
  return Pick{ParticleMeshKind::kCollocation, "no particles"};
}

// 2. The cut cells' accuracy was measured on fixed ellipses in a Newtonian liquid
// (docs/evidence/cut_cell_boundary.md, "A fixed ellipse": forces and torque within 0.06-0.2 % over
// sub-grid positions at D/h = 20, against the collocation points' 1.0-3.0 %), not in a polymer.
// A moving one in a Newtonian liquid is cut accurately ("Moving ellipses": Jeffery's quarter turn
// spreads 0.14 % over sub-grid positions at h = 1/32 against the collocation points' 2 %) but its
// step costs 10 times theirs (5.7 against 0.55 CPU ms there): it keeps the collocation points that
// particles.N.shape names, as a moving disk does by rule 3.
std::optional<Pick> NotDisks(const Params& p) {
  for (std::size_t i = 0; i < p.particles.size(); ++i) {
    const ParticleParams& q = p.particles[i];
    if (q.shape == ShapeKind::kDisk || (q.motion == Motion::kFixed && p.fluid.IsNewtonian())) {
      continue;
    }
    return Pick{ParticleMeshKind::kCollocation,
                "particles." + std::to_string(i) +
                    " is not a disk (cut cells are the default for fixed ellipses in a Newtonian "
                    "liquid only)"};
  }
  return std::nullopt;
}

// 3. A particle that moves: cut cells recut the band and refactorise the capacitance matrix every
// step, 5.5 times a fixed body's step at D/h = 20 (docs/evidence/cut_cell_boundary.md, "A body in
// prescribed motion"), and a free body adds three Stokes solves a step ("A free body"): not yet
// affordable.
std::optional<Pick> MovingParticles(const Params& p) {
  for (std::size_t i = 0; i < p.particles.size(); ++i) {
    if (p.particles[i].motion == Motion::kFixed) continue;
    return Pick{ParticleMeshKind::kCollocation,
                "particles." + std::to_string(i) +
                    " moves (cut cells are measured affordable for fixed bodies only)"};
  }
  return std::nullopt;
}

// 4. A polymer model the cut cells were not measured with. Around fixed disks they carry the
// Oldroyd-B and Giesekus liquids closer to the literature and to their own grid limit than the
// collocation points, standard and log alike, at less cost than the viscous coupling those need in
// creeping flow (docs/evidence/cut_cell_boundary.md, "The polymer around fixed bodies"); FENE-P
// and PTT were not run with them, so they keep the collocation points that docs/accuracy.md gives.
std::optional<Pick> UnmeasuredPolymer(const Params& p) {
  if (p.fluid.IsNewtonian()) return std::nullopt;
  const ConstitutiveModel model = p.fluid.model;
  if (model == ConstitutiveModel::kOldroydB || model == ConstitutiveModel::kGiesekus) {
    return std::nullopt;
  }
  return Pick{ParticleMeshKind::kCollocation,
              "fluid.model = \"" + std::string(WordOf(model)) +
                  "\" (cut cells were measured with Oldroyd-B and Giesekus liquids only)"};
}

// 5. What the cut-cell step cannot run (the one predicate RequireCutCellScene throws from).
std::optional<Pick> CutCellsRefuse(const Params& p) {
  const std::optional<InvalidParameter> obstacle = CutCellObstacle(p);
  if (!obstacle) return std::nullopt;
  return Pick{ParticleMeshKind::kCollocation,
              "cut cells cannot run " + obstacle->key() + " = " + obstacle->value()};
}

// 6. A short run: the cut cells' set-up costs as much as 56-101 of their first steps (2.1 CPU s
// at Schaefer-Turek D/h = 20 against 0.15 for the collocation points), which only a run of
// kMinCutCellSteps steps or more repays (auto_particle_mesh.h).
std::optional<Pick> ShortRun(const Params& p) {
  if (Steps(p) >= static_cast<double>(kMinCutCellSteps)) return std::nullopt;
  return Pick{ParticleMeshKind::kCollocation,
              "fewer steps than the cut cells' set-up needs to pay"};
}

// 7. Fixed bodies over a run long enough: second order, no dependence on the sub-grid position
// worth the name, at less cost than the grid the collocation points need for that accuracy.
std::optional<Pick> CutCells(const Params&) {
  return Pick{ParticleMeshKind::kCutCell,
              "fixed bodies over a run long enough for the set-up to pay"};
}

constexpr Rule kRules[] = {NoParticles,    NotDisks, MovingParticles, UnmeasuredPolymer,
                           CutCellsRefuse, ShortRun, CutCells};

}  // namespace
}  // namespace mesh_rules

ResolvedChoice ResolveParticleMeshKind(const Params& params) {
  ResolvedChoice choice;
  choice.key = "particle_mesh.kind";
  for (mesh_rules::Rule rule : mesh_rules::kRules) {
    std::optional<mesh_rules::Pick> pick = rule(params);
    if (!pick) continue;
    choice.value = WordOf(pick->kind);
    choice.rule = std::move(pick->rule);
    break;
  }
  choice.numbers = {{"steps", mesh_rules::Steps(params)},
                    {"steps to pay the set-up", static_cast<double>(kMinCutCellSteps)}};
  return choice;
}

}  // namespace dlmfd
