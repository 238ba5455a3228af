// Scene files (design.md 3.1): TOML text -> one validated Params (parsed here, then checked by
// ValidateScene of scene/scene_validation.h). Every error is an InvalidParameter naming the dotted
// key, the offending value and what is allowed; unknown keys are errors (a typo must not be
// ignored). Overrides (`--set key=value`) are applied to the TOML tree
// before validation, with the same dotted keys (`particles.1.density=1.02`, indices from 0).
#pragma once

#include <string>
#include <vector>

#include "dlmfd/core/params.h"

namespace dlmfd {

struct SceneOverride {
  std::string key;    // dotted key
  std::string value;  // TOML value text ("2", "[1.0, 0.0]", "\"wave\""); a bare word is a string
};

// Splits "key=value"; throws InvalidParameter when there is no '=' or the key is empty.
SceneOverride ParseOverride(const std::string& key_equals_value);
// Parses and validates scene text. `origin` names the source in messages (a file name).
Params ParseScene(const std::string& toml_text, const std::vector<SceneOverride>& overrides = {},
                  const std::string& origin = "scene");
Params LoadSceneFile(const std::string& path, const std::vector<SceneOverride>& overrides = {});
// Gives every member the struct leaves absent its default, as a scene file that does not give the
// key gets it: splitting.steady_correction numerics.preset's word for the liquid,
// splitting.constraint what "auto" picks (recorded in numerics.resolved; with the struct's weights
// alpha and beta, those of the constraint picked), particle_mesh.h kPaperParticleMeshRatio domain.h
// (the keys with SceneKey::unset, scene/scene_keys.h). ParseScene and the Simulation call it, so
// Params built in code runs as the same scene read from a file does. Idempotent; a member already
// set is kept.
void ResolveDefaults(Params& params);
// The scene as TOML with every default filled in; ParseScene(WriteScene(p)) == p.
std::string WriteScene(const Params& params);

}  // namespace dlmfd
