// The pointwise part of step (35) for any relaxation model (relaxation_model.h): dA/dt = L A +
// A L^T - R(A)/lambda with L frozen at the node, and the steady homogeneous states of a model.
//
// Discrete method:
//   frozen update (FrozenUpdate): with N, c of the model held at a state, the equation is linear,
//     dA/dt = K A + A K^T + (c/lambda) I, K = L - N/(2 lambda), and
//     A(dt) = G(dt) A G(dt)^T + (c/lambda) int_0^dt G(s) G(s)^T ds, G(s) = exp(s K) in closed form
//     (pointwise_update.h), the integral by composite 3-point Gauss-Legendre on n panels, n =
//     ceil(dt (2|tr K|/2 + 2|q_K|) / 0.125) (at most 256; the panel rule of pointwise_update.h,
//     relative error about 2e-12 a panel at the limit).
//   model step (ModelPointwiseStep): predictor A* = frozen update with N(A^n), corrector = frozen
//     update with N((A^n + A*)/2): second order in dt (the frozen coefficients are those of the
//     midpoint up to O(dt^2)); a steady state A_s of the model is a fixed point of both (N(A_s)
//     commutes with A_s), so steady states are exact up to the quadrature. Where a predicted or
//     corrected state leaves the model's domain (FENE-P: tr A >= L^2; linear PTT: Y <= 0) or
//     is not SPD in doubles (an overflowing exponential Y, cond(A) past 1/eps), or where N and c
//     at the corrected state differ from those at the midpoint by more than a quarter (a stiff
//     piece; in a smooth flow they change by O(dt)), that
//     piece is split in halves, recursively, down to dt / 2^20.
//   steady state (SteadyModelConformation): the steady equation L A + A L^T - R(A)/lambda = 0
//     solved by Newton (central-difference Jacobian, until the last correction is below 1e-13
//     (1 + max|A|), or stalls at round-off below 1e-10) with continuation from rest: the states
//     of s L for s = 0 -> 1, each from the last, the step in s doubling after a success (at most
//     1/4) and halving after a failure (at least 1e-6, else InvalidParameter: no steady state
//     connected to rest, as for Oldroyd-B at 2 lambda max Re eig L >= 1). This picks the branch
//     connected to rest, SPD and inside the model's states. (Marching the model step in
//     pseudo-time is not used: with steps far above the relaxation time the predictor-corrector
//     has fixed points that are not steady states; steady states are fixed points of the step,
//     not the converse, once dt |N| / lambda >> 1.)
// Positive definiteness: det G = e^{s tr K} > 0 and c > 0, so each frozen update maps SPD to SPD
//   for any dt (a congruence plus a positive combination of Gram matrices).
// Not supported: time-dependent L within a step (the caller freezes it).
// References: method notes 2, section 2.1 (the exponential integrator); relaxation_model.h.
#pragma once

#include "dlmfd/conformation/relaxation_model.h"
#include "dlmfd/conformation/sym_tensor.h"

namespace dlmfd {

// A(dt) of the frozen linear equation (header block), for any dt > 0 and lambda > 0.
SymTensor FrozenUpdate(const SymTensor& a, const Mat2& l, double dt, double lambda,
                       const FrozenRelaxation& frozen);

// One pointwise step of `model` over dt from a (header block). False when a piece of dt / 2^20
// leaves the model's domain; *out is then the last admissible state reached.
bool ModelPointwiseStep(const RelaxationModel& model, const SymTensor& a, const Mat2& l, double dt,
                        double lambda, SymTensor* out);

// The steady state of `model` in the homogeneous flow of gradient l (header block); throws
// InvalidParameter naming fluid.relaxation_time when it does not exist.
SymTensor SteadyModelConformation(const RelaxationModel& model, const Mat2& l, double lambda);

}  // namespace dlmfd
