// Field snapshots of the results directory (design.md 3.2): fields/snap_NNNNNN.h5, NNNNNN the step.
//
// Datasets /u and /v (velocity), and for a non-Newtonian run /trA, /A11, /A12, /A22 (configuration
// tensor), all of shape (ny+1, nx+1) on the velocity mesh, x fastest; /p of shape (ny/2+1, nx/2+1)
// on the 2h pressure mesh; /velocity of shape (ny+1, nx+1, 3), (u, v, 0) per node, for ParaView
// (fields_xdmf.h). Root attributes: time, step, h, x0, y0 (the mesh origin).
// Format version 2 (results_format.h) adds: root attributes format, format_version, units; /scene
// (the scene as run); the node coordinates /x (nx+1), /y (ny+1), /x_pressure, /y_pressure; on every
// dataset the attributes units, description and dimensions ("y x"); and the group /particles with
// the particles at the snapshot's own step: id, radius (np), position, velocity (np, 2),
// angular_velocity, angle (np), force (np, 2), torque (np), so that a picture of the field draws
// the disks where they were at that time, whatever output.particles_every is. Written to a
// temporary name and renamed. Readers open without HDF5's file lock and read versions 1 and 2.
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

// What a snapshot holds besides the state: the scene as run and each particle's rotation angle
// (results_writer.h integrates it; empty: no /particles/angle).
struct SnapshotExtras {
  std::string scene_text;
  std::vector<double> particle_angles;
};

// Writes the snapshot of `state` (conformation datasets when state.a11 is not empty).
void WriteFieldSnapshot(const std::string& path, const Grid& grid, const FlowState& state,
                        const SnapshotExtras& extras = {});

struct FieldArray {
  std::vector<std::size_t> shape;  // (rows, columns) = (ny+1, nx+1); velocity: (ny+1, nx+1, 3)
  std::vector<double> values;      // row-major, x fastest
};

// The particles of a snapshot at its step (np entries each; angle empty when not written).
struct SnapshotParticles {
  std::vector<std::int64_t> id;
  std::vector<double> radius;
  std::vector<double> position, velocity, force;  // np * 2
  std::vector<double> angular_velocity, torque;   // np
  std::vector<double> angle;                      // np, or empty
  std::vector<double> semi_axes;  // np * 3: (a, b, 0), (R, R, 0) for a disk; empty before issue 37
  std::size_t Count() const { return id.size(); }
};

struct FieldSnapshot {
  std::int64_t format_version = 1;
  double time = 0.0;
  std::int64_t step = 0;
  double h = 0.0;
  double x0 = 0.0;
  double y0 = 0.0;
  std::map<std::string, FieldArray>
      fields;              // "u", "v", "velocity", "p", and "trA", "A11", "A12", "A22" when present
  std::string scene_text;  // "" in version 1
  bool has_particles = false;  // version 2: the /particles group (np may be 0)
  SnapshotParticles particles;
};

// Reads every dataset of a snapshot file; throws dlmfd::Error when the file cannot be read or is
// of a newer format version than this build reads (the message names both).
FieldSnapshot ReadFieldSnapshot(const std::string& path);

}  // namespace dlmfd
