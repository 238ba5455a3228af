// Exact line search of the least-squares CG for (34) (method notes 1, section 4, step 2): along
// u - l w the residual is T0 - l T1 + l^2 T2, so with a_ij = T_i . P^-1 T_j
//   2 J(l) = a00 - 2 l a01 + l^2 (a11 + 2 a02) - 2 l^3 a12 + l^4 a22,
// a quartic whose stationary points are the real roots of the cubic J'(l) = 0 (up to three). The
// minimiser is the root with the lowest J. Roots by the trigonometric / Cardano formulas, polished
// by Newton; when the cubic and quadratic terms are negligible at the quadratic model's minimiser
// l0 = a01 / (a11 + 2 a02) (a nearly linear problem), l0 polished by Newton is used.
#pragma once

namespace dlmfd {

struct QuarticLine {
  double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0;
  double TwiceJ(double l) const {
    return a00 - 2 * l * a01 + l * l * (a11 + 2 * a02) - 2 * l * l * l * a12 + l * l * l * l * a22;
  }
};

// The step l minimising J along the line (0 when the line is flat).
double MinimiseQuarticLine(const QuarticLine& line);

}  // namespace dlmfd
