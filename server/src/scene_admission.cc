#include "scene_admission.h"

#include "dlmfd/core/errors.h"
#include "dlmfd/core/time_stepping.h"
#include "dlmfd/scene/scene_file.h"
#include "dlmfd/scene/scene_footprint.h"
#include "scene_values.h"
#include "service_error.h"

namespace dlmfd::server {
namespace {

// The daemon's limits on one run: its steps and its field snapshots (config max_steps,
// max_snapshots; 0: none). Counted in double, as ValidateScene holds them below 2^53.
void CheckRunLimits(const Params& params, const Config& config) {
  using grpc::StatusCode;
  const double steps = static_cast<double>(StepCount(params.time));
  if (config.max_steps > 0 && steps > static_cast<double>(config.max_steps)) {
    throw ServiceError(StatusCode::RESOURCE_EXHAUSTED,
                       "time.end: the run makes " + std::to_string(static_cast<int64_t>(steps)) +
                           " steps (time.end / time.dt), over the limit of max_steps = " +
                           std::to_string(config.max_steps));
  }
  const auto snapshots =
      static_cast<double>(SnapshotCount(params.time, params.output.fields_every));
  if (config.max_snapshots > 0 && snapshots > static_cast<double>(config.max_snapshots)) {
    throw ServiceError(StatusCode::RESOURCE_EXHAUSTED,
                       "output.fields_every: the run writes " +
                           std::to_string(static_cast<int64_t>(snapshots)) +
                           " field snapshots, over the limit of max_snapshots = " +
                           std::to_string(config.max_snapshots));
  }
}

}  // namespace

SceneEstimate AdmitScene(const std::string& scene, const std::vector<std::string>& overrides,
                         const Config& config) {
  using grpc::StatusCode;
  if (static_cast<int64_t>(scene.size()) > config.max_scene_bytes) {
    throw ServiceError(StatusCode::RESOURCE_EXHAUSTED, "scene has " + std::to_string(scene.size()) +
                                                           " bytes, over the limit of " +
                                                           std::to_string(config.max_scene_bytes));
  }
  if (scene.empty()) throw ServiceError(StatusCode::INVALID_ARGUMENT, "scene: empty scene text");
  std::vector<SceneOverride> parsed;
  for (const auto& text : overrides) {
    if (text.find('\n') != std::string::npos) {
      throw ServiceError(StatusCode::INVALID_ARGUMENT,
                         "overrides: \"" + text + "\" contains a line break");
    }
    parsed.push_back(ParseOverride(text));  // InvalidParameter -> INVALID_ARGUMENT
  }
  const Params params = ParseScene(scene, parsed, "scene");
  const SceneFootprint footprint = EstimateFootprint(params);
  // Compared in double: the estimate is finite but may be far beyond any integer type. Counts are
  // printed as integers, which they fit once ParseScene has held them to the engine's limits.
  if (!(footprint.velocity_nodes <= static_cast<double>(config.max_grid_nodes))) {
    throw ServiceError(
        StatusCode::RESOURCE_EXHAUSTED,
        "domain.h: the grid has " + std::to_string(static_cast<int64_t>(footprint.velocity_nodes)) +
            " velocity nodes, over the limit of " + std::to_string(config.max_grid_nodes));
  }
  const double mib = footprint.bytes / (1024.0 * 1024.0);
  if (!(mib <= static_cast<double>(config.max_memory_mb))) {
    // The largest share names the key: the moving cut bodies' responses (a node array a
    // capacitance row, scene/scene_footprint.h), the multiplier meshes, or the grid.
    const bool responses = sizeof(double) * footprint.cut_cell_rows > kCutCellBytesPerNode;
    const char* key = responses                                               ? "particle_mesh.kind"
                      : footprint.multiplier_nodes > footprint.velocity_nodes ? "particle_mesh.h"
                                                                              : "domain.h";
    const std::string why =
        responses ? " (moving cut-cell bodies hold a grid array per boundary row: " +
                        std::to_string(static_cast<int64_t>(footprint.cut_cell_rows)) +
                        " rows; \"collocation\" needs a fraction of it)"
                  : "";
    throw ServiceError(StatusCode::RESOURCE_EXHAUSTED,
                       std::string(key) + ": the run needs an estimated " +
                           std::to_string(static_cast<int64_t>(std::ceil(mib))) +
                           " MiB, over the limit of " + std::to_string(config.max_memory_mb) +
                           " MiB" + why);
  }
  CheckRunLimits(params, config);
  SceneEstimate estimate;
  estimate.end_time = params.time.end;
  estimate.nodes = static_cast<int64_t>(footprint.velocity_nodes);
  estimate.memory_mb = static_cast<int64_t>(std::ceil(mib));
  estimate.warnings = AccuracyWarnings(params);
  estimate.numerics = params.numerics.resolved;
  estimate.scene_values = FlattenParams(params);
  return estimate;
}

}  // namespace dlmfd::server
