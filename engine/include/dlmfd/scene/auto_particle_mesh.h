// particle_mesh.kind = "auto", the default since issue 32 / 33: cut cells (particles/
// cut_cell_step.h) where every particle is a fixed disk (or a fixed ellipse in a Newtonian
// liquid), the liquid Newtonian or a polymer they were measured with, and the run long enough for
// their set-up to pay, collocation points otherwise (docs/evidence/cut_cell_boundary.md, "Should
// `auto` choose cut cells for fixed bodies?" and "The polymer around fixed bodies";
// docs/accuracy.md).
//
// Why: on the same grid a cut-cell step costs 2-7 times the collocation points' one, but its drag
// is second order and does not depend on where the body sits in the grid (Schaefer-Turek C_D
// within 0.030 % at D/h = 20 at eight sub-grid shifts against the collocation points' 1.26 %; the
// square array within 0.44 % at h = 1/64 against 2.27 %), and the collocation points need a grid
// twice as fine or more to come near that, where their step costs as much or more.
//
// The rules are tried in order and the first that applies decides; each is one function in
// scene/auto_particle_mesh.cc with its evidence beside it, and one test pins it
// (tests/unit/auto_particle_mesh_test.cc). The last rule always applies.
//   1. No particles: "collocation" (nothing to hold; the kind is not used).
//   2. A particle that is not a disk, unless fixed in a Newtonian liquid: "collocation" (the cut
//      cells' forces were measured on fixed ellipses in a Newtonian liquid; a moving ellipse turns
//      at Jeffery's rate to the box's slowing at every sub-grid position, but at 10 times the
//      collocation points' CPU a step; one in a polymer was not measured).
//   3. A particle that is not fixed: "collocation" (cut cells recut every step, 5.5 times a fixed
//      body's step, and a free body adds three Stokes solves a step).
//   4. A polymer model other than Oldroyd-B and Giesekus: "collocation" (cut cells carry any
//      model around fixed bodies, but FENE-P and PTT were not measured with them).
//   5. A scene that cut cells refuse otherwise (CutCellObstacle, particles/particle_rules.h:
//      splitting.beta != 0, domain.flow_rate): "collocation", naming the key.
//   6. A run of fewer than kMinCutCellSteps steps: "collocation" (the set-up would not pay).
//   7. Otherwise: "cut_cell".
// The choice, the rule and the numbers it read go where the coupling's "auto" goes (the run's log,
// summary.json `numerics`, the daemon's job record and `dlmfd show`); the scene as run (scene.toml)
// names the kind chosen, so a resume or a rerun uses the same one. Its numbers: the run's steps
// and kMinCutCellSteps. splitting.constraint is resolved before (its weights decide rule 5).
#pragma once

#include "dlmfd/core/params.h"

namespace dlmfd {

// Steps from which the cut cells' set-up pays (rule 6). The set-up (the cut band's forms and the
// capacitance matrix) costs as much as 56-101 cut-cell steps at the start of a run on every case
// measured (Schaefer-Turek D/h = 20: 1.9-2.1 CPU s against 29-35 ms a step over the first 200-300
// steps from rest; the square array at h = 1/64: 0.21 s against 2.1 ms, at 1/128: 0.78 s against
// 9.3 ms), so from 100 steps on it is at most half the run's cost, and the square array's cut cells
// at h = 1/64 cost less than the collocation points at 1/128, which are still less accurate, from
// 75 steps on. A shorter run is a start or a test. docs/evidence/cut_cell_boundary.md, "`auto`
// picks cut cells for fixed disks: the rule and the defaults remeasured".
inline constexpr long kMinCutCellSteps = 100;

// The particle mesh "auto" stands for in this scene, with the rule that chose it and the numbers
// it read (key "particle_mesh.kind", value the kind's scene word).
ResolvedChoice ResolveParticleMeshKind(const Params& params);

}  // namespace dlmfd
