// The names of the domain's four sides in core/params.h's Side order, as the scene keys spell
// them (domain.boundary.left, ...) and as messages name them.
#pragma once

namespace dlmfd {

// The name of side s (0 to 3: left, right, bottom, top).
inline const char* SideName(int s) {
  static const char* const kNames[4] = {"left", "right", "bottom", "top"};
  return kNames[s];
}

}  // namespace dlmfd
