// The colour of a field value in a picture: a colour range [lo, hi] read through a colour map
// (colour_map.h), as the field panel and its colour bar both draw it.
//
// Sequential (viridis): t = (v - lo) / (hi - lo), or with log10 of v, lo and hi on a log scale (a
// value <= 0 takes the bottom colour); values outside [lo, hi] take the end colours.
// Diverging (cool to warm, for signed quantities): one scale symmetric about zero,
//   t = 1/2 + v / (2 m),   m = max(|lo|, |hi|),   v clamped into [lo, hi],
// so zero is the neutral middle grey whenever it lies in [lo, hi], equal steps in value are equal
// steps in colour on both sides, and the sign of a value is always its hue (blue < 0 < red). The
// automatic range of a signed field is [-m, m] with m its largest finite |value| (field_picture.h),
// and the bar then runs from the blue end to the red end. A range the user fixes is kept as given:
// a lopsided one (say [-1, 3]) shows zero at the neutral grey with less of the blue half, and one
// that excludes zero (say [0.5, 2]) shows only the part of one half that it covers.
// Degenerate ranges: lo = hi (a constant field) takes the middle colour (no division by zero);
// NaN or Inf values take kNanColour. The diverging map has no log scale: `log` with `diverging`
// is an error of the caller (ColourScale's constructor throws).
#pragma once

#include "dlmfd/viz/colour_map.h"

namespace dlmfd {

class ColourScale {
 public:
  // Throws InvalidParameter for lo > hi, non-finite bounds, log with lo <= 0, or log with
  // diverging.
  ColourScale(double lo, double hi, bool log, bool diverging);
  // The colour of a field value.
  Rgb Of(double value) const;
  // The colour at fraction f in [0, 1] of the bar from lo (0) to hi (1), in the scale's own
  // coordinate (log10 of the value on a log scale).
  Rgb AtFraction(double f) const;

 private:
  double lo_;
  double hi_;
  bool log_;
  bool diverging_;
};

}  // namespace dlmfd
