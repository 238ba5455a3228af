// A frame of a results directory (design.md 3.2): the field snapshot picked, the node field of a
// quantity taken from it (node_quantities.h), the velocity for arrows, and the particles as they
// were at that step, ready for DrawFieldPicture.
//
// The snapshot is fields/snap_NNNNNN.h5 of the requested step, or the latest one. The default
// quantity is trA when the snapshot has it (an Oldroyd-B run), else the speed. The particles are
// those the snapshot holds at its own step (results format 2, field_snapshot.h), with their angle.
// A snapshot written before that (format 1) has none: they come from particles.h5, the record of
// the snapshot's step, else linearly interpolated in time between the two records around it (the
// particle cadence need not include every field snapshot), else the nearest record; every case
// but the first says so in particles_note. An angle not stored is the integral of the recorded
// angular velocity from the first record (trapezoidal rule over the records; its error is
// O(dt_record^2) times the angular acceleration).
// The scene's title comes from scene.toml (line `title = "..."`) when the directory has one.
#pragma once

#include <string>
#include <vector>

#include "dlmfd/viz/field_picture.h"

namespace dlmfd {

struct ResultsFrame {
  NodeField field;
  NodeVelocity velocity;  // empty grids when the snapshot has no u, v
  bool has_velocity = false;
  std::vector<DiskOutline> disks;
  double time = 0.0;
  long step = 0;
  std::string snapshot_path;
  double particles_time = 0.0;  // time of the particle state drawn (== time when they match)
  // "" when the particles are at the snapshot's own step; else how they were found
  // ("interpolated between the records at t = 0.1 and 0.2"), for a warning.
  std::string particles_note;
};

// step < 0: the latest snapshot. quantity: "" (trA if present, else speed) or one of
// PictureQuantities(). Throws InvalidParameter (bad quantity, a quantity the snapshot does not
// hold: the message says which datasets it has, no such snapshot: the message lists what exists)
// or dlmfd::Error (unreadable files).
ResultsFrame LoadResultsFrame(const std::string& results_dir, long step = -1,
                              const std::string& quantity = "");
// The title of the scene as run (results_dir/scene.toml), "" when there is none.
std::string SceneTitle(const std::string& results_dir);

}  // namespace dlmfd
