// The flow rate of a channel periodic in one direction, held by a uniform mean pressure gradient
// (domain.flow_rate; issue 37 point 3, sedimentation without end walls).
//
// With e the periodic direction and L the period, the flow rate through a cross-section is
//   Q(u) = (1/L) sum_k w_k u_k . e,   w_k the lumped mass of the distinct node k,
// the mean over the period of the flux through the lines across the channel (they are equal for a
// solenoidal field; the discrete ones agree to the divergence residual). Step (33) gains the force
// G M_l e and the constraint Q(u) = Q_0, with G its Lagrange multiplier:
//   A u - B^T p = F + G M_l e,   B u = 0,   Q(u) = Q_0.
// The constraint's gradient is the force's direction (symmetric: the viscous coupling's PCG, whose
// response solves hold Q = 0, stays a CG). The right side is linear in G, so u = u_0 + G u_e with
// u_0 the solve without G and u_e the response to a unit G with zero boundary data,
// A u_e = M_l e. u_e depends on the cross-stream coordinate only, so B u_e = 0 on the mesh (the
// edges along e of every triangle carry equal values) and the pressure is unchanged. Hence one
// scalar a step, G = (Q_0 - Q(u_0)) / Q(u_e), and after (33) the flow rate is Q_0 to round-off,
// whatever the tolerance of the solve. G is minus the mean pressure gradient along e (the pressure
// of the whole liquid is p - G x.e); in sedimentation G L balances the suspension's excess weight
// and the walls' shear on the liquid that climbs beside the particles. The later sub-steps
// (34)-(38) leave the rate O(dt) off Q_0 (the DLM step hands the particles' weight of one step to
// the liquid); the next (33) restores it. Measurements: docs/evidence/validation_particles.md,
// "Sedimentation without end walls".
#pragma once

#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"

namespace dlmfd {

class FluxControl {
 public:
  // weights: w_k (0 at periodic duplicates); ue, ve: the unit response u_e (zero Dirichlet data).
  FluxControl(const Grid& grid, const DomainParams& domain, std::vector<double> weights,
              std::vector<double> ue, std::vector<double> ve);

  // Q(u, v), the flow rate along the periodic direction.
  double FlowRate(const double* u, const double* v) const;
  // u += G u_e with G such that Q(u) = Q_0; returns G.
  double Hold(double* u, double* v) const;

  double target() const { return target_; }

 private:
  bool along_x_;      // the periodic direction is x (else y)
  double period_;     // L
  double target_;     // Q_0
  double unit_rate_;  // Q(u_e)
  std::vector<double> weights_, ue_, ve_;
};

}  // namespace dlmfd
