// Oldroyd-B relaxation: R(A) = A - I, tau_p = G (A - I) (paper (5); Bird, Armstrong & Hassager
// 1987, vol. 1, 4.3). Frozen form N = I, c = 1: the frozen update is then exact for any step
// (nothing depends on A). The standard representation of step (35) keeps its own vectorised
// exponential integrator for this model (pointwise_update.h); this object serves the general path
// (log and sqrt representations, steady states) and tests that the two agree.
#pragma once

#include "dlmfd/conformation/relaxation_model.h"

namespace dlmfd {

class OldroydBRelaxation final : public RelaxationModel {
 public:
  const char* Name() const override { return "oldroyd_b"; }
  SymTensor Source(const SymTensor& a) const override {
    return SymTensor{a.a11 - 1.0, a.a12, a.a22 - 1.0};
  }
  FrozenRelaxation Frozen(const SymTensor&) const override { return FrozenRelaxation{}; }
};

}  // namespace dlmfd
