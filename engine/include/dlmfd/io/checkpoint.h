// checkpoint.h5: the whole FlowState, bit for bit, to resume a run (design.md 3.2, issue 5 point
// 3).
//
// Root attributes step, time, scene (the scene text as WriteScene gives it, to check on resume that
// the same scene goes on). Datasets /u, /v, /p and, for a non-Newtonian run, /a11, /a12, /a22
// (flat, as in FlowState), with fluid.stress_splitting = devss also /d11, /d12, /d22; per particle,
// in /particles: id, position (np, 2), velocity (np, 2), angular_velocity, force (np, 2), torque,
// radius, density, motion (0 free, 1 fixed, 2 prescribed), and the multiplier vectors concatenated
// in multiplier with multiplier_offset (np + 1), and (since results format 2) each particle's
// rotation angle, /particles/angle, which the results writer integrates (results_writer.h). Doubles
// are stored as native doubles: what is read back equals what was written. With particle_mesh.kind
// = "cut_cell", the group /cut_cell_start holds what the cut-cell step keeps of earlier steps
// (core/state.h's CutCellStart): previous_pressure (a moving body), and around fixed bodies the
// Uzawa start's pressure corrections q, sq (count, pressure unknowns) and wq (count, velocity
// unknowns) with their attribute corrections_dt; a checkpoint without it resumes from p alone
// (the same run to the solver's tolerance, not bit for bit). Written to a temporary
// name and renamed, so a crash while writing leaves the previous checkpoint intact.
#pragma once

#include <string>
#include <vector>

#include "dlmfd/core/state.h"

namespace dlmfd {

void WriteCheckpoint(const std::string& path, const FlowState& state, const std::string& scene_text,
                     const std::vector<double>& particle_angles = {});

struct Checkpoint {
  FlowState state;
  std::string scene_text;
  std::vector<double> particle_angles;  // empty for a checkpoint without them
};

// Throws dlmfd::Error when the file is missing or malformed.
Checkpoint ReadCheckpoint(const std::string& path);

}  // namespace dlmfd
