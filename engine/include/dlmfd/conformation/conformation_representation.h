// The representation in which step (35) advects the conformation tensor (fluid.conformation):
//   standard  A itself, with the SPD blend of conformation_advection.h;
//   log       Psi = log A (Fattal & Kupferman 2004): A = exp(Psi) is SPD for any Psi, so the
//             advection needs no blend, and the steep exponential layers of A become the smooth
//             linear layers of Psi;
//   sqrt      B = A^(1/2), the symmetric positive square root (Balci, Thomases, Renardy & Doering
//             2011): A = B^2 is SPD for any non-singular symmetric B, and B grows like the square
//             root of A.
// The advection dA/dt + u . grad A = 0 is transport, which commutes with any pointwise map, so it
// is equally dPsi/dt + u . grad Psi = 0 and dB/dt + u . grad B = 0: the representation changes
// only which field the third-order scheme interpolates. The stretching and relaxation then act on
// A = exp(Psi) or B^2 by the exact pointwise update (method notes 2, section 2.4, option (i); the
// same split as Basilisk's log-conform.h). In Balci's terms the symmetric root is the gauge: after
// each pointwise update B is taken as the symmetric root of A (their antisymmetric gauge term set
// so that B stays symmetric). What this does not do: integrate the Psi equation's Omega/B
// decomposition or the B equation's stretching terms directly (their option (ii)); with an exact
// pointwise update in A the two agree up to the splitting error.
// Functions of a symmetric 2x2 matrix by the closed-form spectral decomposition (Sylvester):
//   f(A) = f(l2) I + [f(l1) - f(l2)] / (l1 - l2) (A - l2 I), with the divided difference in a
//   cancellation-free form (log1p, expm1, 1/(sqrt l1 + sqrt l2)) so that l1 = l2 is exact.
// Not supported: a log of a matrix that is not SPD (the caller checks A before the step).
// References: Fattal & Kupferman, J. Non-Newton. Fluid Mech. 123 (2004) 281; Balci, Thomases,
//   Renardy & Doering, J. Non-Newton. Fluid Mech. 166 (2011) 546; Higham, Functions of Matrices
//   (2008), 1.2 (Sylvester's formula).
#pragma once

#include <cmath>

#include "dlmfd/conformation/sym_tensor.h"
#include "dlmfd/core/params.h"

namespace dlmfd {

// Eigenvalues l1 >= l2 of a symmetric 2x2 matrix, and the form f(l2) I + g (A - l2 I).
struct SymSpectrum {
  double l1, l2;
};

inline SymSpectrum SpectrumOf(const SymTensor& a) {
  const double half_diff = 0.5 * (a.a11 - a.a22);
  const double radius = std::sqrt(half_diff * half_diff + a.a12 * a.a12);
  const double mean = 0.5 * (a.a11 + a.a22);
  const double l1 = mean + radius;
  // l2 = det / l1 keeps full relative accuracy for an SPD tensor (sym_tensor.h).
  const double l2 = (mean > 0.0 && l1 > 0.0) ? Determinant(a) / l1 : mean - radius;
  return SymSpectrum{l1, l2};
}

inline SymTensor SylvesterForm(const SymTensor& a, double l2, double f2, double g) {
  return SymTensor{f2 + g * (a.a11 - l2), g * a.a12, f2 + g * (a.a22 - l2)};
}

// log A for an SPD A.
inline SymTensor MatrixLog(const SymTensor& a) {
  const SymSpectrum s = SpectrumOf(a);
  const double gap = s.l1 - s.l2;
  const double g = gap > 0.0 ? std::log1p(gap / s.l2) / gap : 1.0 / s.l2;
  return SylvesterForm(a, s.l2, std::log(s.l2), g);
}

// exp Psi for a symmetric Psi.
inline SymTensor MatrixExp(const SymTensor& psi) {
  const SymSpectrum s = SpectrumOf(psi);
  const double gap = s.l1 - s.l2;
  const double e2 = std::exp(s.l2);
  const double g = gap > 0.0 ? e2 * std::expm1(gap) / gap : e2;
  return SylvesterForm(psi, s.l2, e2, g);
}

// The symmetric positive square root of an SPD A.
inline SymTensor MatrixSqrt(const SymTensor& a) {
  const SymSpectrum s = SpectrumOf(a);
  const double r1 = std::sqrt(s.l1), r2 = std::sqrt(s.l2);
  return SylvesterForm(a, s.l2, r2, 1.0 / (r1 + r2));
}

// B^2 for a symmetric B.
inline SymTensor Square(const SymTensor& b) {
  return SymTensor{b.a11 * b.a11 + b.a12 * b.a12, b.a12 * (b.a11 + b.a22),
                   b.a12 * b.a12 + b.a22 * b.a22};
}

// A -> the advected variable of the representation, and back.
inline SymTensor ToRepresentation(ConformationRepresentation r, const SymTensor& a) {
  switch (r) {
    case ConformationRepresentation::kLog:
      return MatrixLog(a);
    case ConformationRepresentation::kSqrt:
      return MatrixSqrt(a);
    case ConformationRepresentation::kStandard:
      break;
  }
  return a;
}

inline SymTensor FromRepresentation(ConformationRepresentation r, const SymTensor& x) {
  switch (r) {
    case ConformationRepresentation::kLog:
      return MatrixExp(x);
    case ConformationRepresentation::kSqrt:
      return Square(x);
    case ConformationRepresentation::kStandard:
      break;
  }
  return x;
}

}  // namespace dlmfd
