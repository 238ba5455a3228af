// Step (35) of the paper: the Oldroyd-B configuration tensor A from t_n to t_{n+1} with the
// velocity u = u^{n+2/4} frozen (construction A of method notes 2, section 2.1); u^{n+2/4} stands
// for the velocity the Simulation passes, the Stokes step's u^{n+1/4} under conformation.velocity =
// "stokes" (core/params.h, ConformationVelocity).
//
// Equation (5): dA/dt + u . grad A = L A + A L^T - (A - I)/lambda, L_ij = du_i/dx_j; A = I inside
//   the particles, A = A_L on the upstream boundary. A is P1 on the h-mesh (values at the velocity
//   nodes).
// Discrete method (a first-order Lie splitting of (35) into advection and a pointwise ODE):
//   1. advection dA/dt + u . grad A = 0 over dt: SSP-RK3 of third-order upwind-biased differences,
//      blended per node with first-order upwind to keep A SPD (conformation_advection.h), in n_sub
//      sub-steps, n_sub = ceil(dt max(|u| + |v|) / (h conformation.max_courant)); with
//      fluid.conformation = log or sqrt the same scheme advects log A or A^(1/2) without the
//      blend, and A = exp(Psi) or B^2 enters step 2 (conformation_representation.h);
//   2. the pointwise ODE dA/dt = L A + A L^T - R(A)/lambda over dt with L frozen at each node
//      (average of the 6 P1 triangle gradients, with domain.diagonals = "both" the mean of that
//      average over both triangulations; velocity_gradient.h), R of the relaxation model
//      (fluid.model, relaxation_model.h): Oldroyd-B (R = A - I) solved exactly by the exponential
//      integrator (pointwise_update.h), the other models by the predictor-corrector of their
//      frozen linear form (model_pointwise_update.h: second order in dt, SPD for any dt);
//   3. A = I at nodes inside particles; A = A_L at the inflow nodes (inflow_state.h: the fully
//      developed state of the model for a poiseuille profile, I for a uniform one), also held
//      during step 1; walls and outflow sides get nothing (constant extrapolation).
// Inflow rule (one rule, applied to u^0 for the initial state and to u^{n+2/4} at every step): a
//   node of a velocity side s is an inflow node of s where u . n_s < 0 (n_s the outward normal) and
//   takes the A_L of s; a corner node of two velocity sides takes the A_L of the last of left,
//   right, bottom, top through which the liquid enters.
// Consistency with (35): (35) is a backward-Euler step of (5) with u^{n+2/4} frozen; the paper
//   (remark 3 of section 4) solves it by a third-order upwind, positive-only scheme. Splitting the
//   frozen-coefficient operator into its convective and pointwise parts is first-order accurate in
//   dt, the same order as (35) and as the Marchuk-Yanenko scheme around it; each part is solved to
//   higher order (third in space and time for the advection; the pointwise part exact up to a
//   sixth-order quadrature, exact for steady states up to it and for pure relaxation).
// Positive definiteness (method notes 2, 2.1): step 1 keeps A SPD (convexity of the SPD cone and
//   concavity of lambda_min, see conformation_advection.h) under the sub-cycled Courant bound; step
//   2 is a positive combination of congruences F A F^T, det F = e^{s tr L} > 0, so SPD for any dt;
//   step 3 assigns SPD values. Hence SPD in, SPD out, unconditionally in dt.
// Checks: A^n is checked before the step and A^{n+1} after it; a non-finite value throws
//   NumericalBlowUp, lambda_min <= 0 throws ConformationNotPositiveDefinite, each naming the time,
//   the node and its position and the quantity. From SPD, finite input this happens only through
//   overflow (e^{2 dt max eig L} beyond 1e308) or a condition number of A beyond 1/eps. A
//   non-finite velocity, or one that would need more than 1000 advection sub-steps, throws
//   NumericalBlowUp.
// Report columns: min_eig_A, max_trA, elastic_courant = lambda dt max |L|_F, blended_nodes (summed
//   over sub-steps), conformation_substeps.
// Not supported: the full Fattal-Kupferman integration of the Psi equation (conformation
//   _representation.h says what the log and sqrt representations do); time-dependent inflow data.
// References: paper section 4 (35) and remark 3; method notes 2, part 2; Shu & Osher (1988).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "dlmfd/conformation/conformation_advection.h"
#include "dlmfd/conformation/relaxation_model.h"
#include "dlmfd/conformation/sym_tensor.h"
#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"

namespace dlmfd {

class ConformationStep {
 public:
  // Throws InvalidParameter for a Newtonian liquid (no conformation step) or when an inflow side
  // has no steady Oldroyd-B state.
  ConformationStep(const Params& params, const Grid& grid);

  // Step (35) with u = u^{n+2/4} frozen: A^n at t_n = time -> A^{n+1} at time + dt (header block).
  void Advance(double time, double dt, const double* u, const double* v,
               const unsigned char* inside_particle, double* a11, double* a12, double* a22,
               StepReport& report);

  // A = A_L at the inflow nodes of the velocity (u, v) (the inflow rule above); other nodes are
  // left as they are.
  void SetInflowState(const double* u, const double* v, double* a11, double* a12, double* a22);

  // The nodal strain rate D_h = (L + L^T) / 2 of the velocity of the last Advance (the L of its
  // step 2), 0 at the nodes inside particles, and at the inflow nodes the strain rate of the
  // profile whose steady state A_L is (so that A - I - 2 lambda D_h = O(lambda^2) at every node),
  // into d11, d12, d22 (fluid.stress_splitting = devss).
  void StrainRate(const unsigned char* inside_particle, double* d11, double* d12,
                  double* d22) const;

  // The relaxation model of the scene (fluid.model).
  const RelaxationModel& model() const { return *model_; }

  // Comparison option for tests only: the unlimited advection (no SPD blend).
  void DisableBlendForComparison() { advection_.DisableBlendForComparison(); }

 private:
  struct BoundaryNode {
    int i, j;
    double nx, ny;                 // outward normal
    SymTensor inflow;              // A_L
    SymTensor inflow_advected;     // A_L in the representation (log A_L, A_L^(1/2))
    SymTensor inflow_strain_rate;  // D of the fully developed profile whose steady state is A_L
    bool active = false;           // an inflow node of this side for the last velocity seen
  };
  // Writes the tensor `value` of every active inflow node into (t11, t12, t22) at its node.
  void WriteAtInflowNodes(SymTensor BoundaryNode::*value, double* t11, double* t12,
                          double* t22) const;
  // Applies the inflow rule to (u, v): BoundaryNode::active and the per-node flags inflow_.
  void FindInflow(const double* u, const double* v);
  // Throws when a node of (a11, a12, a22) is not finite or not SPD. `when` is "before" or "after".
  void CheckField(double time, const char* when, const double* a11, const double* a12,
                  const double* a22) const;
  // Throws NumericalBlowUp (a not finite) or ConformationNotPositiveDefinite for node k.
  [[noreturn]] void ThrowBadNode(double time, const char* when, long k, const SymTensor& a) const;

  Grid grid_;
  double lambda_;
  std::unique_ptr<RelaxationModel> model_;
  bool oldroyd_b_;  // the vectorised exponential integrator applies (pointwise_update.h)
  ConformationRepresentation representation_;
  double max_courant_;
  bool periodic_x_, periodic_y_;
  MeshDiagonals diagonals_;  // domain.diagonals: L on the SW-NE triangles or the mean over both
  ConformationAdvection advection_;
  std::vector<BoundaryNode> boundary_;  // nodes of velocity sides
  std::vector<unsigned char> inflow_;   // per node: 1 where A = A_L this step
  std::vector<double> l11_, l12_, l21_, l22_;
  std::vector<double> r11_, r12_, r22_;  // log and sqrt: the advected variable, then A
};

}  // namespace dlmfd
