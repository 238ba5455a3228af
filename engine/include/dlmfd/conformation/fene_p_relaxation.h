// FENE-P relaxation with extensibility L^2 (Bird, Dotson & Johnson, J. Non-Newton. Fluid Mech. 7
// (1980) 213; Bird, Armstrong & Hassager 1987, vol. 2, 13.5), in the planar form where the trace
// runs over the two components of the plane:
//   R(A) = f A - a I,  tau_p = G (f A - a I),  f = 1 / (1 - tr A / L^2),  a = 1 / (1 - 2 / L^2),
// so that A = I is the rest state (f(I) = a). Defined for tr A < L^2; needs L^2 > 2. The Peterlin
// function f bounds the stretch: tr A < L^2 in every flow, so the extensional viscosity is bounded.
// (The three-dimensional model of a planar flow adds A33 = a/f to the trace: a difference of
// O(1/L^2) from this form.) Frozen form: N = f I, c = a.
#pragma once

#include "dlmfd/conformation/relaxation_model.h"

namespace dlmfd {

class FenePRelaxation final : public RelaxationModel {
 public:
  explicit FenePRelaxation(double extensibility)
      : l2_(extensibility),
        a_(1.0 / (1.0 - 2.0 / extensibility)) {}
  const char* Name() const override { return "fene_p"; }
  // The Peterlin function f(tr A).
  double Peterlin(const SymTensor& a) const { return 1.0 / (1.0 - Trace(a) / l2_); }
  SymTensor Source(const SymTensor& a) const override {
    const double f = Peterlin(a);
    return SymTensor{f * a.a11 - a_, f * a.a12, f * a.a22 - a_};
  }
  FrozenRelaxation Frozen(const SymTensor& a) const override {
    const double f = Peterlin(a);
    return FrozenRelaxation{SymTensor{f, 0.0, f}, a_};
  }
  SymTensor Stress(const SymTensor& a) const override { return Source(a); }
  bool Admits(const SymTensor& a) const override { return Trace(a) < l2_; }
  bool StressIsAMinusI() const override { return false; }
  double extensibility() const { return l2_; }
  double rest_factor() const { return a_; }  // a

 private:
  double l2_, a_;
};

}  // namespace dlmfd
