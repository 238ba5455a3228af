// Colours for pictures of scalar fields: a sequential map for quantities that only grow from a
// floor (trA, the speed, A11, A22) and a diverging map for signed ones (the vorticity, A12, the
// pressure), whose sign is the physics (sense of rotation, sign of the shear stretch).
//
// Viridis (sequential) is perceptually uniform (equal steps in value look like equal steps in
// colour) and stays readable in grey scale and for the common colour-vision deficiencies, so a
// picture of trA shows the stretched regions without the false edges of a rainbow map.
//
// Cool to warm (diverging), Moreland's map: blue (0.230, 0.299, 0.754) at t = 0 through a neutral
// grey at t = 1/2 to red (0.706, 0.016, 0.150) at t = 1 (sRGB), interpolated in his Msh space, the
// polar form of CIELAB: M = sqrt(L^2 + a^2 + b^2), s = acos(L / M), h = atan2(b, a). Each half
// runs linearly in (M, s, h) from an end to the unsaturated middle (M_mid, 0, 0) with
// M_mid = max(M_1, M_2, 88), so lightness rises evenly to the middle and falls evenly beyond, and
// the hue of the unsaturated end is the saturated end's turned by
//   h_spin = s sqrt(M_mid^2 - M^2) / (M sin s)   (towards +h unless h <= -pi/3)
// (his AdjustHue), which keeps the middle free of a hue jump. sRGB <-> CIE XYZ with the sRGB
// primaries and the D65 white (0.95047, 1, 1.08883), XYZ <-> CIELAB with the CIE f(t) = t^(1/3)
// above (6/29)^3 and its linear toe below. The middle, t = 1/2, is the grey (221, 221, 221): the
// colour of zero on a diverging scale (colour_scale.h). The 257 entries reproduce the 33-entry
// table of the reference to within 1 in 255 (rounding), tests/unit/render_test.cc.
//
// NaN or Inf: kNanColour, a darker grey (160) that neither map produces.
// Not supported: other colour maps.
// References: S. van der Walt, N. Smith, "mpl-colormaps" (2015), https://bids.github.io/colormap/;
// K. Moreland, "Diverging Color Maps for Scientific Visualization", Advances in Visual Computing
// (ISVC 2009), LNCS 5876, pp. 92-103, doi:10.1007/978-3-642-10520-3_9, and its expanded version
// with the table, https://www.kennethmoreland.com/color-maps/.
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
// Axes, ticks, their labels and the titles, in field pictures and in charts alike.
inline constexpr Rgb kAxisColour = kBlack;
// Pixels whose field value is NaN or Inf: a neutral grey that neither colour map produces.
inline constexpr Rgb kNanColour{160, 160, 160};

// Viridis at t in [0, 1] (clamped), nearest of 256 entries; NaN gives kNanColour.
Rgb Viridis(double t);
// Moreland's cool to warm at t in [0, 1] (clamped), nearest of 257 entries (t = 1/2 is the
// middle one, the neutral grey); NaN gives kNanColour.
Rgb CoolWarm(double t);

}  // namespace dlmfd
