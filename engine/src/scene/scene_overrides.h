// `--set key=value` overrides (design.md 3.1) applied to a parsed TOML tree before validation.
//
// The dotted key walks tables by name and arrays by index from 0 (`particles.1.density`); missing
// tables on the way are created; an array index must exist. The value text is read as a TOML value
// (`2`, `1.5`, `[1.0, 0.0]`, `"wave"`, `{ type = "outflow" }`); text that is not a TOML value is
// taken as a string (`wave`). Setting `domain.boundary.SIDE.type` replaces that whole side, so that
// the keys of its former type do not linger (set its other keys after it). A `*` in place of an
// index stands for every index of that array (`particles.*.density=1.02` sets every particle); the
// array must exist and not be empty.
#pragma once

#include <vector>

#include <toml++/toml.h>

#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace scene {

// Throws InvalidParameter naming the override's key when its path cannot be followed.
void ApplyOverrides(toml::table& root, const std::vector<SceneOverride>& overrides);

}  // namespace scene
}  // namespace dlmfd
