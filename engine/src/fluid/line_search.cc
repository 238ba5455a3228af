#include "dlmfd/fluid/line_search.h"

#include <cmath>

#include "dlmfd/core/constants.h"

namespace dlmfd {
namespace {

// dJ/dl / 2 = c3 l^3 + c2 l^2 + c1 l + c0.
struct Cubic {
  double c3, c2, c1, c0;
  double operator()(double l) const { return ((c3 * l + c2) * l + c1) * l + c0; }
  double Slope(double l) const { return (3 * c3 * l + 2 * c2) * l + c1; }
  double Polish(double l) const {
    for (int k = 0; k < 4; ++k) {
      const double d = Slope(l);
      if (d == 0.0) break;
      l -= (*this)(l) / d;
    }
    return l;
  }
};

}  // namespace

double MinimiseQuarticLine(const QuarticLine& q) {
  const Cubic f{2 * q.a22, -3 * q.a12, q.a11 + 2 * q.a02, -q.a01};
  if (f.c1 <= 0.0 && f.c2 == 0.0 && f.c3 == 0.0) return 0.0;
  double roots[3];
  int count = 0;
  const double l0 = f.c1 > 0.0 ? -f.c0 / f.c1 : 0.0;
  const bool nearly_linear =
      f.c1 > 0.0 && std::abs(f.c3 * l0 * l0) + std::abs(f.c2 * l0) <= 1e-10 * f.c1;
  if (nearly_linear || f.c3 == 0.0) {
    roots[count++] = f.Polish(l0);
  } else {
    const double a = f.c2 / f.c3, b = f.c1 / f.c3, c = f.c0 / f.c3;
    const double qq = (a * a - 3 * b) / 9, r = (2 * a * a * a - 9 * a * b + 27 * c) / 54;
    if (r * r < qq * qq * qq) {
      const double theta = std::acos(r / std::sqrt(qq * qq * qq));
      const double s = -2 * std::sqrt(qq);
      roots[count++] = f.Polish(s * std::cos(theta / 3) - a / 3);
      roots[count++] = f.Polish(s * std::cos((theta + 2 * kPi) / 3) - a / 3);
      roots[count++] = f.Polish(s * std::cos((theta - 2 * kPi) / 3) - a / 3);
    } else {
      const double big =
          -std::copysign(std::cbrt(std::abs(r) + std::sqrt(r * r - qq * qq * qq)), r);
      const double small = big != 0.0 ? qq / big : 0.0;
      roots[count++] = f.Polish(big + small - a / 3);
    }
  }
  double best = 0.0, best_j = q.TwiceJ(0.0);
  for (int k = 0; k < count; ++k) {
    if (!std::isfinite(roots[k])) continue;
    const double j = q.TwiceJ(roots[k]);
    if (j < best_j) {
      best_j = j;
      best = roots[k];
    }
  }
  return best;
}

}  // namespace dlmfd
