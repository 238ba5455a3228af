// A scene of cases/ as the tests run it: read with the test's overrides, then without output
// (fields, particles and checkpoints every 0: observers see every step all the same) on one thread,
// so that a test's numbers do not depend on the machine's cores.
#pragma once

#include <string>
#include <vector>

#include "dlmfd/core/params.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd::testing {

// `path` relative to the source tree (e.g. "cases/periodic/settling_square_array.toml").
inline Params QuietCase(const std::string& path, std::vector<SceneOverride> overrides) {
  overrides.push_back({"output.fields_every", "0"});
  overrides.push_back({"output.particles_every", "0"});
  overrides.push_back({"output.checkpoint_every", "0"});
  Params params = LoadSceneFile(std::string(DLMFD_SOURCE_DIR) + "/" + path, overrides);
  params.threads = 1;
  return params;
}

}  // namespace dlmfd::testing
