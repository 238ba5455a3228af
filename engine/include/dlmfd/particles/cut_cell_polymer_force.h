// The polymer force of step (33) on the fluid part of a mesh with cut cells (particle_mesh.kind =
// "cut_cell" with a polymer; issue 33 point 3): f_i = -int_{Omega_f} grad phi_i : tau_p, tau_p =
// G (S - I) P1 on the h-mesh (S = A, or what conformation/oldroyd_b_polymer.h passes: T(A) + I,
// minus 2 w lambda D_h with DEVSS).
//
// The whole-mesh force (conformation/polymer_force.h: the integral over every h-triangle, exact
// for a P1 tau_p: |T| grad phi_i . mean of tau_p) is corrected triangle by triangle where the
// mesh is not all fluid (particles/cut_cell_geometry.h): a solid triangle's integral is taken
// out, a cut triangle's replaced by the integral over its fluid polygon, exact for a linear tau_p:
//   int_{T_f} grad phi_i : tau_p = |T_f| grad phi_i : tau_p(c_f),   c_f the polygon's centroid,
// tau_p(c_f) = sum_k tau_k lambda_k(c_f), lambda_k(x) = 1/3 + grad phi_k . (x - c_T) (c_T the
// triangle's centroid). With domain.diagonals = "both" the whole-mesh force is the mean over the
// two triangulations, so each geometry's correction carries the weight 1/2. Across a periodic side
// a repeated last node's contribution goes to the first (the layout of mesh/fem_operators.h).
// The cut-cell step reads the force on a body from the momentum residual with this load in it
// (particles/cut_cell_stokes.h, Load), so the body feels the polymer stress of the fluid around
// it: sum_i Phi_i f_i = -int_{Omega_f} tau_p : grad Phi, the polymer traction over a closed line
// in the fluid (Phi = 1 near the body).
// Check: sum_i x_i fx_i = -int_{Omega_f} tau_11, sum_i y_i fx_i = -int tau_12, sum_i y_i fy_i =
// -int tau_22 for any tau_p (tests/unit/cut_cell_polymer_force_test.cc).
#pragma once

#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/node_force.h"
#include "dlmfd/particles/cut_cell_geometry.h"

namespace dlmfd {

// fx, fy += the correction above for every geometry (one, or the two triangulations of "both"),
// so that a whole-mesh force in (fx, fy) becomes the fluid part's.
void AddCutCellPolymerCorrection(const std::vector<const CutCellGeometry*>& geometries,
                                 double modulus, const double* s11, const double* s12,
                                 const double* s22, double* fx, double* fy);

}  // namespace dlmfd
