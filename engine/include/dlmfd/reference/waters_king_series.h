// Start-up of plane Poiseuille flow of an Oldroyd-B liquid: the series solution of Waters & King.
//
// Equations: the 1-D momentum and Oldroyd-B constitutive equations for u(y, t) between walls at
// y = 0 and y = 2H, liquid at rest with A = I, driven from t = 0 by a constant pressure gradient G.
// Scaled by Ubar = G H^2 / (3 eta), Y = y / H - 1 in [-1, 1], T = t / lambda_r, the elasticity
// number E = lambda_r eta / (rho H^2) and beta = eta_s / eta (docs/sources/reference_data.md):
//   U(Y, T) = 3/2 (1 - Y^2) - 48 sum_k sin(N (1 + Y) / 2) / N^3 exp(-a T / 2)
//             [cosh(b T / 2) + (g / b) sinh(b T / 2)],   N = (2k - 1) pi,
//   a = 1 + beta E N^2 / 4,  b^2 = a^2 - E N^2,  g = 1 - (2 - beta) E N^2 / 4.
// Method: the exponentials are combined as ((1 + g/b) e^{(b - a) T/2} + (1 - g/b) e^{-(a + b) T/2})
// / 2 with b complex (purely imaginary) for the low modes where a^2 < E N^2, so nothing overflows
// and the sum is real. The terms decay as N^-3; with 400 terms the series matches the reference
// table to its 5 decimals (tests/convergence/waters_king_test.cc).
// Not supported: other channel geometries, the polymer stress (only the velocity is given).
// Reference: N. D. Waters, M. J. King, Rheol. Acta 9 (1970) 345-355. Used by
// tests/convergence/waters_king_test.cc and bench/work_precision/wp_error.cc.
#pragma once

#include <cmath>
#include <complex>

namespace dlmfd {

constexpr int kWatersKingTerms = 400;

// U(Y, T) / Ubar of the series, Y in [-1, 1] (0 is the centre line), T = t / lambda_r.
inline double WatersKingVelocity(double y, double t, double beta, double elasticity,
                                 int terms = kWatersKingTerms) {
  const double pi = std::acos(-1.0);
  double sum = 0.0;
  for (int k = 1; k <= terms; ++k) {
    const double n = (2 * k - 1) * pi;
    const double a = 1.0 + beta * elasticity * n * n / 4.0;
    const double g = 1.0 - (2.0 - beta) * elasticity * n * n / 4.0;
    const std::complex<double> b = std::sqrt(std::complex<double>(a * a - elasticity * n * n, 0.0));
    const std::complex<double> mode = 0.5 * ((1.0 + g / b) * std::exp((b - a) * t / 2.0) +
                                             (1.0 - g / b) * std::exp(-(a + b) * t / 2.0));
    sum += std::sin(n * (1.0 + y) / 2.0) / (n * n * n) * mode.real();
  }
  return 1.5 * (1.0 - y * y) - 48.0 * sum;
}

}  // namespace dlmfd
