// The volume flux of a periodic domain held by a uniform mean pressure gradient (domain.flow_rate;
// issue 37 point 3, sedimentation without end walls).
//
// A channel periodic in one direction e (walls or inflow on the other two sides) holds the flow
// rate along e; a box periodic in both directions holds both (the rate along x and along y are
// zero: no wall holds the liquid in either). With L_a the period along the axis a, the rate is
//   Q_a(u) = (1/L_a) sum_k w_k u_k . e_a,   w_k the lumped mass of the distinct node k,
// the mean over the period of the flux through the lines across a (equal for a solenoidal field;
// the discrete ones agree to the divergence residual). In a fully periodic box Q_a is L_b times
// the mean velocity along a. In DLM/FD the velocity fills the particles too (rigid motion), so
// Q is the flux of the mixture, liquid and particles. Step (33) gains the forces G_a M_l e_a and
// the constraints Q_a(u) = Q_a0, with G_a their Lagrange multipliers:
//   A u - B^T p = F + sum_a G_a M_l e_a,   B u = 0,   Q_a(u) = Q_a0.
// The constraints' gradients are the forces' directions (symmetric: the viscous coupling's PCG,
// whose response solves hold Q = 0, stays a CG). The right side is linear in G, so
// u = u_0 + sum_a G_a u_a with u_0 the solve without G and u_a the response to a unit G_a with
// zero boundary data, A u_a = M_l e_a. u_a depends on the coordinate across a only, so B u_a = 0
// on the mesh (the edges along e_a of every triangle carry equal values) and the pressure is
// unchanged; in a fully periodic box K kills the constants and u_a = (dt / rho) e_a exactly, a
// uniform shift. Hence G = R^-1 (Q_0 - Q(u_0)), R_ab = Q_a(u_b) (1 x 1, or 2 x 2 and diagonal),
// and after (33) the rates are Q_0 to round-off, whatever the tolerance of the solve. G is minus
// the mean pressure gradient (the pressure of the whole liquid is p - G . x). In sedimentation
// G |Omega| balances the particles' excess weight, plus in a channel the walls' shear on the
// liquid that climbs beside the particles (a periodic suspension's frame of zero mixture flux and
// the pressure gradient that carries its weight: Ladd, J. Fluid Mech. 271 (1994) 311-339). The
// later sub-steps (34)-(38) leave the rates O(dt) off Q_0 (the DLM step hands the particles' weight
// of one step to the liquid); the next (33) restores them. Measurements:
// docs/evidence/validation_particles.md, "Sedimentation without end walls".
#pragma once

#include <array>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"

namespace dlmfd {

class FluxControl {
 public:
  // The unit response u_a of one held axis (zero Dirichlet data): A u_a = M_l e_a.
  struct UnitResponse {
    int axis = 0;  // 0: x, 1: y
    std::vector<double> u, v;
  };

  // weights: w_k (0 at periodic duplicates). Hold needs the responses of the step's A first.
  FluxControl(const Grid& grid, const DomainParams& domain, std::vector<double> weights);

  // The unit responses of A = (rho/dt) M_l + nu K, one per held axis in the order of axes(): set
  // by the Stokes step for its dt, again when dt changes (A with it).
  void SetResponses(std::vector<UnitResponse> responses);

  // The periodic axes whose rate is held (0: x, 1: y): one in a channel, both in a box.
  static std::vector<int> HeldAxes(const DomainParams& domain);

  // Q_a(u, v), the flow rate along the axis a (0: x, 1: y).
  double FlowRate(int axis, const double* u, const double* v) const;
  // u += sum_a G_a u_a with G such that Q_a(u) = Q_a0 on every held axis; returns G (0 on an axis
  // not held).
  Vec2 Hold(double* u, double* v) const;

  // The held axes, in the order of the responses.
  const std::vector<int>& axes() const { return axes_; }
  double target() const { return target_; }

 private:
  std::array<double, 2> period_{};  // L_x, L_y
  double target_;                   // Q_0, on every held axis
  std::vector<double> weights_;
  std::vector<UnitResponse> responses_;
  std::vector<int> axes_;
  std::array<std::array<double, 2>, 2> inverse_{};  // R^-1
};

}  // namespace dlmfd
