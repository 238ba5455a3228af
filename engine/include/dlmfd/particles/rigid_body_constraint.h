// The rigid-body (DLM) step (37) with gamma = 0: the distributed Lagrange multiplier that makes the
// fluid velocity rigid at the multiplier points of every particle.
//
// Equations (37), gamma = 0, for every particle P at X^{n+2/4} (method notes 2, section 1.2):
//   rho_L h^2 (u - u*)/dt = E^T nu,   m_e (U - U*)/dt = -sum_k nu_k,
//   j_e (omega - omega*)/dt = -sum_k r_perp_k . nu_k,   E u = U + omega r_perp_k at every point k,
// with nu = G lambda the nodal forces, G = M_p + R^2 K_p the H1 Gram matrix of (24), m_e = (rho_d -
// rho_L) pi R^2, j_e = m_e R^2 / 2 (an ellipse: m_e = (rho_d - rho_L) pi a b, j_e = m_e (a^2 + b^2)
// / 4, its points turned to the particle's angle first). Fixed and prescribed particles keep U and
// omega.
// The room, by concept (each header says its part):
//   particles/multiplier_points.h  the multiplier points (the ring mesh of each disk, or
//                                  collocation points on the circle) and G;
//   particles/coupling_operator.h  E, the P1 (or P2) interpolation at the points (rebuilt each
//                                  step), and dt M^-1 E^T, the spreading onto the fluid nodes
//                                  that are unknowns (mesh/point_location.h locates the points);
//   particles/rigid_modes.h        C = [e_x, e_y, r_perp], the excess-mass response and the
//                                  projector P of neutral particles;
//   particles/multiplier_cg.h      the CG on the Schur complement in <a, b>_G = a^T G b, all
//                                  particles stacked in one CG, iterate tracked as nu (lambda is
//                                  never formed), OpenMP from 32 particles on, results independent
//                                  of the thread count;
// and this class composes them: the parameter checks, then per step E, the cold start, the warm
// start, the CG, the neutral particles' motion and the nodal force sums.
// Stacking: all particles share one CG (their supports share fluid nodes when they are close, so
// the per-particle problems are coupled then; the spectrum of the stacked operator is the union of
// the per-particle spectra, so the iteration count does not grow with N).
// Stopping rule: warm start from the stored nu when it leaves a smaller residual than the cold
// start; stop when <g, g>_G <= max(tol^2 <g0, g0>_G, floor), g0 = E u* - U* - omega* r_perp the
// cold-start mismatch (for neutral particles: its projection P g0, after the particular forces
// nu_f; an absolute reference, so warm starts pay) and floor a round-off level (1e-11 times the
// velocity scale, in the G norm). An increment (the lagged multiplier) is solved to tol^2 times
// the larger of <g0, g0>_G and <g_s, g_s>_G, g_s the response of the stored multiplier (the
// mismatch it holds): relative to its own shrinking g0 alone, the 1,000-disk bed's CG needed 16 to
// 370 iterations a step and rising (docs/evidence/constraint_coupling.md, "The increment's stopping
// rule"). Throws SolverNotConverged after solvers.multiplier_max_iterations. Neutrally buoyant free
// particles (rho_d = rho_L, m_e = j_e = 0): the momentum equations of (37) become the constraints
// C^T nu = f, with C = [e_x, e_y, r_perp] the rigid modes at the points and f = (F'_avg, 0) the
// collision force of the predictor (the particle, having no excess mass, passes it straight to the
// fluid); (U, omega) becomes their multiplier:
//   rho_L h^2 (u - u*)/dt = E^T nu,   C^T nu = f,   E u = C (U, omega).
// Exact elimination, with nu = G lambda and the G-orthogonal projector P = I - C S^-1 C^T G
// (S = C^T G C, 3x3 per mesh, constant while the mesh translates; rebuilt when it turns):
//   lambda = lambda_f + P mu with lambda_f = C S^-1 f (so C^T G lambda_f = f, C^T G P = 0), and
//   P (E u* + dt E M^-1 E^T G lambda) = 0 for mu: the operator P E M^-1 E^T G is self-adjoint and
//   positive on range(P) in <., .>_G, so the same CG runs on it with the residual and the response
//   projected by P (the G-weighted rigid part is taken out) and the nodal directions G w free of
//   net force and torque. Then E u - C (U, omega) = P E u, hence (U, omega) = S^-1 C^T G E u, the
//   rigid part of E u in the G metric, recovered after the CG. Heavy, neutral, fixed and prescribed
//   particles mix in one stacked CG (the projector acts per neutral particle).
// Not supported: free particles lighter than the liquid (m_e < 0: eliminating U and omega leaves
// E M^-1 E^T + C D^-1 C^T with D = diag(m_e, m_e, j_e) < 0; on a uniform nodal force the first term
// is about 1/(rho_L pi R^2) and the second -1/|m_e|, larger since |m_e| = (rho_L - rho_d) pi R^2
// < rho_L pi R^2: the operator is indefinite and needs MINRES) - rejected with InvalidParameter;
// grids of more than 2^32 - 1 velocity nodes (32-bit node indices of E) - rejected with
// InvalidParameter; gamma != 0.
// References: Glowinski, Pan, Hesla, Joseph, Periaux, J. Comput. Phys. 169 (2001) 363-426;
// method notes 2, sections 1.1-1.6; deal.II step-60 (the coupling operator as an object, the solve
// as operator algebra).
#pragma once

#include <cstddef>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"
#include "dlmfd/particles/coupling_operator.h"
#include "dlmfd/particles/multiplier_cg.h"
#include "dlmfd/particles/multiplier_points.h"
#include "dlmfd/particles/particle_mesh.h"
#include "dlmfd/particles/rigid_modes.h"

namespace dlmfd {

class RigidBodyConstraint {
 public:
  struct Outcome {
    int iterations = 0;
    double residual =
        0.0;  // max over multiplier points of |E u - U - omega r_perp| after the solve
    double cold_residual = 0.0;  // the same before the solve
    bool warm_start = false;     // the stored multiplier was used
  };

  // Meshes for every particle of params.particles (one per distinct radius). Throws
  // InvalidParameter.
  RigidBodyConstraint(const Params& params, const Grid& grid);

  // Solves (37). On entry particles hold X^{n+2/4}, U* and omega*, u and v hold u^{n+2/4}; on
  // return particles hold U^{n+1}, omega^{n+1} and multiplier = nu, u and v hold u^{n+1}. time
  // names the step in errors. Throws ParticlesOverlap when a particle mesh leaves a non-periodic
  // domain, SolverNotConverged.
  Outcome Enforce(double time, double dt, std::vector<ParticleState>& particles, double* u,
                  double* v);
  // The same, with net_force[p] the force a neutrally buoyant free particle p passes to the fluid
  // (its predictor collision force F'_avg) and net_torque[p] its torque (an ellipse's collisions);
  // ignored for the other particles. nullptr means zero.
  // With increment (splitting.constraint = "incremental", particles/lagged_multiplier.h) the
  // stored multiplier has acted already: the CG finds its increment nu from a zero start and the
  // particles hold multiplier += nu on return (a neutral particle, not lagged: multiplier = nu).
  // With mismatch_shift (2 per point, stacked; nullptr means zero) the constraint holds on
  // E u + shift instead of E u: the lagged multiplier's fixed particles hold it on the Stokes
  // step's velocity (particles/lagged_multiplier.h, "Where the constraint holds").
  Outcome Enforce(double time, double dt, std::vector<ParticleState>& particles, double* u,
                  double* v, const Vec2* net_force, bool increment = false,
                  const double* net_torque = nullptr, const double* mismatch_shift = nullptr);

  // The inviscid Schur complement of (37) as an operator, for the viscous coupling of the Stokes
  // step (particles/viscous_constraint.h), in two calls: Locate builds E at the particles'
  // positions; SolveResponse then finds the nodal forces nu with P nu = -mismatch, P = dt E M^-1
  // E^T
  // + dt C D^-1 C^T (its CG stopped at <g, g>_G <= tolerance^2 <g0, g0>_G), touching neither the
  // fluid nor the particles (scratch_u, scratch_v: fluid-sized arrays whose values it spoils).
  // Returns the CG iterations. Throws ParticlesOverlap (Locate), SolverNotConverged.
  void Locate(double time, double dt, const std::vector<ParticleState>& particles);
  int SolveResponse(double time, double dt, const std::vector<ParticleState>& particles,
                    const double* mismatch, double tolerance, double* forces, double* scratch_u,
                    double* scratch_v);
  // The operators of the last Locate or Enforce.
  const MultiplierPoints& points() const { return points_; }
  const RigidModes& modes() const { return modes_; }
  const CouplingOperator& coupling() const { return coupling_; }
  const MultiplierCg& cg() const { return cg_; }

  // True for a free particle with rho_d = rho_L (solved by the projected CG).
  bool IsNeutral(std::size_t particle) const { return modes_.IsNeutral(particle); }

  // The ring mesh of a particle (particle_mesh.kind = "ring").
  const ParticleMesh& MeshOf(std::size_t particle) const { return points_.Mesh(particle); }
  // The multiplier points of every particle (either kind).
  const MultiplierPoints& Points() const { return points_; }
  // The nodal multiplier count (2 per point) of a particle.
  std::size_t MultiplierSize(std::size_t particle) const {
    return 2 * static_cast<std::size_t>(points_.Count(particle));
  }
  // sum_k nu_k and sum_k r_perp_k . nu_k of the last Enforce (the force and torque the particle
  // exerts on the fluid nodes in (37); of the increment after an Enforce with increment).
  Vec2 NodalForceSum(std::size_t particle) const { return force_sum_[particle]; }
  double NodalTorqueSum(std::size_t particle) const { return torque_sum_[particle]; }

 private:
  // Turns the points of the particles whose shape turns (ellipses) to their angles, and their
  // rigid modes with them; Enforce and Locate call it before building E.
  void Orient(const std::vector<ParticleState>& particles);

  double tolerance_;
  MultiplierPoints points_;
  RigidModes modes_;
  CouplingOperator coupling_;
  MultiplierCg cg_;
  std::vector<Vec2> force_sum_;
  std::vector<double> torque_sum_;
};

}  // namespace dlmfd
