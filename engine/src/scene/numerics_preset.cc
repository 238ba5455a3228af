// The presets' names (scene/numerics_preset.h); their key = word table is in scene_keys.cc.
#include "dlmfd/scene/numerics_preset.h"

#include "dlmfd/core/param_words.h"

namespace dlmfd {

const char* NumericsPresetName(NumericsPreset preset) { return WordOf(preset); }

}  // namespace dlmfd
