// Scene admission: what Submit checks before a job is queued.
//
// The scene text (with overrides) is parsed and validated by dlmfd::ParseScene, whose
// InvalidParameter names the dotted key; the grid size and an estimate of the solver's memory are
// checked against the configured limits. The memory estimate is deliberately coarse: kBytesPerNode
// bytes per velocity node (about 64 doubles: two velocity components and their split-step copies,
// the three conformation components and their copies, pressure, transform work arrays), which is an
// upper bound for the fields listed in method/fluid.md, plus the particle meshes.
// Not supported: estimating the wall time of a run.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "config.h"

namespace dlmfd::server {

struct SceneEstimate {
  int64_t nodes = 0;      // velocity nodes (nx + 1)(ny + 1)
  int64_t memory_mb = 0;  // estimated peak memory of dlmfd-solve
  double end_time = 0;
};

inline constexpr int64_t kBytesPerNode = 512;

// Throws ServiceError INVALID_ARGUMENT (scene or override invalid, the key first in the message) or
// RESOURCE_EXHAUSTED (size, nodes or memory over the limits).
SceneEstimate AdmitScene(const std::string& scene, const std::vector<std::string>& overrides,
                         const Config& config);

}  // namespace dlmfd::server
