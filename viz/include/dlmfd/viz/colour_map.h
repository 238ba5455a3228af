// Colours for pictures of scalar fields.
//
// Viridis is perceptually uniform (equal steps in value look like equal steps in colour) and stays
// readable in grey scale and for the common colour-vision deficiencies, so a picture of trA shows
// the stretched regions without the false edges of a rainbow map.
// Not supported: other colour maps, logarithmic scales.
// Reference: S. van der Walt, N. Smith, "mpl-colormaps" (2015), https://bids.github.io/colormap/.
#pragma once

#include <cstdint>

namespace dlmfd {

struct Rgb {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  bool operator==(const Rgb& o) const { return r == o.r && g == o.g && b == o.b; }
  bool operator!=(const Rgb& o) const { return !(*this == o); }
};

inline constexpr Rgb kBlack{0, 0, 0};
inline constexpr Rgb kWhite{255, 255, 255};
// Pixels whose field value is NaN or Inf: a neutral grey that viridis never produces.
inline constexpr Rgb kNanColour{160, 160, 160};

// Viridis at t in [0, 1] (clamped), nearest of 256 entries; NaN gives kNanColour.
Rgb Viridis(double t);

}  // namespace dlmfd
