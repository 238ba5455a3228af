// numerics.preset: the configuration a scene's numerics keys default to (issue 32 point 2). A key
// the scene sets wins over its preset; the preset only moves the defaults.
//
//   "default" (the default): the configuration measured best on the verification suite
//     (docs/accuracy.md): the particle mesh chosen from the scene ("auto", scene/
//     auto_particle_mesh.h: cut cells for fixed disks over a long run (not yet with FENE-P or PTT),
//     collocation points on the true circle otherwise), the coupling of the constraint
//     chosen from the scene's numbers ("auto", scene/auto_coupling.h), DEVSS for a polymer and
//     the velocity its step (35) freezes chosen from the particle mesh ("auto",
//     scene/auto_conformation_velocity.h), the steady correction in a Newtonian liquid, both
//     diagonals of every square and the wave-like advection.
//   "paper": the choices of Singh, Joseph, Hesla, Glowinski and Pan (J. Non-Newtonian Fluid Mech.
//     91, 2000) at once: the H1 ring mesh of each disk (24), the SW-NE mesh, the least-squares
//     advection step (34), the constraint only in the DLM step (37) with alpha = beta = 1/2
//     (gamma = 0), the polymer stress explicit in (33) and step (35) with the advected velocity,
//     no steady correction, the DLM CG in the product G alone. The paper's case
//     files set it where they must reproduce the paper's numbers, and say so.
//
// The struct defaults of core/params.h are the "default" preset's for the coupling and the
// polymer stress, for the particle mesh what its "auto" picks but for fixed disks in a long run
// (collocation points; code that wants cut cells names them), and for the velocity of step (35)
// what its "auto" picks but around cut cells (advected); for the advection
// scheme and the diagonals they stay the paper's (least squares, SW-NE): the engine's tests and
// benches that build Params themselves studied those (a test holds this table to it). The presets'
// key = word pairs are declared with the keys they set (PresetWord, scene/scene_keys.h).
#pragma once

#include "dlmfd/core/params.h"

namespace dlmfd {

const char* NumericsPresetName(NumericsPreset preset);

}  // namespace dlmfd
