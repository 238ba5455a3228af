// A frame of a results directory (design.md 3.2): the field snapshot picked, the node field taken
// from it and the particles as they were at that step, ready for DrawFieldPicture.
//
// The snapshot is fields/snap_NNNNNN.h5 of the requested step, or the latest one. The field is
// trA when the snapshot has it (an Oldroyd-B run), else the speed |u| = sqrt(u^2 + v^2) at the
// nodes. Particles come from particles.h5: the record of the snapshot's step, else the record
// nearest in time (the particle cadence need not include every field snapshot).
// Not supported: the pressure (it lives on the 2h mesh), tensor components other than trA.
#pragma once

#include <string>
#include <vector>

#include "dlmfd/viz/field_picture.h"

namespace dlmfd {

struct ResultsFrame {
  NodeField field;
  std::vector<DiskOutline> disks;
  double time = 0.0;
  long step = 0;
  std::string snapshot_path;
  double particles_time = 0.0;  // time of the particle record used (== time when they match)
};

// step < 0: the latest snapshot. quantity: "" (trA if present, else speed), "trA" or "speed".
// Throws InvalidParameter (bad quantity, no such snapshot: the message lists what exists) or
// dlmfd::Error (unreadable files).
ResultsFrame LoadResultsFrame(const std::string& results_dir, long step = -1,
                              const std::string& quantity = "");
// |u| at each node.
std::vector<double> NodeSpeed(const std::vector<double>& u, const std::vector<double>& v);

}  // namespace dlmfd
