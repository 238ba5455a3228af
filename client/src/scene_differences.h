// The parameters in which runs differ: the swept parameters of a study, read from each results
// directory's scene as run (scene.toml, every default filled in, design.md 3.2), so that a chart
// can label its series "fluid.relaxation_time = 1.4" rather than by directory or job id.
//
// Method: each scene is flattened to dotted keys as `dlmfd-solve --set` takes them
// (particles.1.density, domain.size), values in TOML's own text; a key is a difference when its
// value is not the same in every scene (absent counts as a value). The title is not a parameter.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace dlmfd::cli {

using FlatScene = std::map<std::string, std::string>;

// The dotted keys and values of results_dir/scene.toml; empty when there is none. Throws
// UsageError naming the file when it is not TOML.
FlatScene ReadFlatScene(const std::string& results_dir);
// The keys whose values differ between the scenes, in key order.
std::vector<std::string> DifferingKeys(const std::vector<FlatScene>& scenes);
// "v1, v2" of the keys in `scene` ("-" for an absent key).
std::string ValuesOf(const FlatScene& scene, const std::vector<std::string>& keys);

}  // namespace dlmfd::cli
