#include "scene_admission.h"

#include <cmath>

#include "dlmfd/core/errors.h"
#include "dlmfd/scene/scene_file.h"
#include "service_error.h"

namespace dlmfd::server {

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
  Params params = ParseScene(scene, parsed, "scene");
  const double nx = std::round(params.domain.size.x() / params.domain.h);
  const double ny = std::round(params.domain.size.y() / params.domain.h);
  const double nodes = (nx + 1) * (ny + 1);
  SceneEstimate estimate;
  estimate.end_time = params.time.end;
  if (!(nodes <= static_cast<double>(config.max_grid_nodes))) {
    throw ServiceError(StatusCode::RESOURCE_EXHAUSTED,
                       "domain.h: the grid has " + std::to_string(static_cast<int64_t>(nodes)) +
                           " velocity nodes, over the limit of " +
                           std::to_string(config.max_grid_nodes));
  }
  estimate.nodes = static_cast<int64_t>(nodes);
  double particle_nodes = 0;
  for (const auto& particle : params.particles) {
    const double r = particle.Radius() / params.particle_mesh.h;
    particle_nodes += 4.0 * r * r + 8.0 * r + 1.0;
  }
  const double bytes = kBytesPerNode * (nodes + particle_nodes);
  estimate.memory_mb = static_cast<int64_t>(std::ceil(bytes / (1024.0 * 1024.0)));
  if (estimate.memory_mb > config.max_memory_mb) {
    throw ServiceError(StatusCode::RESOURCE_EXHAUSTED,
                       "domain.h: the run needs an estimated " +
                           std::to_string(estimate.memory_mb) + " MiB, over the limit of " +
                           std::to_string(config.max_memory_mb) + " MiB");
  }
  return estimate;
}

}  // namespace dlmfd::server
