// Scene values: the effective scene of a job as (dotted key, value) pairs, and the typed value of
// a study axis.
//
// A job's effective scene is what the solver runs: the scene file with the overrides applied and
// every default filled in (the Params that ParseScene returned at admission, flattened from the
// table of scene keys, dlmfd/scene/scene_keys.h: the keys and values WriteScene writes).
// Flattened, every scalar and every array has its dotted key (`fluid.viscosity`,
// `particles.0.center`, `particles.0.center.1`, `domain.boundary.left.type`), so `list --where
// KEY=VALUE` finds a value whether the scene file or an override set it. Values are normalised so
// that equal values compare equal as text: numbers (integer or float) as the shortest text that
// reads back as the same double ("1" for 1 and 1.0), booleans as true/false, strings as their
// characters, arrays as "[a, b]" of normalised elements. A text that is not a TOML value is a
// string, as in overrides (`splitting.advection=wave`).
//
// A `where` filter of List is KEY OP VALUE, OP one of = != < <= > >= (the first '=', '!', '<' or
// '>' ends the key): = and != compare normalised values, the ranges compare numbers, and only a
// value that reads as a number meets a range (`fluid.viscosity>=0.01`, `particles.*.density<1.1`).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "dlmfd/core/params.h"
#include "job_store.h"

namespace dlmfd::server {

// The flattened effective scene of validated Params (the keys WriteScene writes).
std::vector<std::pair<std::string, std::string>> FlattenParams(const Params& params);
// The flattened effective scene of a scene-as-run text; throws StoreError on unreadable TOML.
std::vector<std::pair<std::string, std::string>> FlattenScene(const std::string& scene_as_run);
// The normalised form of a TOML value text (an override's or a `where` filter's value).
std::string NormalizedValue(const std::string& value_text);
// An axis value with its type: integer, float, boolean, string or array (a number for the first
// two).
ParameterValue TypedValue(const std::string& key, const std::string& value_text);
// A `where` filter's text as a filter; throws ServiceError INVALID_ARGUMENT naming `where` for a
// text without a key or an operator, or a range whose value is not a number.
SceneValueFilter ParseWhere(const std::string& text);

}  // namespace dlmfd::server
