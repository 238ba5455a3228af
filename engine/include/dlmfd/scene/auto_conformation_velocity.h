// conformation.velocity = "auto", the default in a polymer liquid: the velocity the conformation
// step (35) freezes (core/params.h, ConformationVelocity), chosen from the particle mesh the scene
// runs. A Newtonian scene has no step (35); the "default" preset gives it "advected" without a rule
// (PresetWord, scene/scene_keys.h), and numerics.preset = "paper" gives "advected" everywhere.
//
// Why: the paper's u^{n+2/4} carries the advection step's - dt (u.grad) u into (35), so a steady
// stress carries an O(dt U / L) error that does not shrink with the Reynolds number; the Stokes
// step's u^{n+1/4} removes it (docs/evidence/splitting.md, "The velocity the conformation step
// sees"). Around fixed disks with cut cells it made the confined cylinder's K nearly independent
// of dt (within 0.07 % of its dt -> 0 limit at dt = lambda / 120, against 0.34 %) and closer to
// the literature at Wi = 0.6 and 0.9 (docs/evidence/splitting.md, "Around fixed disks cut out of
// the mesh"); without particles it put the steady stress of the cavity and of the stagnation flow
// 2-14 times closer to its dt -> 0 limit (docs/evidence/splitting.md, "Without particles and
// around moving ones").
// The rules are tried in order and the first that applies decides; each is one function in
// scene/auto_conformation_velocity.cc with its evidence beside it, and one test pins it
// (tests/unit/auto_conformation_velocity_test.cc). The last rule always applies.
//   1. No particles: "stokes" (the Fattal-Kupferman cavity and the planar stagnation flow; the
//      Waters-King start-up, whose advection vanishes, is the same to round-off, and its time
//      step's stability limit is the same; past it "stokes" fails sooner).
//   2. Particles held by multiplier points (ring mesh or collocation points), which includes every
//      moving particle but the cut-cell disks: "advected" (the paper's polymer cases 5.2
//      and 5.3 and the collocation points' polymer figures in docs/accuracy.md were measured with
//      it; "stokes" was measured on a settling disk and the 5.2 pair on a coarse grid only: the
//      same below Re ~ 1, 1.5 times closer to its dt -> 0 limit at Re ~ 30).
//   3. Otherwise (fixed, prescribed or free disks cut out of the mesh): "stokes".
// The choice, the rule and the numbers it read go where the particle mesh's "auto" goes (the run's
// log, summary.json `numerics`, the daemon's job record and `dlmfd show`); the scene as run
// (scene.toml) names the velocity chosen. particle_mesh.kind is resolved before (rule 2 reads it).
#pragma once

#include "dlmfd/core/params.h"

namespace dlmfd {

// The velocity "auto" stands for in this scene, with the rule that chose it (key
// "conformation.velocity", value the velocity's scene word).
ResolvedChoice ResolveConformationVelocity(const Params& params);

}  // namespace dlmfd
