// Giesekus relaxation with mobility alpha in [0, 0.5] (Giesekus, J. Non-Newton. Fluid Mech. 11
// (1982) 69; Bird, Armstrong & Hassager 1987, vol. 1, 4.3):
//   R(A) = (A - I) + alpha (A - I)^2,  tau_p = G (A - I),
// the anisotropic drag of the dumbbells; alpha = 0 is Oldroyd-B. Shear-thinning, bounded
// extensional viscosity for alpha > 0.
// Frozen form: (A - I) + alpha (A - I)^2 = alpha A^2 + (1 - 2 alpha) A - (1 - alpha) I
//   = (N A + A N)/2 - c I with N = (1 - 2 alpha) I + alpha A (commutes with A), c = 1 - alpha > 0.
#pragma once

#include "dlmfd/conformation/relaxation_model.h"

namespace dlmfd {

class GiesekusRelaxation final : public RelaxationModel {
 public:
  explicit GiesekusRelaxation(double mobility)
      : alpha_(mobility) {}
  const char* Name() const override { return "giesekus"; }
  SymTensor Source(const SymTensor& a) const override {
    const double b11 = a.a11 - 1.0, b12 = a.a12, b22 = a.a22 - 1.0;
    return SymTensor{b11 + alpha_ * (b11 * b11 + b12 * b12), b12 + alpha_ * b12 * (b11 + b22),
                     b22 + alpha_ * (b12 * b12 + b22 * b22)};
  }
  FrozenRelaxation Frozen(const SymTensor& a) const override {
    const double d = 1.0 - 2.0 * alpha_;
    return FrozenRelaxation{SymTensor{d + alpha_ * a.a11, alpha_ * a.a12, d + alpha_ * a.a22},
                            1.0 - alpha_};
  }

 private:
  double alpha_;
};

}  // namespace dlmfd
