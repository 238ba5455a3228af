// The rigid-body constraint coupled with viscosity (splitting.constraint = "viscous", issue 13
// point 2; method note particle-coupling.md, section 2b): the Stokes step (33) solved with the
// particles in it, so that the constraint meets the implicit viscosity and the pressure at once and
// the flow cannot leak through a particle within a step, whatever nu dt / h^2.
//
// Equations, for the particles at X^n (free heavy particles with the unknown xi = (U, omega),
// fixed and prescribed ones with xi given), nu the nodal forces at the multiplier points:
//   (rho/dt) M (u - u^n) + nu_N K u - B^T p = f + E^T nu,   B u = 0,
//   D (xi - xi^n)/dt = (m_e g, 0) - C^T nu,   E u = C xi   (rigid at every multiplier point),
// with M, K, B of step (33) (fluid/stokes_solver.h), E, C, D = diag(m_e, m_e, j_e) of step (37)
// (particles/rigid_body_constraint.h). The excess weight m_e g of the heavy free particles acts
// here, where the drag resists it (ParticleStep's predictor (36) then carries the collision forces
// only): a particle at its terminal speed meets no gravity kick that (37) would share with the
// liquid around it without viscosity. Steps (34)-(38) then follow as in the paper: the DLM step
// (37) with gamma = 0 corrects what advection and the collisions changed. The hydrodynamic force
// adds -C^T nu of this step to that of (37) (ParticleStep).
//
// Solve: (u, p) depend on nu through the Stokes solution operator, u = L(u^n + dt M^-1 E^T nu)
// (rho M^-1 E^T nu enters as a velocity increment). The mismatch g = E u - C xi is affine in nu
// with the Schur complement S = E L0 E^T + dt C D^-1 C^T (L0: (33) with zero data), symmetric and
// positive semidefinite (null space: forces whose spreading is a discrete gradient; the pressure
// takes them and nothing moves, the net force and torque included). PCG on S nu = -g(0) with the
// preconditioner P^-1, P = dt E M^-1 E^T + dt C D^-1 C^T the Schur complement of the paper's (37),
// inverted by its CG (RigidBodyConstraint::SolveResponse, relative tolerance kInnerTolerance). As
// L0 <= dt (rho M)^-1, the spectrum of P^-1 S lies in (0, 1], the small end set by how much
// viscosity resists a force over dt (about 1 / (1 + nu_N dt / h^2) on the finest multiplier modes).
// Polak-Ribiere directions, so the inexact inner solve does not stall the outer one.
// Per iteration: one Stokes solve with zero data (the same Uzawa/PCG, relative to its own
// response), one inner CG of (37)'s size, two fluid-sized updates.
// Warm start: the previous step's nu, for every particle with the ring mesh, and for the fixed
// particles only with the collocation points (WarmStarts). A moving disk's collocation points move
// against the grid, and carried over they made the PCG diverge after a few steps (suspected, not
// established: the interior points give S many more null directions, spreadings that are discrete
// gradients, and the carried nu seeds them); started cold a falling disk converges every step
// (ViscousCoupling.CollocationPointsConvergeEveryStep). A fixed disk's points keep their place, and
// its flow is where the cold start costs most: the interior lattice points' constraints, nearly
// redundant with the boundary's where viscosity dominates, make S ill-conditioned against P.
// Warm-started, a fixed disk's later steps take 0-1 iterations
// (ViscousCoupling.FixedDiskWarmStartsWithCollocationPoints). With every particle fixed the PCG
// also keeps its last directions and starts each step from their Galerkin correction
// (particles/recycled_directions.h). The iteration counts behind these choices:
// docs/evidence/constraint_coupling.md, "The viscous coupling with collocation points, measured".
// Stopping rule: max over the points
// of |E u - C xi| <= tol V, tol = solvers.multiplier_tolerance, V the velocity scale of the step
// (max |u| after the first Stokes solve, and |U| + |omega| R of every particle); throws
// SolverNotConverged after solvers.multiplier_max_iterations. A stall (kStallWindow) tightens the
// coupled Stokes solves a hundredfold and restarts from the current nu: the looser solves' errors
// make S nu = -g inconsistent (kCollocationStokesShare) and leave a floor under the mismatch. Not
// supported: neutrally buoyant free particles (validation rejects them: their velocity would be a
// multiplier of the net-force constraint); a warm start across a resume (the stored nu is not
// checkpointed: the first step after a resume starts cold and agrees to the tolerance). References:
// Glowinski, Pan, Hesla, Joseph, Periaux, J. Comput. Phys. 169 (2001) 363-426 (the constraint with
// viscosity, gamma > 0, solved by Uzawa/CG on the multiplier); Glowinski, Finite element methods
// for incompressible viscous flow (2003), section 21 (Uzawa/PCG).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/fluid/stokes_solver.h"
#include "dlmfd/particles/recycled_directions.h"
#include "dlmfd/particles/rigid_body_constraint.h"

namespace dlmfd {

class ViscousConstraint {
 public:
  // Relative tolerance of the inner (37) solves that apply P^-1.
  static constexpr double kInnerTolerance = 1e-6;
  // With collocation points the coupled Stokes solves (the first one and the responses) stop at
  // a tolerance of at most this share of solvers.multiplier_tolerance. Their interior points make
  // S singular: a multiplier whose spreading is a discrete gradient B^T q (q at the pressure nodes
  // inside the disk) moves nothing, and the right side's component along it is q . B u_0, the
  // divergence the first Stokes solve leaves. PCG on that inconsistent system grows along the null
  // space once it asks for less mismatch than the divergence allows (Schaefer-Turek's fixed disk
  // diverged at a share of 1 and 0.1, converged at 1e-2; the ring mesh's sparser points complete at
  // 1: docs/evidence/constraint_coupling.md, "The viscous coupling with collocation points,
  // measured").
  static constexpr double kCollocationStokesShare = 1e-2;
  // A stall of the outer PCG: kStallWindow iterations in which the mismatch never fell below
  // kStallGain times its best value so far. It multiplies the coupled Stokes solves' tolerance by
  // kTightening for the rest of that step and restarts from the current nu (the next step starts
  // again from StokesSettings: the cold start is where the stalls were seen, and a tolerance kept
  // tight for the run cost 1.46 times the Stokes iterations a step of the confined cylinder;
  // docs/evidence/constraint_coupling.md, "The viscous coupling's cost"), while the tolerance stays
  // >= kStokesToleranceFloor (one tightening from the collocation points' 1e-6, two from the
  // ring mesh's 1e-4). Without the rule three of eight sub-grid positions of a creeping fixed disk
  // failed at step 0; the measurements are in docs/evidence/constraint_coupling.md, "The viscous
  // coupling with collocation points, measured".
  static constexpr int kStallWindow = 50;
  static constexpr double kStallGain = 0.9;
  static constexpr double kTightening = 1e-2;
  static constexpr double kStokesToleranceFloor = 1e-9;
  // The solver settings of the Stokes solves coupled with the constraint (kCollocationStokesShare).
  static SolverParams StokesSettings(const Params& params);
  // Whether a particle's block of nu is carried to the next step as its warm start: always with
  // the ring mesh; with the collocation points only when the particle is fixed (see above).
  static bool WarmStarts(ParticleMeshKind kind, Motion motion);
  // The advice of the non-convergence error: with collocation points it names the coupled Stokes
  // solves' tolerance (their inexact solutions make S nu = -g inconsistent, see above) first, with
  // its value at the failure (stokes_tolerance: after any tightening).
  static std::string RemedyText(ParticleMeshKind kind, double stokes_tolerance);

  struct Outcome {
    int iterations = 0;             // outer PCG iterations
    int stokes_iterations = 0;      // Uzawa iterations of every Stokes solve of the step
    double stokes_residual = 0.0;   // the Uzawa residual of the first Stokes solve
    double residual = 0.0;          // max |E u - C xi| over the points, relative to V
    double divergence = 0.0;        // the discrete divergence norm of the final u
    double stokes_tolerance = 0.0;  // the coupled Stokes solves' tolerance at the end of the step
    Vec2 mean_pressure_gradient = Vec2::Zero();  // G of domain.flow_rate (fluid/flux_control.h)
  };

  ViscousConstraint(const Params& params, const Grid& grid);
  ~ViscousConstraint();

  // Step (33) with the constraint: on entry u, v = u^n, p = the warm start, particles at (X^n,
  // U^n, omega^n); on return u, v, p solve the coupled problem and the free particles hold xi.
  // stokes: the solver of (33) (data of t^{n+1}); fx, fy: its extra dual forcing (the polymer's)
  // or nullptr. time = t^{n+1} for errors. Throws SolverNotConverged, ParticlesOverlap.
  // gravity: g, acting on the excess mass of the heavy free particles.
  Outcome Solve(double time, double dt, const Vec2& gravity, StokesSolver& stokes, const double* fx,
                const double* fy, std::vector<ParticleState>& particles, double* u, double* v,
                double* p);

  // C^T nu of the last Solve for particle p: the force and torque it exerted on the fluid nodes.
  Vec2 NodalForceSum(std::size_t p) const { return force_sum_[p]; }
  double NodalTorqueSum(std::size_t p) const { return torque_sum_[p]; }

 private:
  // From the step's entry state in u, v, p (u^n and the pressure's warm start; a restart copies
  // them back from u_in_, v_in_, p_in_) and the particles' entry velocities: adds the carried nu
  // when carry (its velocity increment and the particles' response) and solves (33). The start of
  // the outer iteration, and its restart after a stall.
  StokesReport Start(double dt, bool carry, StokesSolver& stokes, const double* fx,
                     const double* fy, double* u, double* v, double* p);
  // r = E u - C xi at every point, for fields (u, v) and particle velocities (vel, omega); returns
  // max |r_k|.
  double MismatchOf(const double* u, const double* v, const std::vector<Vec2>& vel,
                    const std::vector<double>& omega, double* r) const;
  // (du, dv) = L0 (dt M^-1 E^T dir), (dvel, domega) = -dt D^-1 C^T dir; returns Uzawa iterations.
  int Respond(double dt, const double* dir);
  double Dot(const double* a, const double* b) const;
  // After the warm start: adds the recycled directions' Galerkin correction to nu, u, v, p and the
  // particles' velocities, unless it does not lower the mismatch; returns the mismatch (r_ holds
  // its vector).
  double StartFromRecycled(double* u, double* v, double* p, Vec2& gradient);

  RigidBodyConstraint inviscid_;  // E, C, D and P^-1
  DomainParams zero_domain_;      // the sides of the scene with zero data
  BoundaryData zero_data_;
  std::unique_ptr<StokesSolver> response_solver_;  // (33) with zero data and no body force
  double tolerance_;
  int max_iterations_;
  double base_stokes_tolerance_;  // of the coupled Stokes solves at a step's start: StokesSettings
  double stokes_tolerance_;       // the same, tightened on a stall for the rest of that step
  std::vector<double> u_in_, v_in_, p_in_;  // the step's entry state, for a restart
  std::vector<Vec2> velocity_in_;
  std::vector<double> omega_in_;
  std::vector<Vec2> velocity_, dvelocity_;
  std::vector<double> omega_, domega_;
  std::vector<ParticleState> scratch_particles_;  // the particles at xi, for the inner solves
  // Stacked point vectors (2 per point): nu, residual, previous residual, preconditioned residual,
  // direction, S direction.
  std::vector<double> nu_, r_, r_old_, z_, d_, sd_;
  std::vector<double> slot_uv_;  // dt M^-1 E^T dir at the slots (u and v side by side)
  std::vector<double> du_, dv_, dp_, su_, sv_;  // fluid-sized: response, its pressure, scratch
  Vec2 dgradient_ = Vec2::Zero();  // the response's mean pressure gradient (domain.flow_rate)
  std::vector<Vec2> force_sum_;
  std::vector<double> torque_sum_;
  bool have_warm_ = false;
  bool recycles_ = false;  // RecycledDirections::Used: every particle fixed
  RecycledDirections recycled_;
  double recycled_dt_ = 0.0;      // the dt of the stored directions' S
  std::vector<char> heavy_free_;  // per particle: free and heavier than the liquid (gets m_e g)
};

}  // namespace dlmfd
