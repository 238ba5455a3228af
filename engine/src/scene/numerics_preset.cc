// The presets' defaults (scene/numerics_preset.h).
#include "dlmfd/scene/numerics_preset.h"

namespace dlmfd {

NumericsDefaults DefaultsOf(NumericsPreset preset) {
  if (preset == NumericsPreset::kPaper) {
    return {"ring", "sw_ne", "least_squares", "paper", "explicit", "none", "none"};
  }
  return {"collocation", "both", "wave", "auto", "devss", "tendency", "none"};
}

const char* NumericsPresetName(NumericsPreset preset) {
  return preset == NumericsPreset::kPaper ? "paper" : "default";
}

}  // namespace dlmfd
