// Symmetric 2x2 tensors (the configuration tensor A = [[a11, a12], [a12, a22]]) and the velocity
// gradient L_ij = du_i/dx_j, with the small inline kernels the conformation step needs.
//
// The smallest eigenvalue is computed as det / lambda_max (method notes 2, section 2.3): the
// textbook (a + c)/2 - sqrt(...) cancels to 0 when A11 ~ 1e5 while det/lambda_max keeps full
// relative accuracy for an SPD tensor.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace dlmfd {

struct SymTensor {
  double a11 = 1.0;
  double a12 = 0.0;
  double a22 = 1.0;
};

// A general 2x2 matrix, row-major: [[m11, m12], [m21, m22]].
struct Mat2 {
  double m11 = 0.0, m12 = 0.0, m21 = 0.0, m22 = 0.0;
};

inline double Trace(const SymTensor& a) { return a.a11 + a.a22; }
inline double Determinant(const SymTensor& a) { return a.a11 * a.a22 - a.a12 * a.a12; }
inline bool IsFinite(const SymTensor& a) {
  return std::isfinite(a.a11) && std::isfinite(a.a12) && std::isfinite(a.a22);
}

// sqrt rather than hypot: hypot is ~10x slower and guards only against overflow beyond 1e154.
inline double MaxEigenvalue(const SymTensor& a) {
  const double half_diff = 0.5 * (a.a11 - a.a22);
  return 0.5 * (a.a11 + a.a22) + std::sqrt(half_diff * half_diff + a.a12 * a.a12);
}

// lambda_min = det / lambda_max when lambda_max > 0 (no cancellation); otherwise the direct
// formula.
inline double MinEigenvalue(const SymTensor& a) {
  const double lambda_max = MaxEigenvalue(a);
  if (lambda_max > 0.0) return Determinant(a) / lambda_max;
  const double half_diff = 0.5 * (a.a11 - a.a22);
  return 0.5 * (a.a11 + a.a22) - std::sqrt(half_diff * half_diff + a.a12 * a.a12);
}

// A lower bound of lambda_min (Gershgorin discs): cheap screens before the exact value.
inline double GershgorinLowerBound(const SymTensor& a) {
  return std::min(a.a11, a.a22) - std::abs(a.a12);
}

// theta a + (1 - theta) b.
inline SymTensor Mix(double theta, const SymTensor& a, const SymTensor& b) {
  return SymTensor{theta * a.a11 + (1.0 - theta) * b.a11, theta * a.a12 + (1.0 - theta) * b.a12,
                   theta * a.a22 + (1.0 - theta) * b.a22};
}

// F A F^T.
inline SymTensor Congruence(const Mat2& f, const SymTensor& a) {
  // G = F A (2x2), then G F^T, symmetric by construction.
  const double g11 = f.m11 * a.a11 + f.m12 * a.a12;
  const double g12 = f.m11 * a.a12 + f.m12 * a.a22;
  const double g21 = f.m21 * a.a11 + f.m22 * a.a12;
  const double g22 = f.m21 * a.a12 + f.m22 * a.a22;
  return SymTensor{g11 * f.m11 + g12 * f.m12, g11 * f.m21 + g12 * f.m22, g21 * f.m21 + g22 * f.m22};
}

// F F^T.
inline SymTensor GramOf(const Mat2& f) {
  return SymTensor{f.m11 * f.m11 + f.m12 * f.m12, f.m11 * f.m21 + f.m12 * f.m22,
                   f.m21 * f.m21 + f.m22 * f.m22};
}

inline double FrobeniusNorm(const Mat2& l) {
  return std::sqrt(l.m11 * l.m11 + l.m12 * l.m12 + l.m21 * l.m21 + l.m22 * l.m22);
}

// x of m x = b for a 3x3 system in (A11, A12, A22), by Cramer's rule.
inline std::array<double, 3> SolveThreeByThree(const double m[3][3],
                                               const std::array<double, 3>& b) {
  auto det3 = [](const double a[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const double det = det3(m);
  std::array<double, 3> x{};
  for (int col = 0; col < 3; ++col) {
    double mc[3][3];
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) mc[r][c] = (c == col) ? b[r] : m[r][c];
    }
    x[col] = det3(mc) / det;
  }
  return x;
}

}  // namespace dlmfd
