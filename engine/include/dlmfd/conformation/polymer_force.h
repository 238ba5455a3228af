// The polymer force on the right side of step (33): f_i = -int grad phi_i : tau_p, with
// tau_p = (eta_p / lambda)(A - I) (design.md 4; the paper's c A / lambda_s differs by an isotropic
// part, which the pressure takes, and lambda_s is a typo for lambda_r).
//
// Discrete method: phi_i the P1 hat functions of the h-mesh, A P1 on the same mesh. grad phi_i is
// constant on each triangle and tau_p linear, so the integral is exact per triangle:
// int_T grad phi_i . tau_p = |T| grad phi_i . (mean of tau_p at the 3 vertices). The result is
// added into dual vectors (fx, fy) at every node, boundary nodes included (the Stokes solver
// ignores Dirichlet rows); across a periodic side the contributions to the repeated last node are
// folded into the first node and the repeated node gets none (the layout of mesh/fem_operators.h).
// Scale: f ~ h tau_p. Interior rows equal h^2 div tau_p for a linear tau_p.
// With domain.diagonals = "both" the force is the mean of the integrals on the SW-NE and on the
// NW-SE triangles, each node's gathered from both triangulations in one sweep (interior nodes by
// the mean's closed form, polymer_force.cc).
// Not supported: other stress models (log-conformation would pass exp(Psi)).
// References: paper (33); design.md 4.
#pragma once

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"

namespace dlmfd {

// fx, fy += -int grad phi_i : tau_p, tau_p = polymer_modulus (A - I), polymer_modulus = eta_p /
// lambda.
void AddPolymerForce(const Grid& grid, const DomainParams& domain, double polymer_modulus,
                     const double* a11, const double* a12, const double* a22, double* fx,
                     double* fy);

}  // namespace dlmfd
