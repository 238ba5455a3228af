// particles.h5 of the results directory (design.md 3.2): the particle states at the particle
// cadence.
//
// Datasets, nt records of np particles: /time (nt), /step (nt), /position (nt, np, 2), /velocity
// (nt, np, 2), /angular_velocity (nt, np), /force (nt, np, 2), /torque (nt, np); fixed per run: /id
// (np), /radius (np). Format version 2 (results_format.h) adds /angle (nt, np), the rotation since
// t = 0 (results_writer.h integrates it), the root attributes format, format_version and units,
// /scene (the scene as run) and on every dataset its units, description and dimensions ("record
// particle component"). Extendible chunked datasets (64 records a chunk); the file is flushed after
// each record so a reader (opening without HDF5's file lock) sees whole records. The writer holds
// one record's buffers, allocated once. On resume the file is reopened and cut back to the records
// at or before the checkpoint step.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dlmfd/core/state.h"

namespace dlmfd {

class ParticleHistoryWriter {
 public:
  // Creates (truncates) `path` for the particles of `state`, the scene text in /scene.
  static std::unique_ptr<ParticleHistoryWriter> Create(const std::string& path,
                                                       const FlowState& state,
                                                       const std::string& scene_text = "");
  // Reopens an existing file and drops the records with step > last_step. A file of version 1 (no
  // /angle) goes on without angles.
  static std::unique_ptr<ParticleHistoryWriter> Resume(const std::string& path, long last_step);
  ~ParticleHistoryWriter();
  ParticleHistoryWriter(const ParticleHistoryWriter&) = delete;
  ParticleHistoryWriter& operator=(const ParticleHistoryWriter&) = delete;

  // One record; `angles` (np values) go into /angle when the file has it.
  void Append(const FlowState& state, const std::vector<double>& angles = {});
  std::size_t records() const { return records_; }
  bool has_angle() const;

 private:
  struct Impl;
  explicit ParticleHistoryWriter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  std::size_t records_ = 0;
};

struct ParticleHistory {
  std::int64_t format_version = 1;
  std::size_t records = 0;    // nt
  std::size_t particles = 0;  // np
  std::vector<double> time;
  std::vector<std::int64_t> step;
  std::vector<std::int64_t> id;
  std::vector<double> radius;
  std::vector<std::int64_t> shape;  // per particle: 0 disk, 1 ellipse; empty in older files
  std::vector<double> semi_axes;    // np * 2: (a, b), (R, R) for a disk; empty in older files
  std::vector<double> position, velocity, force;  // nt * np * 2, row-major
  std::vector<double> angular_velocity, torque;   // nt * np
  std::vector<double> angle;                      // nt * np; empty in version 1
  std::string scene_text;                         // "" in version 1
};

ParticleHistory ReadParticleHistory(const std::string& path);

}  // namespace dlmfd
