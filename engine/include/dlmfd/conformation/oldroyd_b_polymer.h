// The polymer of a viscoelastic liquid: everything the model adds to the Marchuk-Yanenko scheme,
// in one place (the shape of Basilisk's log-conform.h: parameters, initial state, force on the
// momentum equation, substep). Named for the paper's model; it carries every model of
// fluid.model (relaxation_model.h: Oldroyd-B, Giesekus, FENE-P, linear and exponential PTT).
//
// Parameters: relaxation time lambda = fluid.relaxation_time, polymer viscosity eta_p = (1 - beta)
//   eta, modulus G = eta_p / lambda; tau_p = G T(A), T(A) = A - I but for FENE-P (f A - a I)
//   (design.md 4; relaxation_model.h).
// Initial state: A^0 = I, and A^0 = A_L on the inflow nodes of u^0 (the inflow rule of
//   conformation_step.h, the same rule that every step applies to u^{n+2/4}).
// Force on the momentum equation (33): f_i = -int grad phi_i : G T(A^n) (polymer_force.h, which
//   reads S = T(A) + I as it reads A), passed to the Stokes solver as its dual forcing (the solver
//   adds the body force itself). With fluid.stress_splitting = devss the stress is
//   G T(A^n) - w eta_p 2 D_h, S = T(A) + I - 2 w lambda D_h, w = 1 / (1 + lambda eta_p / (rho h^2))
//   (FluidParams::DevssWeight), where D_h (FlowState::d11, d12, d22) is the nodal strain rate that
//   step (35) used for A^n, and the fluid steps carry w eta_p implicitly
//   (FluidParams::ImplicitViscosity). Why the limit lambda -> 0 is then the Newtonian step: w -> 1,
//   and step (35)'s pointwise update with lambda << dt forgets the advected A and leaves
//   A - I = lambda (L + L^T) + O(lambda^2) = 2 lambda D_h + O(lambda^2) with the same L; A = I
//   inside particles, where D_h = 0; and at the inflow nodes A = A_L, the steady state of the
//   profile's strain rate, which D_h takes there. So G T(A) - w eta_p 2 D_h = O(lambda) at every
//   node. The cost of the split is its lag, w eta_p 2 (D(u^{n+1}) - D_h(u^{n-1+2/4})): first order
//   in dt with a constant w eta_p, small where the polymer is elastic on the grid's scale (w ~ rho
//   h^2 / (lambda eta_p)). w is not 1 - e^{-dt/lambda}, which would also vanish for lambda >> dt:
//   a w that depends on dt moves steady states with dt, by w times the difference of the implicit
//   (5-point) and explicit (node-averaged) discretisations of eta_p div 2D (5 % on the viscosity
//   rule's channel at lambda = dt = 2e-3 between dt = 2e-3 and 5e-4).
// Step (35): A^n -> A^{n+1} with u^{n+2/4} frozen (conformation_step.h), with A = I (the rest
//   state of every model) at the velocity nodes strictly inside the particles at X^n (across
//   periodic sides by the minimum image) and A = A_L on the inflow nodes.
// A itself is FlowState::a11, a12, a22 (checkpoints and observers read it there, so tr A is in
//   the events and snapshots for every model); this object holds the force arrays, and the
//   particle marks when the scene has particles.
// Not supported: a Newtonian liquid (lambda = 0 or beta = 1: the run builds no polymer at all).
// References: paper (5), (33), (35); Basilisk src/log-conform.h (the module layout).
#pragma once

#include <vector>

#include "dlmfd/conformation/conformation_step.h"
#include "dlmfd/core/grid.h"
#include "dlmfd/core/node_force.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"

namespace dlmfd {

class OldroydBPolymer {
 public:
  // Throws InvalidParameter for a Newtonian liquid or an inflow side without a steady state.
  OldroydBPolymer(const Params& params, const Grid& grid);

  // A^0 into state.a11, a12, a22: I, and A_L on the inflow nodes of state.u, state.v; with devss
  // D_h = 0 into state.d11, d12, d22.
  void SetInitialState(FlowState& state);
  // The polymer force of (33) for A^n of state; the arrays stay valid until the next call.
  NodeForce MomentumForce(const FlowState& state);
  // Step (35): A^n at state.time -> A^{n+1}, with u^{n+2/4} = state.u, state.v (or u^{n+1/4}:
  // conformation.velocity, core/simulation.cc) and the particles
  // of state at X^n; with devss also D_h of u^{n+2/4} into state.d11, d12, d22. inside_nodes, when
  // given, marks the nodes where A = I in place of the particles' insides (the cut cells' nodes
  // inside the bodies: particles/cut_cell_step.h).
  void Update(double dt, FlowState& state, StepReport& report,
              const unsigned char* inside_nodes = nullptr);

  double modulus() const { return modulus_; }  // G = eta_p / lambda

 private:
  // Marks the velocity nodes strictly inside a particle (inside_particle_).
  void MarkParticleNodes(const std::vector<ParticleState>& particles);

  Grid grid_;
  DomainParams domain_;
  double modulus_;
  double lambda_;
  bool devss_;           // fluid.stress_splitting = devss
  double devss_weight_;  // w with devss (FluidParams::DevssWeight)
  ConformationStep step_;
  std::vector<double> fx_, fy_;          // the force of (33)
  std::vector<double> s11_, s12_, s22_;  // T(A) + I (- 2 w lambda D_h) where that is not A itself
  std::vector<unsigned char> inside_particle_;  // nodes where A = I; scenes with particles only
};

}  // namespace dlmfd
