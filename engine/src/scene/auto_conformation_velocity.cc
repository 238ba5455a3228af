// conformation.velocity = "auto": the rules, one function each, tried in order
// (scene/auto_conformation_velocity.h). A rule returns the velocity it picks, or nothing when it
// does not apply; the evidence for each is beside it. To add a rule: write its function, put it in
// kRules at its place in the order, pin it with a test in
// tests/unit/auto_conformation_velocity_test.cc and list it in the header and in the key's
// description (docs/scenes.md is generated from it).
#include "dlmfd/scene/auto_conformation_velocity.h"

#include <optional>
#include <string>

#include "dlmfd/core/param_words.h"

namespace dlmfd {
namespace velocity_rules {  // named: the unity build puts the other "auto" rules beside these
namespace {

struct Pick {
  ConformationVelocity velocity;
  std::string rule;  // why, in words
};

using Rule = std::optional<Pick> (*)(const Params&);

// 1. A polymer without particles: the steady stress of the Fattal-Kupferman cavity (Wi = 0.5,
// 64^2) lies 0.10 % from its dt -> 0 limit at the scene's dt (the paper's velocity: 1.38 %), the
// stagnation point's of the planar stagnation flow (Wi = 0.3) 0.19 % (2.03 %); the Waters-King
// start-up, whose advection vanishes, is the same to 1e-14, and stable to dt = 0.0225 and unstable
// from 0.025 with both (past that limit its wave along x grows 1.2-1.6 times faster a step with
// "stokes", which `advected` damps with the advection step's streamline diffusion).
// docs/evidence/splitting.md, "Without particles and around moving ones".
std::optional<Pick> NoParticles(const Params& p) {
  if (!p.particles.empty()) return std::nullopt;
  return Pick{ConformationVelocity::kStokes,
              "no particles (the steady stress without the advection step's O(dt U / L))"};
}

// 2. Multiplier points (every moving particle but the cut-cell disks): the paper's polymer
// cases 5.2, 5.3 and the collocation points' confined cylinder were measured with the paper's
// velocity. The Stokes step's was run on a settling disk (5.1b's liquid at Re ~ 30 and 5.2's at Re
// ~ 0.6, h = 1/48) and on the 5.2 pair (h = 1/48 and 1/96): the same to 1e-4 below Re ~ 1, and at
// Re ~ 30 1.5 times closer to its dt -> 0 limit, a coarse transient only
// (docs/evidence/splitting.md, "Without particles and around moving ones").
std::optional<Pick> MultiplierPoints(const Params& p) {
  if (p.particle_mesh.kind == ParticleMeshKind::kCutCell) return std::nullopt;
  return Pick{ConformationVelocity::kAdvected,
              "particle_mesh.kind = \"" + std::string(WordOf(p.particle_mesh.kind)) +
                  "\" (the Stokes step's velocity was measured there on coarse grids only)"};
}

// 3. Disks cut out of the mesh (fixed, prescribed or free): the confined cylinder's K within
// 0.07 % of its dt -> 0 limit at the scene's dt = lambda / 120 (the paper's velocity: 0.34 %;
// R/h = 16, Wi = 0.6), and at R/h = 24 closer to the literature at Wi = 0.6 and 0.9
// (+0.14 / +1.72 % against +0.58 / +2.67 %, standard). docs/evidence/splitting.md, "Around fixed
// disks cut out of the mesh". A free disk settling in Oldroyd-B (Wi about 0.19): the two
// velocities within 1.5e-4 of each other at D/h = 10 and 20 and at dt = lambda / 20 to
// lambda / 80 (docs/evidence/cut_cell_boundary.md, "The polymer around a free body"); a disk towed
// through Oldroyd-B (Wi = 0.2, D/h = 20): drags within 0.011 % ("The polymer around a towed
// body").
std::optional<Pick> CutCells(const Params&) {
  return Pick{ConformationVelocity::kStokes,
              "fixed, prescribed or free disks cut out of the mesh (the steady stress without the "
              "advection step's O(dt U / L))"};
}

constexpr Rule kRules[] = {NoParticles, MultiplierPoints, CutCells};

}  // namespace
}  // namespace velocity_rules

ResolvedChoice ResolveConformationVelocity(const Params& params) {
  ResolvedChoice choice;
  choice.key = "conformation.velocity";
  for (velocity_rules::Rule rule : velocity_rules::kRules) {
    std::optional<velocity_rules::Pick> pick = rule(params);
    if (!pick) continue;
    choice.value = WordOf(pick->velocity);
    choice.rule = std::move(pick->rule);
    break;
  }
  choice.numbers = {{"particles", static_cast<double>(params.particles.size())}};
  return choice;
}

}  // namespace dlmfd
