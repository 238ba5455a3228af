// Phan-Thien-Tanner relaxation (simplified form, xi = 0: upper-convected derivative) with
// parameter epsilon >= 0 (Phan-Thien & Tanner, J. Non-Newton. Fluid Mech. 2 (1977) 353;
// Phan-Thien, J. Rheol. 22 (1978) 259):
//   R(A) = Y (A - I),  tau_p = G (A - I),
//   linear       Y = 1 + epsilon tr(A - I)
//   exponential  Y = exp(epsilon tr(A - I))
// (tr(A - I) = lambda tr tau_p / eta_p, the network's destruction rate grows with the stress).
// epsilon = 0 is Oldroyd-B. Shear-thinning; bounded extensional viscosity for epsilon > 0.
// Frozen form: N = Y I, c = Y. The linear Y is positive for tr A > 2 - 1/epsilon; a state with
// Y <= 0 is outside the model (Admits is false).
#pragma once

#include <cmath>

#include "dlmfd/conformation/relaxation_model.h"

namespace dlmfd {

class PttRelaxation final : public RelaxationModel {
 public:
  PttRelaxation(double epsilon, bool exponential)
      : epsilon_(epsilon),
        exponential_(exponential) {}
  const char* Name() const override { return exponential_ ? "ptt_exponential" : "ptt_linear"; }
  // The stress function Y(tr A).
  double StressFunction(const SymTensor& a) const {
    const double x = epsilon_ * (Trace(a) - 2.0);
    return exponential_ ? std::exp(x) : 1.0 + x;
  }
  SymTensor Source(const SymTensor& a) const override {
    const double y = StressFunction(a);
    return SymTensor{y * (a.a11 - 1.0), y * a.a12, y * (a.a22 - 1.0)};
  }
  FrozenRelaxation Frozen(const SymTensor& a) const override {
    const double y = StressFunction(a);
    return FrozenRelaxation{SymTensor{y, 0.0, y}, y};
  }
  bool Admits(const SymTensor& a) const override { return StressFunction(a) > 0.0; }

 private:
  double epsilon_;
  bool exponential_;
};

}  // namespace dlmfd
