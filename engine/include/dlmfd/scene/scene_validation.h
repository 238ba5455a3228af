// The one validation of a scene (design.md 2: parse + validate once, the same for the solver and
// the daemon). ParseScene and LoadSceneFile end with ValidateScene, so dlmfd-solve and the daemon's
// admission reject the same scenes; a scene it admits is one the engine's constructors accept.
//
// The rules, in the order they are checked (the first broken one is reported):
// - each key as its table entry declares it (scene/scene_keys.h): its range (domain.h > 0,
//   fluid.solvent_ratio in (0, 1], ...), given where it is required (fluid.mobility with
//   fluid.model = "giesekus"), absent where it does not apply (docs/scenes.md);
// - the footprint (scene/scene_footprint.h) within the engine's limits: at most kMaxVelocityNodes
//   velocity nodes (domain.h) and kMaxMultiplierNodes multiplier nodes (particle_mesh.h);
// - the mesh: domain.size an even number >= 4 of cells of domain.h in both directions (the
//   pressure mesh is 2h and its fast solver needs 2 cells), periodic sides in pairs;
// - the rules each module owns, defined once beside the code that needs them: time stepping
//   (core/time_stepping.h: the splitting weights, step and output counts that fit), the particles
//   (particles/particle_rules.h: not lighter than the liquid, inside, apart, indexable grid), the
//   conformation (conformation/inflow_state.h: steady inflow states exist);
// - with accuracy.strict = true, every setting inside the accuracy envelope
//   (scene/accuracy_envelope.h); the first one outside names the key to change.
// Every failure is an InvalidParameter naming the dotted key, its value and what is allowed.
#pragma once

#include "dlmfd/core/params.h"

namespace dlmfd {

inline constexpr double kMaxVelocityNodes = 2e7;
inline constexpr double kMaxMultiplierNodes = 2e7;

void ValidateScene(const Params& params);

// The keys of time, splitting and output: their ranges (the key table, scene/scene_keys.h), then
// the rules between them (core/time_stepping.h). Part of ValidateScene; Simulation's constructor
// applies it as the time loop's guard.
void ValidateTimeStepping(const Params& params);

}  // namespace dlmfd
