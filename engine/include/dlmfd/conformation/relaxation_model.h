// The constitutive model of the polymer: its relaxation source term in the conformation equation
// and its polymer stress, as one small strategy object per model (the files named after each
// model hold the equations; this header holds the common form, the factory and the scene rule).
//
// Equation (paper (5) generalised): dA/dt + u . grad A = L A + A L^T - R(A) / lambda, and
//   tau_p = (eta_p / lambda) T(A), with R(I) = T(I) = 0 (A = I is the rest state of every model,
//   so A = I inside particles and at a uniform inflow). Every model here writes its source term as
//   R(A) = (N(A) A + A N(A)) / 2 - c(A) I with N(A) symmetric and commuting with A (a polynomial
//   in A) and c(A) > 0:
//     oldroyd_b        R = A - I                         N = I,                  c = 1
//     giesekus         R = (A - I) + alpha (A - I)^2     N = (1 - 2 alpha) I + alpha A, c = 1 -
//     alpha fene_p           R = f A - a I                     N = f I,                c = a
//     ptt_linear       R = Y (A - I), Y = 1 + eps tr(A - I)   N = Y I,           c = Y
//     ptt_exponential  R = Y (A - I), Y = exp(eps tr(A - I))  N = Y I,           c = Y
// Frozen over a step (N, c evaluated at a given A), the pointwise equation is linear in A:
//   dA/dt = K A + A K^T + (c / lambda) I,  K = L - N / (2 lambda),
// solved exactly by A(dt) = G(dt) A G(dt)^T + (c / lambda) int_0^dt G(s) G(s)^T ds, G = exp(s K)
// (model_pointwise_update.h). c > 0 and det G > 0 make it SPD for any dt, and a steady state of
// the model is a fixed point of the frozen update (N commutes with A), so steady states are exact
// up to the quadrature.
// Not supported: models whose source term does not take this form (e.g. the full PTT with xi > 0,
//   whose Gordon-Schowalter derivative changes the stretching term).
// References: Bird, Armstrong & Hassager, Dynamics of Polymeric Liquids vol. 1 (1987), 4.3 and
//   vol. 2 13.5; Giesekus, J. Non-Newton. Fluid Mech. 11 (1982) 69; Phan-Thien & Tanner,
//   J. Non-Newton. Fluid Mech. 2 (1977) 353; Alves, Oliveira & Pinho, Annu. Rev. Fluid Mech. 53
//   (2021) 509 (the forms used by rheoTool).
#pragma once

#include <memory>

#include "dlmfd/conformation/sym_tensor.h"
#include "dlmfd/core/params.h"

namespace dlmfd {

// N(A) and c(A) of the source term, evaluated at one A and then held over a step.
struct FrozenRelaxation {
  SymTensor n;
  double c = 1.0;
};

class RelaxationModel {
 public:
  virtual ~RelaxationModel() = default;
  // The scene word of the model ("giesekus").
  virtual const char* Name() const = 0;
  // R(A) of the header block.
  virtual SymTensor Source(const SymTensor& a) const = 0;
  // N(A), c(A) of the header block.
  virtual FrozenRelaxation Frozen(const SymTensor& a) const = 0;
  // T(A) = tau_p / G, G = eta_p / lambda (A - I for every model but FENE-P).
  virtual SymTensor Stress(const SymTensor& a) const {
    return SymTensor{a.a11 - 1.0, a.a12, a.a22 - 1.0};
  }
  // The states A where the model is defined (FENE-P: tr A < L^2); true by default.
  virtual bool Admits(const SymTensor&) const { return true; }
  // Whether T(A) = A - I (the momentum force then reads A directly).
  virtual bool StressIsAMinusI() const { return true; }
};

// The scene words of fluid.model and fluid.conformation ("fene_p", "log").
const char* ModelName(ConstitutiveModel model);
const char* RepresentationName(ConformationRepresentation representation);

// The model of fluid.model with its parameters (validated: ValidateConstitutiveModel).
std::unique_ptr<RelaxationModel> MakeRelaxationModel(const FluidParams& fluid);

// The conformation module's scene rule for fluid.model and fluid.conformation: a non-default model
// or representation only for a viscoelastic liquid. (Each model parameter's range, and that it is
// given with its model only, are its scene key's: scene/scene_keys.h.) InvalidParameter names the
// key and what is allowed.
void ValidateConstitutiveModel(const FluidParams& fluid);

}  // namespace dlmfd
