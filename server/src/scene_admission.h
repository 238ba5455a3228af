// Scene admission: what Submit checks before a job is queued.
//
// The scene text (with overrides) is parsed and validated by dlmfd::ParseScene, the one validation
// of dlmfd-solve too (scene/scene_validation.h), whose InvalidParameter names the dotted key; then
// the scene's footprint (dlmfd::EstimateFootprint, scene/scene_footprint.h: velocity nodes and
// memory, computed in double) is held against the configured limits. The scene's accuracy warnings
// (dlmfd::AccuracyWarnings, scene/accuracy_envelope.h) are returned for the job record; with
// accuracy.strict = true ParseScene has already rejected a scene that has any.
// Not supported: estimating the wall time of a run.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "config.h"
#include "dlmfd/scene/accuracy_envelope.h"

namespace dlmfd::server {

struct SceneEstimate {
  int64_t nodes = 0;      // velocity nodes (nx + 1)(ny + 1)
  int64_t memory_mb = 0;  // estimated peak memory of dlmfd-solve
  double end_time = 0;
  std::vector<AccuracyWarning> warnings;  // settings outside the accuracy envelope
  std::vector<ResolvedChoice> numerics;   // what each "auto" became (scene/auto_coupling.h)
  // The effective scene (WriteScene of the validated Params), flattened (scene_values.h).
  std::vector<std::pair<std::string, std::string>> scene_values;
};

// Throws ServiceError INVALID_ARGUMENT (scene or override invalid, the key first in the message) or
// RESOURCE_EXHAUSTED (size, nodes or memory over the limits).
SceneEstimate AdmitScene(const std::string& scene, const std::vector<std::string>& overrides,
                         const Config& config);

}  // namespace dlmfd::server
