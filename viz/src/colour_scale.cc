// A field value to its colour: sequential (linear or log10) on viridis, or diverging about zero on
// cool to warm (colour_scale.h).
#include "dlmfd/viz/colour_scale.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", value);
  return text;
}

}  // namespace

ColourScale::ColourScale(double lo, double hi, bool log, bool diverging)
    : lo_(lo),
      hi_(hi),
      log_(log),
      diverging_(diverging) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo <= hi) || (log && !(lo > 0.0))) {
    throw InvalidParameter("colour range", Number(lo) + "," + Number(hi),
                           log ? "finite 0 < min <= max for log colours" : "finite min <= max");
  }
  if (log && diverging) {
    throw InvalidParameter("colour scale", "log and diverging",
                           "a log scale on viridis, or a linear diverging scale");
  }
}

Rgb ColourScale::Of(double v) const {
  if (!std::isfinite(v)) return kNanColour;
  if (diverging_) {
    const double m = std::max(std::abs(lo_), std::abs(hi_));
    return CoolWarm(m > 0.0 ? 0.5 + std::clamp(v, lo_, hi_) / (2.0 * m) : 0.5);
  }
  if (log_ && !(v > 0.0)) return Viridis(0.0);
  const double bottom = log_ ? std::log10(lo_) : lo_;
  const double span = (log_ ? std::log10(hi_) : hi_) - bottom;
  const double c = log_ ? std::log10(v) : v;
  return Viridis(span > 0.0 ? std::clamp((c - bottom) / span, 0.0, 1.0) : 0.5);
}

Rgb ColourScale::AtFraction(double f) const {
  if (std::isnan(f)) return kNanColour;
  if (diverging_) return Of(lo_ + std::clamp(f, 0.0, 1.0) * (hi_ - lo_));
  return Viridis(hi_ > lo_ ? f : 0.5);
}

}  // namespace dlmfd
