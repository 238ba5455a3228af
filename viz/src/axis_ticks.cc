// LinearTicks, LogTicks: nice numbers on an axis range.
#include "dlmfd/viz/axis_ticks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

// Relative slack when deciding whether a computed tick lies inside the range.
constexpr double kRoundOff = 1e-9;

std::string Printf(const char* format, int digits, double value) {
  char text[48];
  std::snprintf(text, sizeof(text), format, digits, value);
  return text;
}

// A label for a multiple of `step` on an axis reaching `magnitude`: fixed decimals as the step
// needs, or scientific notation when the axis values are all very large or very small.
std::string LinearLabel(double value, double step, double magnitude) {
  const int step_exponent = int(std::floor(std::log10(step) + kRoundOff));
  if (magnitude >= 1e6 || magnitude < 1e-3) {
    if (std::abs(value) < kRoundOff * step) return "0";
    const int exponent = int(std::floor(std::log10(magnitude)));
    return Printf("%.*e", std::max(0, exponent - step_exponent), value);
  }
  return Printf("%.*f", std::max(0, -step_exponent), value);
}

// Ticks m * 10^k of a log axis (m in 1, 2, 5), labelled in one notation for the whole axis: plain
// digits when every k is moderate (0.001 to 50000), else "me" k for every tick, so that an axis
// never reads "10000, 1e5".
AxisTicks LogLabelled(const std::vector<std::pair<int, int>>& marks) {
  bool plain = true;
  for (const auto& [m, k] : marks) plain = plain && k >= -3 && k <= 4;
  AxisTicks ticks;
  for (const auto& [m, k] : marks) {
    ticks.values.push_back(m * std::pow(10.0, k));
    ticks.labels.push_back(plain ? Printf("%.*f", std::max(0, -k), ticks.values.back())
                                 : std::to_string(m) + "e" + std::to_string(k));
  }
  return ticks;
}

}  // namespace

bool Usable(double value, AxisScale scale) {
  return std::isfinite(value) && (scale == AxisScale::kLinear || value > 0.0);
}

AxisTicks LinearTicks(double lo, double hi, int wanted) {
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo < hi)) {
    throw InvalidParameter("axis range", "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]",
                           "finite ends with lo < hi");
  }
  wanted = std::max(2, wanted);
  const double raw = (hi - lo) / wanted;
  const double base = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * base;
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * base >= raw * (1.0 - kRoundOff)) {
      step = m * base;
      break;
    }
  }
  AxisTicks ticks;
  const double magnitude = std::max(std::abs(lo), std::abs(hi));
  for (double k = std::ceil(lo / step - kRoundOff); k <= std::floor(hi / step + kRoundOff);
       k += 1.0) {
    const double value = std::abs(k) < 0.5 ? 0.0 : k * step;
    ticks.values.push_back(value);
    ticks.labels.push_back(LinearLabel(value, step, magnitude));
  }
  return ticks;
}

AxisTicks LogTicks(double lo, double hi, int wanted) {
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo > 0.0 && lo < hi)) {
    throw InvalidParameter("log axis range",
                           "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]",
                           "finite ends with 0 < lo < hi");
  }
  wanted = std::max(2, wanted);
  const int k_lo = int(std::ceil(std::log10(lo) - kRoundOff));
  const int k_hi = int(std::floor(std::log10(hi) + kRoundOff));
  const int decades = k_hi - k_lo + 1;
  if (decades < 3) {
    std::vector<std::pair<int, int>> multiples;
    for (int k = k_lo - 2; k <= k_hi + 1; ++k) {
      for (const int m : {1, 2, 5}) {
        const double value = m * std::pow(10.0, k);
        if (value >= lo * (1.0 - kRoundOff) && value <= hi * (1.0 + kRoundOff)) {
          multiples.emplace_back(m, k);
        }
      }
    }
    const std::size_t count = multiples.size();
    // Two marks over less than two decades read poorly: linear ticks give three or more.
    const bool enough = count >= 3 || (count == 2 && decades >= 2);
    if (enough && (count <= std::size_t(wanted) + 1 || decades < 2)) return LogLabelled(multiples);
  }
  if (decades >= 2) {
    const int every = std::max(1, (k_hi - k_lo + wanted - 1) / wanted);
    // Decades that are multiples of `every` when that leaves two or more, else from k_lo.
    int first = int(std::ceil(double(k_lo) / every)) * every;
    if (first + every > k_hi) first = k_lo;
    std::vector<std::pair<int, int>> marks;
    for (int k = first; k <= k_hi; k += every) marks.emplace_back(1, k);
    return LogLabelled(marks);
  }
  return LinearTicks(lo, hi, wanted);
}

AxisTicks ScaleTicks(double lo, double hi, int wanted, AxisScale scale) {
  return scale == AxisScale::kLog10 ? LogTicks(lo, hi, wanted) : LinearTicks(lo, hi, wanted);
}

}  // namespace dlmfd
