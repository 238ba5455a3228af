// The cut-cell boundary of fixed bodies (issue 33; docs/evidence/cut_cell_boundary.md, "A
// second-order boundary"): the generalized Stokes problem of step (33), optionally with an Oseen
// term, on the fluid part of the uniform mesh only, the no-slip condition on the bodies imposed
// weakly by Nitsche's method on the chords of the cut elements (particles/cut_cell_geometry.h):
//   find u (P1-iso-P2, active nodes), p (P1 on the 2h macro-triangles, active nodes) with
//   (rho/dt) (u, v)_l + rho ((w . grad) u, v) + eta (grad u, grad v) - (p, div v) + (q, div u)
//   - eta <d_n u, v> - eta <d_n v, u> + gamma eta / h <u, v> + <p, v . n> - <q, u . n>
//   + g_u eta h sum_F [d_n u][d_n v] - g_p H^3 / phi_p sum_F [d_n p][d_n q] = (f, v)
// (n out of the fluid; the chord terms by two-point Gauss; volume terms over the fluid polygons;
// the last two are ghost penalties on the faces of cut h-triangles and cut macro-triangles, which
// keep small cuts well conditioned; (.,.)_l the lumped mass of the fluid part). H = 2h, and
// phi_p = eta + (rho/dt) H^2: with the mass term the Schur complement on the grid's scale is
// M_p / phi_p (Cahouet-Chabard's model below, K_p ~ M_p / H^2 there; Massing, Schott & Wall
// 2018's scaling without its Oseen part). Over eta alone the penalty was 42 times that on
// Schaefer-Turek at D/h = 9.76, dt = h, and 0.47 points of its +1.29 % drag
// (docs/evidence/cut_cell_boundary.md, "The pressure ghost penalty's scale"). The bodies are at
// rest (boundary value zero) unless SetBodyMotion gives each its rigid motion g = U + omega x
// (x - X) on its chords: the right side then carries Nitsche's consistent terms
//   - eta <d_n v, g> + gamma eta / h <g, v>   (momentum),   - <q, g . n>   (continuity)
// (a body in prescribed motion, particles/cut_cell_step.h; docs/evidence/cut_cell_boundary.md, "A
// body in prescribed motion"). Domain sides as in step (33): Dirichlet data on walls and velocity
// sides, do-nothing outflow (p = 0 there), periodic sides periodic (the geometry's periodic axes
// must be the domain's; the elements next to a periodic side couple across it). Without an outflow
// side p is fixed by a zero mean over the fluid part (B^T 1 = 0). A steady problem (rho/dt = 0)
// needs a Dirichlet velocity side (the fast solver is the capacitance matrix's base). The viscous
// form is eta grad u : grad v, as in the engine's step (33). On one triangulation (the paper's
// SW-NE) or on both, every form then the mean of the two.
//
// Solver. The velocity block A without the Oseen term is solved exactly by its capacitance matrix
// against the fast solver of (rho/dt) M_l + eta K on the whole uniform grid (particles/
// cut_cell_capacitance.h: built once, two fast solves and a dense solve of rank about 3 x 3 pi D/h
// an application, the second fast solve a sum of kept responses where a mass term makes them
// local). Without an Oseen term the saddle point [[A, B^T], [B, -G_p / phi_p]] is then
// solved by Uzawa / preconditioned CG on the pressure (Glowinski, as the default step (33),
// fluid/stokes_solver.h): u = A^-1 (f - B^T p) exactly, CG on the Schur complement B A^-1 B^T +
// G_p / phi_p (symmetric positive definite) with Cahouet-Chabard's S~^-1 = eta M_p^-1 + (rho/dt)
// K~^-1, M_p the lumped pressure mass of the fluid part plus eta / phi_p times the pressure ghost
// penalty's diagonal (a pressure node with a small cut support gets a small M_p: with the whole
// cell's mass the iterations at D/h = 10 / 20 were 211 / 389 against 104 / 130). K~ = K_p +
// (rho/dt) / phi_p G_p, K_p the pressure's P1 stiffness over the fluid part (the Schur complement
// is about (dt/rho) K~ where the mass term rules), solved by a capacitance matrix against the fast
// solver of the whole grid's K_p (rank: the pressure nodes of the cut macro-triangles); with a
// moving body, or without a Dirichlet pressure side, the whole grid's K_p (the fast solver alone).
// The fluid part's took the Uzawa iterations of Schaefer-Turek 2D-1 over t = 5 from 2300 to 1464
// at D/h = 9.76 and from 2165 to 1578 at D/h = 19.5 (docs/evidence/cut_cell_boundary.md, "The Uzawa
// step's cost at D/h = 19.5"). The CG starts from the given pressure plus the Galerkin correction
// in the span of the earlier solves' corrections (Fischer's projection, particles/
// pressure_correction_basis.h: S is the same until the operators change), which took them on to
// 708 and 758 (docs/evidence/cut_cell_boundary.md, "The Uzawa start from the earlier steps'
// corrections"). Stopping rule: the saddle point's relative residual |rhs - K x|_2
// <= tolerance |rhs|_2, as GMRES's; Uzawa forms its continuity part only (the momentum part is the
// exact velocity solves' round-off); a free body's solves also stop on its load (LoadStop, below).
// Cost and iterations: docs/evidence/cut_cell_boundary.md, "The time loop's cost". With an
// Oseen term (or SetExactVelocityPreconditioner): restarted GMRES on the saddle point,
// right-preconditioned by the block upper triangle [[A~, B^T], [0, -S~]] (z_p = -S~^-1 r_p, then
// z_u = A~^-1 (r_u - B^T z_p)), A~^-1 the exact Stokes solve above or the Oseen velocity block's
// own factorization. The force on a body is read from the momentum residual of the fluid forms
// (Nitsche and ghost terms left out) with a test function equal to 1 at the nodes within 1.5 h of
// the body's boundary and inside it: F = -sum_i Phi_i (rho (w . grad) u + eta K u - B^T p)_i (the
// discrete stress integrated over a closed line in the fluid around the body; steady flows).
// References: Burman & Hansbo, Appl. Numer. Math. 62 (2012) 328-341 (fictitious domain Stokes,
// ghost penalty); Massing, Larson, Logg & Rognes, J. Sci. Comput. 61 (2014) 604-628 (Nitsche for
// Stokes on cut meshes); Cahouet & Chabard, Int. J. Numer. Methods Fluids 8 (1988) 869-895;
// Glowinski, Finite element methods for incompressible viscous flow (2003), sections 21-22;
// Massing, Schott & Wall, Comput. Methods Appl. Mech. Engrg. 328 (2018) 262-300 (arXiv:1611.02895;
// the ghost penalties' scaling functions).
#pragma once

#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/particles/cut_cell_geometry.h"

namespace dlmfd {

// The method's constants, declared once. The ghost penalties are the smaller pair of the study
// (docs/evidence/cut_cell_boundary.md, "A second-order boundary"): the penalty is most of the
// drag's error and 0.1 / 0.01 miss 0.3 % at D/h = 20. g_p multiplies H^3 / phi_p (header), which
// is the study's H^3 / eta in its steady problems.
struct CutCellConstants {
  double nitsche = 20.0;          // gamma
  double ghost_velocity = 0.01;   // g_u
  double ghost_pressure = 0.001;  // g_p
  // g_u with a polymer that is elastic on the grid's scale (particles/cut_cell_step.h: g_u =
  // ghost_velocity + (ghost_velocity_elastic - ghost_velocity) (1 - w), w the devss weight, so g_u
  // -> ghost_velocity as lambda -> 0): with 0.01 the confined cylinder at Wi = 0.6, R/h = 24 blew
  // up at step 550-630 of 1800, with 0.1 it ran (docs/evidence/cut_cell_boundary.md, "The polymer
  // around fixed bodies").
  double ghost_velocity_elastic = 0.1;
  int restart = 120;  // GMRES restart length (80: 2.1 times the iterations at D/h 40)
  // Step (33) in the time loop (particles/cut_cell_step.h): the saddle point's relative residual
  // and the iteration limit; the loosest tolerance at which Schaefer-Turek's C_D no longer moves
  // (docs/evidence/cut_cell_boundary.md, "A second-order boundary: the time loop").
  double step_tolerance = 1e-7;
  int step_max_iterations = 2000;
  // A free body's solves (the step's first and the one at V, particles/cut_cell_step.h) also stop
  // on its load (CutCellStokes::LoadStop): an iteration changes its force by at most this times
  // its load scale (the largest of its weight less buoyancy, the last step's load less buoyancy
  // and the viscous load of its motion, particles/cut_cell_step.h).
  double free_load_tolerance = 1e-4;
  // The unit solves of a free body's coupling matrix K (particles/cut_cell_free_bodies.h) where the
  // step's solution does not come from them (the step then solves at V, started from their
  // composition): their relative residual. 1e-5 / 1e-4 / 1e-3 took them from 15.0 Uzawa
  // iterations a step to 9.3 / 5.9 / 3.2 on the 5.2 pair and moved its velocities over 100 steps
  // by 3.3e-9 / 6.1e-9 / 2.2e-6 of their largest (docs/evidence/cut_cell_boundary.md, "A stopping
  // rule on the body's load" and "Where a free step's CPU goes"); with the solve at V started
  // from the kept unit solutions, 1e-4 -> 1e-3 took them from 7.0 to 4.6 a step and moved the
  // velocities by 1.8e-8 ("The solve at V started from the kept unit solutions").
  double unit_tolerance = 1e-3;
  // Cahouet-Chabard's Laplacian over the fluid part (header; fixed bodies with a Dirichlet pressure
  // side), or the whole grid's as a moving body's steps use (false: tests that compare the two).
  bool fluid_pressure_laplacian = true;
};

// A body's rigid motion: the boundary value U + omega x (x - X) on its chords.
struct RigidMotion {
  Vec2 centre = Vec2::Zero();       // X
  Vec2 velocity = Vec2::Zero();     // U
  double angular_velocity = 0.0;    // omega
  Vec2 At(const Vec2& arm) const {  // at x = X + arm
    return velocity + angular_velocity * Vec2(-arm.y(), arm.x());
  }
};

struct CutCellReport {
  int iterations = 0;
  double relative_residual = 0.0;
  int unknowns = 0;
};

class CutCellStokes {
 public:
  // rho_over_dt >= 0 (0: steady), viscosity > 0, density (of the Oseen term) >= 0.
  CutCellStokes(const CutCellGeometry& geometry, const DomainParams& domain, double viscosity,
                double density, double rho_over_dt, const CutCellConstants& constants = {});
  // The mean of every form on the SW-NE and the NW-SE triangulations (the counterpart of
  // domain.diagonals = "both": mirror-symmetric). The geometries must outlive the solver.
  CutCellStokes(const CutCellGeometry& sw_ne, const CutCellGeometry& nw_se,
                const DomainParams& domain, double viscosity, double density, double rho_over_dt,
                const CutCellConstants& constants = {});
  ~CutCellStokes();
  CutCellStokes(const CutCellStokes&) = delete;
  CutCellStokes& operator=(const CutCellStokes&) = delete;

  // The geometries have changed in place (a body in prescribed motion, particles/cut_cell_step.h):
  // the forms, the unknowns and the capacitance matrix anew for them, at the cost of the band.
  // The forms are the uniform grid's (assembled at the first call) plus the correction of the
  // triangles cut by or inside the bodies (the same up to round-off), updated in place in the
  // columns of the last band and of the new one only (the rest of the grid's forms do not change:
  // the same bits as the whole sums); the fast solvers are kept, and the capacitance matrix's
  // columns A_0^-1 e_s are kept for the rows that stay in the band (fast solves for the new rows
  // only: CapacitanceFastSolves; n doubles a row held). What stays of the order of the grid: B and
  // B^T over the unknowns, copied from the forms in one pass over their entries (the unknowns'
  // numbering moves as nodes enter and leave the liquid), and scans of the grid's nodes. The Oseen
  // term and the bodies' motion are cleared (SetBodyMotion after).
  void Recut();
  // Precondition the velocity block by its own sparse factorization instead of the fast solvers
  // (steady Oseen problems, which the Laplacian does not precondition).
  void SetExactVelocityPreconditioner(bool exact);
  // The earlier solves' pressure corrections that start a solve's Uzawa CG (particles/
  // pressure_correction_basis.h; forgotten whenever the operator is built anew), and the same
  // again, read from a checkpoint, for the same operator. Throws InvalidParameter when their sizes
  // are not the unknowns'.
  const PressureCorrections& Corrections() const;
  void RestoreCorrections(PressureCorrections corrections);
  // The rigid motion of every body of the geometry (indexed as its bodies), or an empty vector for
  // bodies at rest (the default): the boundary value g of Nitsche's terms (header).
  void SetBodyMotion(const std::vector<RigidMotion>& motions);
  // The advecting velocity w of the Oseen term (full node arrays), or nullptr for none.
  void SetAdvection(const double* wu, const double* wv);
  // A stopping rule on some bodies' loads (Load, below), besides the residual's: Uzawa stops only
  // once its last iteration has changed each listed body's force by at most force_bound and its
  // torque about its centre by at most torque_bound, and makes at least one iteration (the change
  // of an iteration is the estimate of the load's error; a free body's solves, particles/
  // cut_cell_step.h). GMRES (an Oseen term) ignores it.
  struct LoadStop {
    std::vector<int> bodies;
    std::vector<Vec2> centres;
    std::vector<double> force_bound, torque_bound;
  };
  // Solves with the Dirichlet data of `data` and the load (fu, fv) (dual, at velocity nodes; may be
  // nullptr). u, v, p: full node arrays, the initial guess on entry (values at unknowns), the
  // solution on return (Dirichlet data written, inactive nodes 0). Throws SolverNotConverged.
  CutCellReport Solve(const BoundaryData& data, const double* fu, const double* fv, double* u,
                      double* v, double* p, double tolerance, int max_iterations,
                      const LoadStop* stop = nullptr);
  // The same by a sparse direct factorization of the whole saddle point (tests, small grids).
  void SolveDirect(const BoundaryData& data, const double* fu, const double* fv, double* u,
                   double* v, double* p);
  // The force on body `body` (header), from a solution of Solve without a load.
  Vec2 Force(int body, const double* u, const double* v, const double* p) const;
  // The force and the torque about `centre` on body `body` from a solution of Solve with the load
  // (fu, fv) (nullptr: none): F = -sum_i Phi_i R_i, T = -sum_i Phi_i (x_i - centre) x R_i with R
  // the momentum residual of the fluid forms, the mass term (rho/dt) M_l u and the load included
  // (so in a time step the inertia of the fluid near the body counts).
  struct BodyLoad {
    Vec2 force = Vec2::Zero();
    double torque = 0.0;
  };
  BodyLoad Load(int body, const Vec2& centre, const double* u, const double* v, const double* p,
                const double* fu, const double* fv) const;
  // The lumped mass of the fluid part at each velocity node (0 at nodes without fluid): the load
  // of a field f is M_l f.
  const Eigen::VectorXd& FluidMass() const;

  std::size_t NodeCount() const;  // velocity nodes of the grid
  int VelocityUnknowns() const;
  int PressureUnknowns() const;
  // k, the rank of the capacitance matrix (particles/cut_cell_capacitance.h).
  int CapacitanceRank() const;
  // The fast solves the last capacitance matrix's set-up made (k at construction; after Recut,
  // the rows new to the band).
  int CapacitanceFastSolves() const;
  // Whether a velocity solve sums the capacitance rows' responses in place of its second fast
  // solve (particles/cut_cell_capacitance.h: a mass term that makes them decay within the budget).
  bool CapacitanceSumsResponses() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Steady Navier-Stokes past fixed bodies by Picard (Oseen) iterations of CutCellStokes from the
// Stokes solution, until an Oseen solve changes the velocity by less than `change` (relative,
// 2-norm). Returns the number of solves, Stokes included; throws SolverNotConverged after
// max_picard Oseen solves. The Oseen term is left set to the last advecting velocity (Force reads
// it).
// How the Oseen solves are done: GMRES with the fast solvers (header), GMRES with the velocity
// block's own factorization as its preconditioner, or SolveDirect. With the fast solvers GMRES
// stalls on the Oseen problem of Schaefer-Turek 2D-1 at D/h = 20 (relative residual 5.6e-2 after
// 5000 iterations): the Laplacian does not precondition the channel's advection (U L / nu = 660).
enum class CutCellLinearSolver { kGmres, kGmresExactVelocity, kDirect };
int SolveSteadyNavierStokes(CutCellStokes& flow, const BoundaryData& data, double* u, double* v,
                            double* p, double tolerance, int max_iterations, double change,
                            int max_picard,
                            CutCellLinearSolver solver = CutCellLinearSolver::kGmres);

}  // namespace dlmfd
