// Moreland's cool to warm diverging map (colour_map.h), built once as 257 8-bit entries from his
// Msh interpolation.
#include <algorithm>
#include <array>
#include <cmath>

#include "dlmfd/core/constants.h"
#include "dlmfd/viz/colour_map.h"

namespace dlmfd {
namespace {

struct Msh {
  double m = 0.0;  // magnitude: sqrt(L^2 + a^2 + b^2)
  double s = 0.0;  // saturation: the angle from the L axis
  double h = 0.0;  // hue: the angle in the a-b plane
};

// The D65 white point in CIE XYZ (Y = 1).
constexpr double kWhiteX = 0.95047;
constexpr double kWhiteY = 1.0;
constexpr double kWhiteZ = 1.08883;
// Below this Y / Y_n (= (6/29)^3) CIELAB's f is linear.
constexpr double kLabToe = 0.008856;

double LinearOfSrgb(double c) {
  return c > 0.04045 ? std::pow((c + 0.055) / 1.055, 2.4) : c / 12.92;
}

double SrgbOfLinear(double c) {
  return c > 0.0031308 ? 1.055 * std::pow(c, 1.0 / 2.4) - 0.055 : 12.92 * c;
}

double LabF(double t) { return t > kLabToe ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; }

double LabFInverse(double f) {
  const double cube = f * f * f;
  return cube > kLabToe ? cube : (f - 16.0 / 116.0) / 7.787;
}

Msh MshOfSrgb(double r, double g, double b) {
  const double lr = LinearOfSrgb(r), lg = LinearOfSrgb(g), lb = LinearOfSrgb(b);
  const double x = 0.4124 * lr + 0.3576 * lg + 0.1805 * lb;
  const double y = 0.2126 * lr + 0.7152 * lg + 0.0722 * lb;
  const double z = 0.0193 * lr + 0.1192 * lg + 0.9505 * lb;
  const double fy = LabF(y / kWhiteY);
  const double lightness = 116.0 * fy - 16.0;
  const double a = 500.0 * (LabF(x / kWhiteX) - fy);
  const double bb = 200.0 * (fy - LabF(z / kWhiteZ));
  Msh out;
  out.m = std::sqrt(lightness * lightness + a * a + bb * bb);
  out.s = std::acos(lightness / out.m);
  out.h = std::atan2(bb, a);
  return out;
}

Rgb SrgbOfMsh(const Msh& c) {
  const double lightness = c.m * std::cos(c.s);
  const double a = c.m * std::sin(c.s) * std::cos(c.h);
  const double bb = c.m * std::sin(c.s) * std::sin(c.h);
  const double fy = (lightness + 16.0) / 116.0;
  const double x = kWhiteX * LabFInverse(fy + a / 500.0);
  const double y = kWhiteY * LabFInverse(fy);
  const double z = kWhiteZ * LabFInverse(fy - bb / 200.0);
  const double linear[3] = {3.2406 * x - 1.5372 * y - 0.4986 * z,
                            -0.9689 * x + 1.8758 * y + 0.0415 * z,
                            0.0557 * x - 0.2040 * y + 1.0570 * z};
  std::uint8_t bytes[3];
  for (int k = 0; k < 3; ++k) {
    const double c01 = SrgbOfLinear(linear[k]);
    bytes[k] =
        static_cast<std::uint8_t>(std::lround(255.0 * (c01 < 0.0 ? 0.0 : std::min(c01, 1.0))));
  }
  return Rgb{bytes[0], bytes[1], bytes[2]};
}

// The hue of the unsaturated colour of magnitude m_unsaturated next to `saturated` (AdjustHue).
double SpunHue(const Msh& saturated, double m_unsaturated) {
  if (saturated.m >= m_unsaturated) return saturated.h;
  const double spin = saturated.s *
                      std::sqrt(m_unsaturated * m_unsaturated - saturated.m * saturated.m) /
                      (saturated.m * std::sin(saturated.s));
  return saturated.h > -kPi / 3.0 ? saturated.h + spin : saturated.h - spin;
}

// Moreland's InterpolateColor between two saturated colours of distant hue, at t in [0, 1].
Msh Interpolate(Msh a, Msh b, double t) {
  const bool both_saturated = a.s > 0.05 && b.s > 0.05;
  if (both_saturated && std::abs(a.h - b.h) > kPi / 3.0) {
    const double m_mid = std::max({a.m, b.m, 88.0});
    if (t < 0.5) {
      b = Msh{m_mid, 0.0, 0.0};
      t = 2.0 * t;
    } else {
      a = Msh{m_mid, 0.0, 0.0};
      t = 2.0 * t - 1.0;
    }
  }
  if (a.s < 0.05 && b.s > 0.05) {
    a.h = SpunHue(b, a.m);
  } else if (b.s < 0.05 && a.s > 0.05) {
    b.h = SpunHue(a, b.m);
  }
  return Msh{(1.0 - t) * a.m + t * b.m, (1.0 - t) * a.s + t * b.s, (1.0 - t) * a.h + t * b.h};
}

constexpr int kEntries = 257;

std::array<Rgb, kEntries> CoolWarmTable() {
  const Msh cool = MshOfSrgb(0.230, 0.299, 0.754);
  const Msh warm = MshOfSrgb(0.706, 0.016, 0.150);
  std::array<Rgb, kEntries> table;
  for (int k = 0; k < kEntries; ++k)
    table[k] = SrgbOfMsh(Interpolate(cool, warm, double(k) / (kEntries - 1)));
  return table;
}

}  // namespace

Rgb CoolWarm(double t) {
  static const std::array<Rgb, kEntries> kTable = CoolWarmTable();
  if (std::isnan(t)) return kNanColour;
  const double clamped = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  return kTable[static_cast<std::size_t>(std::lround(clamped * (kEntries - 1)))];
}

}  // namespace dlmfd
