// Step (33) of the paper: the generalized Stokes problem of the Marchuk-Yanenko scheme,
//   rho (u^{n+1/4} - u^n)/dt - div(nu grad u^{n+1/4}) + grad p^{n+1/4} = f,  div u^{n+1/4} = 0,
// u^{n+1/4} = u_Gamma on the Dirichlet sides, nu du/dn - p n = 0 on outflow sides (do-nothing).
//
// Discrete method (method notes 1, sections 1-3): P1-iso-P2 velocity, P1 pressure on the 2h mesh.
// The viscous term alpha 2 eta_N D:D is replaced by nu grad u : grad v, nu = alpha eta_N (equal
// for solenoidal fields with Dirichlet data; it decouples u and v for the fast solver). eta_N =
// fluid.NewtonianViscosity(): eta_s = beta eta with a modelled polymer, the whole eta without one
// (a Newtonian liquid, lambda = 0 or beta = 1), so a Newtonian liquid has viscosity eta. With
// A = (rho/dt) M_l + nu K per component the system is A u - B^T p = F, B u = 0, where
// F = (rho/dt) M_l u^n + M_l f_body + (fx, fy) (the extra dual forcing: polymer stress, DLM terms).
// Gravity does not enter: the split scheme absorbs rho_L g into the pressure. B is the SW-NE
// mesh's, or with domain.diagonals = "both" the mean of the SW-NE and NW-SE triangulations'
// (inf-sup stable, mirror-symmetric: tests/unit/mesh_diagonals_test.cc); M_l, K and the
// preconditioner are the same on both.
//
// dt comes with each call, as to every step of the loop (core/simulation.cc); what depends on it
// (the fast solver of A, the floor of ref below, the flux control's unit responses) is built for
// the dt of the first call and rebuilt only when a call brings another (PrepareStep).
// Solver: Uzawa / preconditioned CG on the pressure (Glowinski), Cahouet-Chabard preconditioner
// P^-1 = nu M_p^-1 + (rho/dt) K_p^-1; each iteration 2 velocity fast solves (u and v side by side
// on two OpenMP sections), 1 pressure fast solve. Warm start from the given pressure (with the
// time loop's defect, less the predicted correction: "Warm start" below). Stopping rule:
// sqrt(r.P^-1 r) <= tol * ref with the fixed reference
//   ref = max(sqrt((rho/dt) max(|u^n|^2_M, |u^0|^2_M)), 1e-11 U_data sqrt((rho/dt) |Omega|))
// (u^0 the first velocity iterate), so sqrt(r.P^-1 r)/ref measures the non-solenoidal part of the
// velocity relative to the velocity itself; it does not depend on how good the warm start is
// (method notes 1, pitfall 5). The floor: U_data = max(|u_Gamma|, |f_body| dt / rho, G dt /
// (rho h)) is the data's velocity scale (boundary values, one step of the body force, one step of
// a polymer stress of modulus G = eta_p / lambda over one cell); a flow below 1e-11 of it is at
// rest, so a liquid at rest, whose velocity is the round-off of its data, costs no iterations
// (issue 13 point 8). Moving flows are 1e-8 and more of U_data, where the floor does not bind.
// Pressure: mean-free (M_p-weighted) when every side is Dirichlet or periodic; p = 0 on outflow
// sides. Throws SolverNotConverged after stokes_max_iterations. With domain.flow_rate the solve
// ends by holding the flow rate with the mean pressure gradient (fluid/flux_control.h).
//
// Warm start (with the time loop's defect; issue 34 point 4): p^0 = p^n - P^-1 (d^n + e^{n-1}),
// the pressure that would cancel a predicted first residual. d = B u~ is the divergence of the
// explicit velocity of the data, u~ = u^n + (dt/rho) M_l^-1 (M_l f_body + (fx, fy) - nu K u^n)
// (u^n with the data of t^{n+1}; the boundary values at the known nodes), which is A^-1 F to
// O((nu dt / h^2)^2) without a fast solve; e = r - d is its defect at the end of the last step (r
// its final residual B u^{n+1/4}, d computed without the pressure). As B^T p^n is the same in both
// steps' predictions it cancels: d^n + e^{n-1} = r^{n-1} + B (u~^n - u~^{n-1}), the last residual
// plus the predicted divergence of what the data gained since (the advection step (34), the DLM
// step's kick, the lagged multiplier, the polymer force's change). At a steady state d^n =
// d^{n-1}, so the prediction is r^{n-1}: the last residual, not a drift. The correction is taken
// only where the predicted residual sqrt(q.P^-1 q), q = d^n + e^{n-1}, is above the stopping
// rule's target with ref estimated from u^n alone (ref >= that estimate), and above the
// round-off of d, 1e-11 (kQuietFlow) of sqrt((rho/dt) |u~|_M^2): where p^n would do, p^0 = p^n as
// before, so a steady state within the tolerance, a liquid at rest and the exact flows keep their
// bits (a correction computed from round-off puts P^-1's amplification of it into the velocity:
// 8e-12 in a periodic box at rest under a body force, tests/unit/flux_control_test.cc).
// Without a defect (the first step, an older checkpoint) p^0 = p^n. Cost a step: K, B and one
// pressure solve, against a velocity pair and a B^T more for an iteration. Measured on the
// 1,000-disk bed (docs/evidence/performance.md, "A thousand particles"): the first residual 1.6e-4
// to 2.3e-4 -> 6.0e-5 to 8.8e-5 (tol 1e-4), so no Uzawa iteration a step where there was one; its
// grid alone none where it had 0.4 a step. The linear extrapolation 2 p^n - p^{n-1} was tried and
// was worse there.
//
// Not supported: the symmetric-gradient form 2 eta_N D:D (it couples the components).
// References: Glowinski, Finite element methods for incompressible viscous flow (2003), sections
// 21-22; Cahouet & Chabard, Int. J. Numer. Methods Fluids 8 (1988) 869-895.
#pragma once

#include <memory>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/fluid/flux_control.h"
#include "dlmfd/fluid/node_set.h"
#include "dlmfd/mesh/boundary_topology.h"
#include "dlmfd/solvers/separable_helmholtz.h"

namespace dlmfd {

struct StokesReport {
  int iterations = 0;
  double residual = 0.0;   // final sqrt(r.P^-1 r) / ref
  double reference = 0.0;  // ref of the stopping rule
  double divergence =
      0.0;  // sqrt(sum_Q (B u)_Q^2 / M_p,Q) over unknown Q: the L2 norm of the discrete divergence
  Vec2 mean_pressure_gradient = Vec2::Zero();  // G of domain.flow_rate (fluid/flux_control.h)
};

class StokesSolver {
 public:
  StokesSolver(const Grid& grid, const DomainParams& domain, const FluidParams& fluid, double alpha,
               const SolverParams& solvers, const BoundaryData& boundary_data);
  ~StokesSolver();
  StokesSolver(const StokesSolver&) = delete;
  StokesSolver& operator=(const StokesSolver&) = delete;

  // One step of dt. In: u, v = u^n, p = the warm start (pressure grid). fx, fy: extra dual forcing
  // at velocity nodes (already integrated against the test functions), or nullptr. Out: u, v =
  // u^{n+1/4} (boundary data written), p = p^{n+1/4}. defect (the time loop's, or nullptr): the
  // predicted warm start's defect of the last step ("Warm start" above; empty or of another size:
  // none yet, p alone), replaced by this step's.
  StokesReport Solve(double dt, const double* fx, const double* fy, double* u, double* v, double* p,
                     std::vector<double>* defect = nullptr);

  // Replaces the relative tolerance of the stopping rule (solvers.stokes_tolerance at
  // construction): the viscous coupling tightens it when its outer iteration stalls.
  void set_tolerance(double tolerance) { tolerance_ = tolerance; }

  // sqrt(r.P^-1 r) for r = B(u, v): the residual measure of the stopping rule of a step of dt (for
  // tests).
  double ResidualNorm(double dt, const double* u, const double* v);
  // The discrete divergence norm sqrt(sum (B u)^2 / M_p) of (u, v).
  double DivergenceNorm(const double* u, const double* v);

  const BoundaryTopology& velocity_topology() const { return vtopo_; }
  const BoundaryTopology& pressure_topology() const { return ptopo_; }
  const NodeSet& velocity_nodes() const { return vnodes_; }
  const NodeSet& pressure_nodes() const { return pnodes_; }
  // The flow-rate control of domain.flow_rate, or nullptr.
  const FluxControl* flux_control() const { return flux_.get(); }

 private:
  // The operators of a step of dt (header block): (rho/dt) M_l + nu K, the floor of ref and the
  // flux control's unit responses, built for the dt of the last call and rebuilt when it changes.
  void PrepareStep(double dt);
  void ApplyPreconditioner(const double* r, double* g);
  // d = B u~ of the explicit velocity u~ of the data (header block, "Warm start") into predicted_;
  // u, v = u^n, fx, fy as Solve's. Uses tu_, tv_, fu_, fv_ as scratch. Returns |u~|_M^2.
  double PredictDivergence(const double* fx, const double* fy, const double* u, const double* v);
  void RemoveMean(double* p) const;                 // p in L2_0 (all sides Dirichlet or periodic)
  double WeightedSquareSum(const double* r) const;  // sum_Q M_p,Q^-1 r_Q^2 over the unknown nodes
  void SolveVelocityPair(const double* fu, const double* fv, double* u, double* v);
  std::vector<FluxControl::UnitResponse> UnitResponses() const;

  Grid grid_, pgrid_;
  BoundaryTopology vtopo_, ptopo_;
  MeshDiagonals diagonals_;  // of B and B^T (domain.diagonals)
  NodeSet vnodes_, pnodes_;
  double density_, nu_;
  Vec2 body_force_;
  double tolerance_;
  double data_speed_;       // max |u_Gamma| of the data at construction
  bool polymer_;            // a modelled polymer (not a Newtonian liquid)
  double polymer_modulus_;  // its G = eta_p / lambda
  double area_ = 0.0;       // |Omega|: sum of the lumped mass over the distinct nodes
  int max_iterations_;
  const BoundaryData& boundary_data_;
  double dt_ = 0.0;  // of the operators below; 0 before the first step
  double rho_over_dt_ = 0.0;
  double reference_floor_ = 0.0;                         // the floor of ref (header block)
  std::unique_ptr<SeparableHelmholtz> velocity_solver_;  // (rho/dt) M_l + nu K
  SeparableHelmholtz pressure_solver_;            // K_p (Neumann: mean-free; Dirichlet on outflow)
  std::vector<double> mass_, pmass_, pmass_inv_;  // pmass_: 0 at known nodes
  std::vector<double> fu_, fv_, ubar_, vbar_, tu_, tv_;  // velocity work
  std::vector<double> r_, g_, w_, sw_, z_;               // pressure work
  std::vector<double> predicted_;                        // d of the warm start
  std::unique_ptr<FluxControl> flux_;                    // domain.flow_rate only
};

}  // namespace dlmfd
