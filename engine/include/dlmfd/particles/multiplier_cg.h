// The solve of the DLM step (37): conjugate gradients on the Schur complement of (37) in the nodal
// forces nu = G lambda, in the H1 product <a, b>_G = a^T G b (method notes 2, section 1.3), written
// as operator algebra over the coupling operator E (particles/coupling_operator.h), the rigid
// modes C with the excess-mass response D^-1 and the projector P (particles/rigid_modes.h), and
// the product G of the multiplier points (particles/multiplier_points.h).
//
// Operators (the shape of deal.II step-60's Schur complement solve; here the inner solve is exact,
// M being the lumped fluid mass): a force increment dir moves the fluid by dt M^-1 E^T dir and the
// particles by -dt D^-1 C^T dir, so the mismatch g = E u - C (U, omega) moves by the response
//   A dir = P (E dt M^-1 E^T dir + C dt D^-1 C^T dir),
// and (37) is A G lambda = -g(0): A G is self-adjoint and positive (on range(P)) in <., .>_G, so CG
// runs on it with g as the residual (its Riesz representative in the G product is g itself). The
// iterate carries nu, the fluid update by slot of E^T and (U, omega), each updated by the CG
// recursion, so the fluid velocity is written once at the end; G w is updated by
// G w' = G g' + beta G w, one G product per iteration.
// Steps (Enforce of particles/rigid_body_constraint.h calls them in this order): Start, Mismatch
// (the cold start), AddParticularForces (neutral particles), WarmStart, Solve,
// RecoverNeutralMotion, Mismatch (the true residual). Stopping rule: <g, g>_G <= threshold (given
// by the caller); throws SolverNotConverged on a breakdown (curvature <= 0) or after
// max_iterations. OpenMP (from kParallelParticles particles on; below, the barriers cost more than
// the work): one parallel region for the whole CG, the per-particle loops and the per-slot gathers
// shared between the threads; every sum is taken per particle (four running sums) and then over the
// particles in a fixed order, so the result does not depend on the thread count (no atomics).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"
#include "dlmfd/particles/component_pair.h"
#include "dlmfd/particles/coupling_operator.h"
#include "dlmfd/particles/multiplier_points.h"
#include "dlmfd/particles/multiplier_preconditioner.h"
#include "dlmfd/particles/rigid_modes.h"

namespace dlmfd {

// The operators of (37) that the CG composes, for one step (owned by RigidBodyConstraint).
struct ConstraintOperators {
  const MultiplierPoints& points;    // the stacking and the product G
  const CouplingOperator& coupling;  // E and dt M^-1 E^T
  const RigidModes& modes;           // C, -dt D^-1 C^T and P
};

class MultiplierCg {
 public:
  // The CG runs on the OpenMP threads from this many particles on. One CG iteration costs about
  // 3.5 us per particle (D = 0.2, h_p = 1/70) and has 4 barriers; with OMP_WAIT_POLICY=passive
  // (the setting for shared machines) a barrier is a futex wake-up of 5-50 us, so fewer particles
  // than this lose more at the barriers than they gain.
  static constexpr std::size_t kParallelParticles = CouplingOperator::kParallelParticles;

  MultiplierCg() = default;
  // For the stacked points of points and at most max_slots slots of E^T; preconditioned: the
  // block-Jacobi preconditioner K (particles/multiplier_preconditioner.h) in place of G.
  MultiplierCg(const MultiplierPoints& points, std::size_t max_slots, int max_iterations,
               bool preconditioned);

  // The iterate at the predictor: (U, omega) = (U*, omega*) of the particles, nu = 0.
  void Start(const std::vector<ParticleState>& particles);
  // g = E u - C (U, omega) of the iterate at every point.
  void Mismatch(const ConstraintOperators& op, const double* u, const double* v);
  // g = a given mismatch (stacked, two per point): the right side of a response solve.
  void SetMismatch(const double* g) { std::copy(g, g + g_.size(), g_.begin()); }
  // g += shift (2 per point, stacked): the constraint held on E u + shift.
  void ShiftMismatch(const double* shift) {
    for (std::size_t k = 0; k < g_.size(); ++k) g_[k] += shift[k];
  }
  // max over the points of |g_k|.
  double MaxMismatch() const;
  // g = P g.
  void ProjectMismatch(const ConstraintOperators& op) {
    op.modes.ProjectMismatch(op.points, g_.data());
  }
  // nu = G C S^-1 (net_force[p], net_torque[p]) on every neutral particle p (net_force nullptr:
  // none; net_torque nullptr: zero torques), and u, (U, omega) and g follow.
  void AddParticularForces(const ConstraintOperators& op, double dt, const Vec2* net_force,
                           const double* net_torque, double* u, double* v);
  // <g, g>_G.
  double MismatchNorm2(const ConstraintOperators& op) { return GramDot(op, g_.data(), g_.data()); }
  // Adds the stored multipliers of the particles (less their net force and torque on a neutral
  // particle) when that leaves <g, g>_G below gg; then gg is the new value and true is returned.
  bool WarmStart(const ConstraintOperators& op, double dt,
                 const std::vector<ParticleState>& particles, double* u, double* v, double& gg);
  // CG from the residual g with <g, g>_G = gg until gg <= threshold, then u and v take the fluid
  // update. Returns the iteration count; time names the step in errors. Throws
  // SolverNotConverged.
  int Solve(const ConstraintOperators& op, double time, double dt, double threshold, double& gg,
            double* u, double* v);
  // For the neutral particles: (U, omega) = the G-weighted rigid part of E u.
  // <g_s, g_s>_G of the response g_s of the particles' stored multipliers: the mismatch they hold,
  // the scale of an increment's stopping rule (0 when none is stored).
  double StoredResponseNorm2(const ConstraintOperators& op, double dt,
                             const std::vector<ParticleState>& particles);
  void RecoverNeutralMotion(const ConstraintOperators& op, const double* u, const double* v);

  Vec2 Velocity(std::size_t p) const { return velocity_[p]; }
  double AngularVelocity(std::size_t p) const { return omega_[p]; }
  // The stacked nodal forces nu.
  const double* Forces() const { return nu_.data(); }
  // The block preconditioner (its counts; unused with the product G alone).
  const MultiplierPreconditioner& Preconditioner() const { return preconditioner_; }

 private:
  // The response to nodal forces dir, in three parts: the rigid response (velocity_b_, omega_b_) of
  // particle p; the fluid response uvb_ = dt M^-1 E^T dir at the slots (CouplingOperator::
  // Spread); gb_ = P (E uvb - Ub - omegab r_perp) at the points of particle p.
  void RigidResponseOf(const ConstraintOperators& op, std::size_t p, double dt, const double* dir);
  void ResponseMismatchOf(const ConstraintOperators& op, std::size_t p);
  void Respond(const ConstraintOperators& op, double dt, const double* dir);  // all three
  // nub_ = the particles' stored multipliers (projected), gb_ = their response; false if none.
  bool RespondToStored(const ConstraintOperators& op, double dt,
                       const std::vector<ParticleState>& particles);
  // g = E u - U - omega r_perp at the points of particle p.
  void MismatchOf(const ConstraintOperators& op, std::size_t p, const double* u, const double* v);
  // The iterate takes the last response: u += ub, v += vb, U += Ub, omega += omegab.
  void TakeResponse(const ConstraintOperators& op, double* u, double* v);
  double GramDot(const ConstraintOperators& op, const double* a, const double* b);  // stacked
  // z = K r (preconditioned) or G r on particle p's block (r, z: stacked arrays).
  void PreconditionOf(const ConstraintOperators& op, std::size_t p, const double* r, double* z);
  // K's blocks for this step's E, unless current.
  void Factor(const ConstraintOperators& op, double dt);
  void ApplyGram(const ConstraintOperators& op, const double* a, double* out) const;
  // The iterations on (g_, nub_ = the direction of nu) from rho = <g, z> (z = K g or G g);
  // returns false on a breakdown (curvature <= 0) with the curvature in *curvature_out. Updates
  // nu_, duv_, velocity_, omega_, gg, iterations.
  bool ConjugateGradients(const ConstraintOperators& op, double dt, double threshold, double rho,
                          double& gg, int& iterations, double* curvature_out);

  int max_iterations_ = 0;
  bool parallel_ = false;  // the CG runs on the OpenMP threads (enough particles)
  bool preconditioned_ = false;
  MultiplierPreconditioner preconditioner_;
  // Stacked point arrays, 2 per point.
  std::vector<double> nu_, g_, w_, nub_, gb_, scratch_, gram_g_;
  // Per slot, u and v side by side: the fluid response and the accumulated CG update of the fluid
  // velocity.
  std::vector<double> uvb_, duv_;
  // Per particle: its part of a stacked sum.
  std::vector<double> partial_, partial_gg_, partial_rho_;
  std::vector<Vec2> velocity_, velocity_b_;
  std::vector<double> omega_, omega_b_;
};

}  // namespace dlmfd
