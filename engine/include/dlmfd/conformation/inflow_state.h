// Steady Oldroyd-B states used as boundary data A_L of step (35) and as references in tests.
//
// Equation: the steady, homogeneous form of paper (5): L A + A L^T - (A - I)/lambda = 0 with a
// constant velocity gradient L. It is linear in (A11, A12, A22):
//   [1/lambda - 2 L11, -2 L12, 0; -L21, 1/lambda - L11 - L22, -L12; 0, -2 L21, 1/lambda - 2 L22] A
//   = I/lambda,
// solved by Cramer's rule. For a parallel flow (L^2 = 0) the solution is
// A = I + lambda (L + L^T) + 2 lambda^2 L L^T; in simple shear of rate g (u = g y):
// A11 = 1 + 2 (lambda g)^2, A12 = lambda g, A22 = 1 (reference README, "steady simple shear").
// Inflow of a poiseuille side: the parabola u(s) = max 4 s (W - s) / W^2 along the side (s from its
// first corner, W its length) is the fully developed channel flow; its state is the steady state of
// L = max (d phi/ds) e_s^T at that point. A uniform profile has L = 0, so A_L = I. A quartic side
// carries tangential data only (fluid/boundary_profile.h), so it is never an inflow: its A_L is I,
// unused. Other models
// (relaxation_model.h): the steady homogeneous state of the same L, by the model's steady solve
// (closed forms exist in shear for some of them; the tests compare the solve with them).
// Not supported: a steady state that does not exist (2 lambda max Re eig L >= 1, strong extension):
// SteadyConformation throws InvalidParameter, since no fully developed inflow state exists. The
// scene validation asks ValidateInflowStates before anything runs, with the same rule.
// References: Bird, Armstrong & Hassager, Dynamics of Polymeric Liquids vol. 1 (1987), 4.3.
#pragma once

#include "dlmfd/conformation/relaxation_model.h"
#include "dlmfd/conformation/sym_tensor.h"
#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"

namespace dlmfd {

// The steady state of the homogeneous flow with gradient l (lambda > 0).
SymTensor SteadyConformation(const Mat2& l, double lambda);
// Steady simple shear of rate g: the closed form of the reference README.
SymTensor SimpleShearConformation(double lambda, double shear_rate);
// A_L at node k (k = 0..nodes along the side - 1, from the bottom or left corner) of a velocity
// side.
SymTensor InflowConformation(const Grid& grid, const DomainParams& domain, Side side, int k,
                             double lambda);
// The velocity gradient L of the fully developed profile at node k of a poiseuille side; false
// (and L = 0) for any other side.
bool InflowGradient(const Grid& grid, const DomainParams& domain, Side side, int k, Mat2* l);
// A_L at node k of a velocity side for the relaxation model of the scene: the closed form above
// for Oldroyd-B, the model's steady homogeneous state otherwise (model_pointwise_update.h).
SymTensor InflowConformation(const Grid& grid, const DomainParams& domain, Side side, int k,
                             double lambda, const RelaxationModel& model);
// The conformation module's scene rule: for a viscoelastic liquid, A_L exists at every node of
// every velocity side of `grid`; else InvalidParameter naming fluid.relaxation_time and the side.
void ValidateInflowStates(const Params& params, const Grid& grid);

}  // namespace dlmfd
