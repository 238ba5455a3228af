// Step (34) of the paper by the wave-like equation method of Dean and Glowinski, followed by an
// implicit diffusion step: the advection part d_t u + (V.grad) u = 0, with V = u^{n+1/4} frozen
// (discretely solenoidal after (33)), is replaced by the equivalent second-order problem
//   d_tt u - div((V.grad u) V) = 0,  u(0) = u^{n+1/4},  d_t u(0) = -(V.grad) u^{n+1/4},
// u = u_Gamma on Dirichlet sides and (V.n)(d_t u + V.grad u) = 0 on the rest (method notes 1, end
// of section 4). Then (rho/dt) M_l (u^{n+2/4} - u_adv) + nu_b K u^{n+2/4} = 0 with nu_b = beta
// eta_N (one fast solve per component; skipped when beta = 0); eta_N = fluid.NewtonianViscosity(),
// eta_s with a modelled polymer and the whole eta without one (core/params.h).
//
// Discrete method: lumped mass M_l, K_V = int (V.grad phi_i)(V.grad phi_j) with the exact P1
// integral W_T = int_T V V^T = |T|/12 (sum_k V_k V_k^T + S S^T) per triangle (S the sum of the
// vertex values); centred explicit sub-steps tau = dt / Q,
//   M (u^{q+1} - 2 u^q + u^{q-1}) / tau^2 + K_V u^q + M_out (V.n)^+ (u^{q+1} - u^{q-1}) / (2 tau) =
//   0,
// started by u^1 = u^0 + tau u_t + tau^2/2 u_tt with u_t = -M^-1 N(V, u^0). Q is the smallest count
// with max|V| tau / h <= solvers.wave_max_courant (a uniform flow is stable up to 1/sqrt(2)
// across the mesh diagonals and sqrt(2/3) along the axes: advection_wave.cc).
// Outflow sides: M_out is the lumped boundary mass; at nodes where V.n < 0 (backflow through an
// outflow side) no data exist and the boundary term is dropped (the wave reflects there).
// No linear solve in the advection part, so no iteration count: the report gives the sub-steps.
// With domain.diagonals = "both", K_V and N(V, .) are the means of these forms on the mesh's
// triangles (a, b, c), (a, c, d) and on the NW-SE triangles (a, b, d), (b, c, d) of each square,
// all four gathered in one sweep (K_V: each cell's share of its corners' rows; N: the gradient
// sums of fem_operators.h): the step then commutes with the mirrors x -> -x and y -> -y, at twice
// the arithmetic of the forms and the same passes over memory. Its stability bound is the
// SW-NE mesh's: the symbols are the means of the two meshes' (mirror images of each other, so with
// the same bound), and the condition sigma^2 <= kappa (1 - c^2 kappa / 4) is convex in the pair.
//
// Steady-state correction (splitting.steady_correction = "taylor"): for any count Q the step maps
// u^0 to u^0 + dt u_t + (dt^2/2) u_tt + O(dt^3), so at a fixed point of the Lie splitting the
// implicit step (33) sees (u - u_adv)/dt = M^-1 N(V, u) + (dt/2) M^-1 (K_V u + M_out u_t): the
// steady solution is that of the equations with an extra streamline diffusion (dt/2) (V.grad)^2 u,
// of size dt |V|^2 / 2 (docs/evidence/validation.md, cavity section). The correction adds
// theta (dt^2/2) M^-1 (K_V u^0 + M_out u_t) back to u_adv, node by node with
//   theta = min(1, kappa nu_N / (dt |V|^2 / 2)),  kappa = 1/2,  nu_N = eta_N / rho,
// so the fixed point solves the steady equations to O(dt^2) wherever dt |V|^2 / 2 <= nu_N / 2.
// Where it is removed in full the advection alone is a forward-Euler step (unstable on its own);
// the implicit viscosity of (33) damps a Fourier mode by 1 / (1 + nu dt k^2) and the removed term
// grows it by at most 1 + theta dt^2 |V|^2 k^2 / 2 <= 1 + kappa nu dt k^2, so with kappa < 1 the
// pair stays stable. That is a constant-coefficient argument, assuming the central advection
// symbol is bounded by the Laplacian's; no test checks it. Measured: the stability limits of the
// Newtonian runs did not move, while a polymer's did (docs/evidence/splitting.md, "The splitting's
// steady-state error").
//
// Tendency correction (splitting.steady_correction = "tendency"; docs/evidence/splitting.md, "The
// splitting's fixed point"): the Taylor correction's cap leaves part of the term where the
// streamline diffusion exceeds nu_N / 2 (near a lid, a disk, at Re 1000), and with Q > 1 the
// sub-steps add O(dt^3) terms that do not vanish at a steady state. Here the step integrates the
// whole frozen tendency, d_t u = L u + r, L u = -M^-1 N(V, u), r = (u^{n+1/4} - u^n) / dt the
// tendency of step (33) (viscous, pressure, polymer and lagged multiplier forces; u^n given by
// BeginStep), as the wave equation
//   M u_tt + K_V u + M_out (u_t - r) + N(V, r) = 0,  u(0) = u^{n+1/4},  u_t(0) = L u(0) + r,
// and returns u(dt) - dt r: to first order the plain advection, but every higher Taylor term acts
// on the full tendency q = L u + r, which vanishes at a steady state. One discrete difference
// remains: u_tt(0) = -M^-1 (K_V u + M_out L u) + L r, whose compact form of (V.grad)^2 u differs
// from the wide one L(L u) by eps = O(h^2) (a fourth-order damping, V^2 h^2 d^4 / 4 along V: what
// keeps the Lax-Wendroff step stable without viscosity). The step removes phi (dt^2/2) eps after
// the sub-steps, node by node with phi = min(1, kappa C nu_N h^2 / (dt^3 |V|^4)), C = 13.8 the
// bound below which the wide form with the implicit viscosity of (33) is stable (von Neumann,
// constant V: bench/wave_tendency_stability.py), kappa = 1/2. Where phi = 1 the second-order term
// is L q, and a fixed point of the splitting has q = 0 at every unknown: (33)'s velocity u^{n+1/4}
// solves the discrete steady equations whatever dt and Q (the written velocity, core/simulation.cc;
// u^{n+1} = u^{n+1/4} - dt r is O(dt) from it). Exact with beta = 0 (the default); the diffusion
// part of (34) with beta > 0 is still split. Cost: two more G a component (of r and of L u), a copy
// of u^n a step.
//
// References: Dean & Glowinski, C. R. Acad. Sci. Paris 325 (1997) 789-797; Glowinski, Pan, Hesla,
// Joseph & Periaux, J. Comput. Phys. 169 (2001) 363-426.
#pragma once

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

class AdvectionWave final : public VelocityAdvection {
 public:
  AdvectionWave(const Grid& grid, const DomainParams& domain, const FluidParams& fluid, double beta,
                SteadyCorrection correction, const SolverParams& solvers,
                const BoundaryData& boundary_data);
  ~AdvectionWave() override;
  AdvectionWave(const AdvectionWave&) = delete;
  AdvectionWave& operator=(const AdvectionWave&) = delete;

  // In: u, v = u^{n+1/4}. Out: u, v = u^{n+2/4} after dt. report.iterations = wave sub-steps Q.
  AdvectionReport Solve(double dt, double* u, double* v) override;
  void BeginStep(const double* u, const double* v) override;
  // wave_substeps.
  void Record(const AdvectionReport& result, StepReport& report) const override;

 private:
  // W_T / h^2 per triangle of the cells: a, b the SW-NE pair (a, b, c), (a, c, d), or the NW-SE
  // pair (a, b, d), (b, c, d).
  struct TriangleWeights {
    std::vector<double> w11a, w12a, w22a, w11b, w12b, w22b;
  };
  // With "both": the mean of the four triangles' K_V in each cell as the symmetric 3 x 3 matrix M
  // on the differences (u_b - u_a, u_c - u_a, u_d - u_a) that gives the shares of b, c, d (a's is
  // minus their sum: K_V's rows and columns sum to zero).
  struct CellMatrix {
    std::vector<double> bb, bc, bd, cc, cd, dd;
  };
  // dt and the diffusion's (rho/dt) M_l + nu_b K for a step of dt, rebuilt when dt changes.
  void PrepareStep(double dt);
  void FreezeVelocity(const double* u, const double* v);  // W_T per triangle from V
  void ComputeWeights(const double* vx, const double* vy);
  void ApplyWaveStiffness(const double* u, const double* v, double* ku, double* kv);  // K_V
  // K_V on the SW-NE triangles.
  void ApplyMeshWaveStiffness(const double* u, const double* v, double* ku, double* kv);
  // The mean of K_V on the SW-NE and the NW-SE triangles (domain.diagonals = "both").
  void ApplyMeanWaveStiffness(const double* u, const double* v, double* ku, double* kv);
  // Copies the last cell column / row of each padded cell array into its ghost on a periodic side.
  void FillPeriodicGhosts(std::vector<double>* const* cells, int count);
  void RemoveTaylorTerm();  // u1_, v1_ -= theta (dt^2/2) u_tt (steady-state correction)

  Grid grid_;
  BoundaryTopology topo_;
  MeshDiagonals diagonals_;
  NodeSet nodes_;
  double density_, nu_b_, max_courant_;
  double dt_ = 0.0, rho_over_dt_ = 0.0;  // of the last step (PrepareStep); 0 before the first
  double taylor_viscosity_;              // kappa nu_N with the correction, 0 without
  const BoundaryData& boundary_data_;
  std::unique_ptr<SeparableHelmholtz> helmholtz_;  // (rho/dt) M_l + nu_b K; null when nu_b == 0
  std::vector<double> mass_, out_mass_;  // lumped mass; outflow boundary mass (V.n)^+ M_out
  std::vector<double> vx_, vy_;          // frozen V
  TriangleWeights weights_;              // the SW-NE triangles (domain.diagonals = "sw_ne")
  CellMatrix mean_;                      // domain.diagonals = "both"
  // Fluxes F_T per SW-NE triangle (padded cells; the mesh's diagonals only).
  std::vector<double> f1xu_, f1yu_, f2xu_, f2yu_, f1xv_, f1yv_, f2xv_, f2yv_;
  // With "both": each padded cell's share of the rows of its corners a, b, c, d, for u then v.
  std::vector<double> corners_[8];
  std::vector<double> u0_, v0_, u1_, v1_, ku_, kv_, gx_, gy_;
  std::vector<double> utt_u_, utt_v_;  // u_tt of the start, kept for the correction
  bool tendency_ = false;
  bool entry_set_ = false;           // BeginStep since the last Solve
  double wide_viscosity_ = 0.0;      // kappa C nu_N h^2 (tendency only)
  std::vector<double> ru_, rv_;      // u^n at BeginStep, then the Stokes tendency r
  std::vector<double> srcu_, srcv_;  // M_out r - N(V, r)
  std::vector<double> epsu_, epsv_;  // phi eps: the share of the compact-minus-wide term removed
  int outflow_normal_[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
  bool outflow_[4] = {false, false, false, false};
};

}  // namespace dlmfd
