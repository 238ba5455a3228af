// Field snapshots of the results directory (design.md 3.2): fields/snap_NNNNNN.h5, NNNNNN the step.
//
// Datasets /u and /v (velocity), and for a non-Newtonian run /trA, /A11, /A12, /A22 (configuration
// tensor), all of shape (ny+1, nx+1) on the velocity mesh, x fastest; /p of shape (ny/2+1, nx/2+1)
// on the 2h pressure mesh; /velocity of shape (ny+1, nx+1, 3), (u, v, 0) per node, for ParaView
// (fields_xdmf.h). Root attributes: time, step, h, x0, y0 (the mesh origin). Written to a
// temporary name and renamed. Readers open without HDF5's file lock.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/state.h"

namespace dlmfd {

// "snap_000123.h5" for step 123 (more digits when the step needs them).
std::string SnapshotFileName(long step);
// Steps of the snapshots in results_dir/fields, ascending (none when the folder is missing).
std::vector<long> SnapshotSteps(const std::string& results_dir);

// Writes the snapshot of `state` (conformation datasets when state.a11 is not empty).
void WriteFieldSnapshot(const std::string& path, const Grid& grid, const FlowState& state);

struct FieldArray {
  std::vector<std::size_t> shape;  // (rows, columns) = (ny+1, nx+1); velocity: (ny+1, nx+1, 3)
  std::vector<double> values;      // row-major, x fastest
};

struct FieldSnapshot {
  double time = 0.0;
  std::int64_t step = 0;
  double h = 0.0;
  double x0 = 0.0;
  double y0 = 0.0;
  std::map<std::string, FieldArray>
      fields;  // "u", "v", "velocity", "p", and "trA", "A11", "A12", "A22" when present
};

// Reads every dataset of a snapshot file; throws dlmfd::Error when the file cannot be read.
FieldSnapshot ReadFieldSnapshot(const std::string& path);

}  // namespace dlmfd
