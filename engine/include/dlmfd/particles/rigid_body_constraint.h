// The rigid-body (DLM) step (37) with gamma = 0: the distributed Lagrange multiplier that makes the
// fluid velocity rigid at the multiplier nodes of every particle.
//
// Equations (37), gamma = 0, for every particle P at X^{n+2/4} (method notes 2, section 1.2):
//   rho_L h^2 (u - u*)/dt = E^T nu,   m_e (U - U*)/dt = -sum_k nu_k,
//   j_e (omega - omega*)/dt = -sum_k r_perp_k . nu_k,   E u = U + omega r_perp_k at every node k,
// with nu = G lambda the nodal forces, G = M_p + R^2 K_p the H1 Gram matrix of (24), m_e = (rho_d -
// rho_L) pi R^2, j_e = m_e R^2 / 2. Fixed and prescribed particles keep U and omega.
// Discrete method: E is the P1 interpolation from the fluid h-grid (SW-NE diagonals) at the
// particle nodes, rebuilt each step; E^T only reaches fluid nodes that are unknowns (Dirichlet
// nodes keep their data); the lumped mass is rho_L h^2 times the trapezoid edge factors. Solver:
// the conjugate gradient of method notes 1.3 in the H1 product <a, b>_G = a^T G b, all particles
// stacked in one CG (their supports share fluid nodes when they are close, so the per-particle
// problems are coupled then; the spectrum of the stacked operator is the union of the per-particle
// spectra, so the iteration count does not grow with N). The iterate is tracked as nu (lambda is
// never formed). Warm start from the stored nu when it leaves a smaller residual than the cold
// start. Stop when <g, g>_G <= max(tol^2 <g0, g0>_G, floor), g0 = E u* - U* - omega* r_perp the
// cold-start mismatch (for neutral particles: its projection P g0, after the particular forces
// nu_f; an absolute reference, so warm starts pay) and floor a round-off level (1e-11 times the
// velocity scale, in the G norm). Throws SolverNotConverged after
// solvers.multiplier_max_iterations.
// Cost: one G product per iteration (G w is updated by the CG recursion G w' = G g' + beta G w),
// and E^T is applied by fluid node: the distinct fluid nodes that E^T reaches get compact slots,
// and each slot gathers its contributions (stacked multiplier node, weight) from a transposed list
// built once per step, so the work per iteration is proportional to the multiplier nodes (no
// fluid-sized array is touched inside the CG) and the fluid velocity is updated once after it.
// OpenMP (from 32 particles on; below, the barriers cost more than the work): the per-particle
// loops and the per-slot gathers are shared between the threads; every sum is taken per particle
// and then over the particles in a fixed order, so the result does not depend on the thread count
// (no atomics). Neutrally buoyant free particles (rho_d = rho_L, m_e = j_e = 0): the momentum
// equations of (37) become the constraints C^T nu = f, with C = [e_x, e_y, r_perp] the rigid modes
// at the nodes and f = (F'_avg, 0) the collision force of the predictor (the particle, having no
// excess mass, passes it straight to the fluid); (U, omega) becomes their multiplier:
//   rho_L h^2 (u - u*)/dt = E^T nu,   C^T nu = f,   E u = C (U, omega).
// Exact elimination, with nu = G lambda and the G-orthogonal projector P = I - C S^-1 C^T G
// (S = C^T G C, 3x3 per mesh, constant because the mesh translates without rotating):
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
// gamma != 0.
// References: Glowinski, Pan, Hesla, Joseph, Periaux, J. Comput. Phys. 169 (2001) 363-426;
// method notes 2, sections 1.1-1.6.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"
#include "dlmfd/particles/particle_mesh.h"

namespace dlmfd {

class RigidBodyConstraint {
 public:
  struct Outcome {
    int iterations = 0;
    double residual = 0.0;  // max over multiplier nodes of |E u - U - omega r_perp| after the solve
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
  // (its predictor collision force F'_avg); ignored for the other particles. nullptr means zero.
  Outcome Enforce(double time, double dt, std::vector<ParticleState>& particles, double* u,
                  double* v, const Vec2* net_force);

  // True for a free particle with rho_d = rho_L (solved by the projected CG).
  bool IsNeutral(std::size_t particle) const { return neutral_[particle] != 0; }

  const ParticleMesh& MeshOf(std::size_t particle) const { return meshes_[mesh_of_[particle]]; }
  // The nodal multiplier count (2 per node) of a particle.
  std::size_t MultiplierSize(std::size_t particle) const {
    return 2 * MeshOf(particle).NodeCount();
  }
  // sum_k nu_k and sum_k r_perp_k . nu_k of the last Enforce (the force and torque the particle
  // exerts on the fluid nodes).
  Vec2 NodalForceSum(std::size_t particle) const { return force_sum_[particle]; }
  double NodalTorqueSum(std::size_t particle) const { return torque_sum_[particle]; }

 private:
  // E (stencil_*), the slots of the fluid nodes E^T reaches (touched_) and E^T by slot (spread_*).
  void BuildInterpolation(double time, double dt, const std::vector<ParticleState>& particles);
  void BuildSpreading(double dt);
  // g = E u - U - omega r_perp at the nodes of particle p (g: the stacked array).
  void MismatchOf(std::size_t p, const double* u, const double* v, const Vec2* velocity,
                  const double* omega, double* g) const;
  void Mismatch(const double* u, const double* v, const Vec2* velocity, const double* omega,
                double* g) const;
  // The response to nodal forces dir, in three parts: the rigid response (velocity_b_, omega_b_) of
  // particle p; the fluid response (ub, vb) = dt M^-1 E^T dir at slot s; gb = P (E ub - Ub - omegab
  // r_perp) at the nodes of particle p (P: the projection of neutral particles).
  void RigidResponseOf(std::size_t p, double dt, const double* dir);
  void SpreadSlot(std::size_t slot, const double* dir);
  void ResponseMismatchOf(std::size_t p);
  void Respond(double dt, const double* dir);  // all three
  // u += ub, v += vb at the fluid nodes of the slots.
  void AddResponse(const double* ub, const double* vb, double* u, double* v) const;
  double GramDot(const double* a, const double* b);  // <a, b>_G, stacked
  void ApplyGram(const double* a, double* out) const;
  double InverseNodeMass(int i, int j) const;
  // The rigid modes of every mesh: G C (3 columns of 2 N) and S^-1 = (C^T G C)^-1.
  void BuildRigidModes();
  // (U, omega) = S^-1 (G C)^T a: the G-weighted rigid part of a nodal field of particle p.
  Eigen::Vector3d RigidPart(std::size_t p, const double* a) const;
  // a -= C RigidPart(a) for particle p (a: its block), and on every neutral particle (P a).
  void ProjectMismatchOf(std::size_t p, double* a) const;
  void ProjectMismatch(double* a) const;
  // f -= G C S^-1 C^T f for particle p (f: its block), and on every neutral particle.
  void ProjectForcesOf(std::size_t p, double* f) const;
  void ProjectForces(double* f) const;
  // The conjugate gradients on (g_, w_, nub_ = G w_); returns false on a breakdown (curvature <= 0)
  // with the curvature in *curvature_out. Updates nu_, du_, dv_, velocity_, omega_, gg, iterations.
  bool ConjugateGradients(double dt, double threshold, double& gg, int& iterations,
                          double* curvature_out);

  Grid grid_;
  bool periodic_x_, periodic_y_;
  bool dirichlet_[4];  // by Side
  bool neumann_[4];
  double fluid_density_;
  double tolerance_;
  int max_iterations_;

  std::vector<ParticleMesh> meshes_;
  std::vector<int> mesh_of_;
  std::vector<std::size_t> offset_;  // first stacked node of each particle, then the total
  std::size_t total_nodes_ = 0;
  std::vector<double> inv_excess_mass_, inv_excess_inertia_;  // 0 for fixed, prescribed, neutral
  std::vector<char> neutral_;
  bool any_neutral_ = false;
  std::vector<std::vector<double>> gram_rigid_;      // per mesh: G C, column c at [c * 2 N + q]
  std::vector<Eigen::Matrix3d> rigid_gram_inverse_;  // per mesh: S^-1

  // E, 3 entries per stacked node: the fluid node, its compact response slot (0, a slot always
  // zero, at Dirichlet nodes), the P1 weight and the weight / lumped node mass (0 at Dirichlet
  // nodes).
  std::vector<std::uint32_t> stencil_node_, stencil_slot_;
  std::vector<double> stencil_weight_, stencil_scatter_;
  std::size_t slot_count_ = 0;          // slots 1..slot_count_ are in use this step
  std::vector<std::uint32_t> touched_;  // per slot: its fluid node (touched_[0] unused)
  std::vector<long> stamp_;             // per fluid node: last step that gave it a slot
  std::vector<std::uint32_t> slot_of_;  // per fluid node: its slot in that step
  long stamp_counter_ = 0;
  // E^T by slot: contributions spread_start_[s] .. spread_start_[s + 1] - 1, each a stacked node
  // and dt times its scatter weight, in increasing stacked node order.
  std::vector<std::size_t> spread_start_, spread_cursor_;
  std::vector<std::uint32_t> spread_source_;
  std::vector<double> spread_weight_;

  // Stacked node arrays, 2 per node.
  std::vector<double> nu_, g_, w_, nub_, gb_, scratch_;
  // Per slot: the fluid response and the accumulated CG update of the fluid velocity.
  std::vector<double> ub_, vb_, du_, dv_;
  std::vector<double> partial_, partial_gg_;  // per particle: its part of a stacked sum
  bool parallel_ = false;  // the CG runs on the OpenMP threads (enough particles)
  std::vector<Vec2> velocity_, velocity_b_, force_sum_;
  std::vector<double> omega_, omega_b_, torque_sum_;
};

}  // namespace dlmfd
