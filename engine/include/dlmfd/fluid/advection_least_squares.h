// Step (34) of the paper by the least-squares conjugate gradient method of Bristeau, Glowinski and
// Periaux: find u = u^{n+2/4} with u = u_Gamma on the Dirichlet sides and, at every unknown node,
//   T_c(u) = (rho/dt) M_l (u_c - u*_c) + rho N_c(u, u) + nu_b K u_c = 0,   c = x, y,
// where u* = u^{n+1/4}, nu_b = beta eta_N, N_c(a, b) = a_x (G_x b_c) + a_y (G_y b_c) the convection
// by vertex (trapezoidal) quadrature, consistent with the lumped mass (method notes 1, section 4).
// eta_N = fluid.NewtonianViscosity(): eta_s with a modelled polymer, the whole eta without one.
//
// Solver: minimise J(u) = 1/2 <P^-1 T(u), T(u)> with P = (rho/dt) M_l + nu_b K (fast solver; the
// diagonal (rho/dt) M_l when nu_b = 0) by Polak-Ribiere CG (restart when the coefficient is
// negative) with the exact line search along w: T(u - l w) = T0 - l T1 + l^2 T2 is quadratic in l,
// so J is a quartic whose stationary points are the real roots of a cubic; the root with the lowest
// J is taken. 6 scalar fast solves per iteration, 4 to start. Stopping rule: sqrt(g.r / g0.r0) <=
// tol (solvers.advection_tolerance; 1e-3 is ample for this first-order splitting, notes section 4).
// The gradient T'(u)^T y uses G^T z = -G z + (boundary integral of z phi n) on outflow sides, exact
// for every boundary kind (the boundary term vanishes where y = 0 and on periodic sides).
// With domain.diagonals = "both", G is the mean of the SW-NE and NW-SE triangulations' (the
// identity above holds for each, so for the mean), and the step commutes with the mirrors x -> -x,
// y -> -y. Throws SolverNotConverged after advection_max_iterations.
//
// Steady-state correction (splitting.steady_correction = "taylor", not the default here): the step
// is backward Euler, u = u* - dt M^-1 N(u, u), so at a fixed point of the splitting the Stokes
// step (33) sees (u* - u)/dt = M^-1 N(u, u) = M^-1 N(u*, u*) + dt M^-1 K_V u* + O(dt^2), a
// streamline diffusion dt |u|^2 (twice the wave-like step's). The correction adds theta dt M^-1
// (N(u, u) - N(u*, u*)) to the result, node by node with theta = min(1, kappa nu_N / (dt |u*|^2)),
// kappa = 1/2, the cap of fluid/advection_wave.h, so that (33) sees M^-1 N(u*, u*) where the cap
// allows. Tendency correction (splitting.steady_correction = "tendency", see advection_wave.h):
// the step solves backward Euler for the whole frozen tendency, T_c(u) - rho M_l r_c = 0 with r the
// tendency of step (33), (u^{n+1/4} - u^n) / dt (u^n given by BeginStep), and returns u - dt r;
// backward Euler's fixed point is exact, so at a steady state u = u^{n+1/4} and that velocity
// solves the discrete steady equations whatever dt, with beta > 0 too (no cap). Not supported: the
// symmetric-gradient viscous form (see StokesSolver). References: Bristeau, Glowinski & Periaux,
// Comput. Phys. Rep. 6 (1987) 73-187; Glowinski (2003), section 26.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/fluid/node_set.h"
#include "dlmfd/fluid/velocity_advection.h"
#include "dlmfd/mesh/boundary_topology.h"
#include "dlmfd/solvers/separable_helmholtz.h"

namespace dlmfd {

class AdvectionLeastSquares final : public VelocityAdvection {
 public:
  AdvectionLeastSquares(const Grid& grid, const DomainParams& domain, const FluidParams& fluid,
                        double beta, SteadyCorrection correction, const SolverParams& solvers,
                        const BoundaryData& boundary_data);
  ~AdvectionLeastSquares() override;
  AdvectionLeastSquares(const AdvectionLeastSquares&) = delete;
  AdvectionLeastSquares& operator=(const AdvectionLeastSquares&) = delete;

  // In: u, v = u^{n+1/4}. Out: u, v = u^{n+2/4} after dt.
  AdvectionReport Solve(double dt, double* u, double* v) override;
  void BeginStep(const double* u, const double* v) override;
  // advection_iterations, advection_residual.
  void Record(const AdvectionReport& result, StepReport& report) const override;

  // Exposed for tests. The step, dt and u*, is the last Solve's (or set by SetReference); the
  // operators below are T's of that step. P = (rho/dt) M_l + nu_b K is built for its dt and rebuilt
  // when a step brings another.
  void SetReference(double dt, const double* u, const double* v);
  // u += theta dt M^-1 (N(u, u) - N(u*, u*)) (the steady-state correction, see above).
  void RemoveBackwardEulerTerm(double* u, double* v);
  // out = T(u) (zero at known nodes).
  void Residual(const double* u, const double* v, double* out_u, double* out_v);
  // out = T'(u) w.
  void Jacobian(const double* u, const double* v, const double* wu, const double* wv, double* out_u,
                double* out_v);
  // out = T'(u)^T y (y zero at known nodes).
  void JacobianTranspose(const double* u, const double* v, const double* yu, const double* yv,
                         double* out_u, double* out_v);
  // y = P^-1 t (zero at known nodes).
  void ApplyPreconditioner(const double* tu, const double* tv, double* yu, double* yv);
  const NodeSet& nodes() const { return nodes_; }

 private:
  void GradientsOf(const double* u, const double* v);  // gxu_, gyu_, gxv_, gyv_ = G of u and v
  void AddBoundaryTransposeTerm(const double* z, int component, double* out) const;

  Grid grid_;
  BoundaryTopology topo_;
  MeshDiagonals diagonals_;  // of G (domain.diagonals)
  NodeSet nodes_;
  double rho_, nu_b_;
  double dt_ = 0.0, rho_over_dt_ = 0.0;  // of the step (SetReference); 0 before the first
  double taylor_viscosity_;              // kappa nu_N with the steady correction, 0 without
  double tolerance_;
  int max_iterations_;
  const BoundaryData& boundary_data_;
  std::unique_ptr<SeparableHelmholtz> helmholtz_;  // null when nu_b == 0
  std::vector<double> mass_;
  bool outflow_[4] = {false, false, false, false};  // by Side
  // Work arrays, two components each where paired.
  std::vector<double> su_, sv_;                  // u*
  std::vector<double> gxu_, gyu_, gxv_, gyv_;    // G of the current iterate
  std::vector<double> gxw_, gyw_, gxwv_, gywv_;  // G of w (u and v components)
  std::vector<double> t0u_, t0v_, t1u_, t1v_, t2u_, t2v_;
  std::vector<double> yu_, yv_, z1u_, z1v_, z2u_, z2v_;
  std::vector<double> ru_, rv_, gu_, gv_, wu_, wv_;
  std::vector<double> s1_, s2_, s3_, s4_;  // scratch
  bool tendency_ = false;
  bool entry_set_ = false;       // BeginStep since the last Solve
  std::vector<double> tu_, tv_;  // u^n at BeginStep, then the Stokes tendency r
};

}  // namespace dlmfd
