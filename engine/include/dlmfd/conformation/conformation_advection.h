// The advective part of step (35): dA/dt + u . grad A = 0 with u = u^{n+2/4} frozen,
// component-wise, keeping A symmetric positive definite (method notes 2, section 2.1, construction
// A, step 1).
//
// Discrete method, one sub-step of length tau on the node values:
//   high order A_H: SSP-RK3 (Shu-Osher) of the third-order upwind-biased differences, for u > 0
//     dA/dx ~ (A_{i-2} - 6 A_{i-1} + 3 A_i + 2 A_{i+1}) / 6h and the mirror image for u < 0 (same
//     in y);
//   low order A_L: one forward-Euler step of first-order upwind, A_L = (1 - |cx| - |cy|) A_i
//     + |cx| A_upwind-x + |cy| A_upwind-y, a convex combination when |cx| + |cy| <= 1;
//   SPD blend per node: with m_H = lambda_min(A_H), m_L = lambda_min(A_L), keep A_H when
//     m_H >= kappa m_L, else A = theta A_H + (1 - theta) A_L, theta = (1 - kappa) m_L / (m_L -
//     m_H).
//   The caller chooses tau so that (|u| + |v|) tau / h <= conformation.max_courant <= 1.
// Why A stays SPD: the SPD cone is convex, so A_L is SPD with lambda_min(A_L) >= the smallest
//   lambda_min of its stencil; lambda_min is concave, so lambda_min(theta A_H + (1 - theta) A_L) >=
//   theta m_H + (1 - theta) m_L = kappa m_L > 0 for the theta above. The blend is applied once per
//   sub-step to the SSP-RK3 result, against the SPD A_L (a non-finite A_H is replaced by A_L).
// Boundaries: two ghost layers; periodic sides wrap (the repeated last node is kept equal to the
//   first); other sides extrapolate the boundary value (constant), which is the upwind value A_L
//   at an inflow node (held fixed by the caller through SetFixed) and a zero-gradient condition on
//   walls and outflow sides, where nothing enters. The order drops to one at the boundary only.
// Not supported: non-uniform grids; Courant numbers above 1 (the caller sub-cycles).
// References: Shu & Osher, J. Comput. Phys. 77 (1988) 439; method notes 2, sections 2.1 and 2.3.
#pragma once

#include <cstddef>
#include <vector>

#include "dlmfd/conformation/sym_tensor.h"
#include "dlmfd/core/grid.h"

namespace dlmfd {

class ConformationAdvection {
 public:
  ConformationAdvection(const Grid& grid, bool periodic_x, bool periodic_y, double blend_kappa);

  // Node values that the sub-steps hold fixed (inflow data); replaces the previous list.
  void ClearFixed();
  void AddFixed(int i, int j, const SymTensor& value);

  // Copies the node arrays into the padded state and fills the ghosts.
  void Load(const double* a11, const double* a12, const double* a22);
  // One sub-step of length tau with node velocities (u, v). Returns the number of blended nodes.
  long SubStep(double tau, const double* u, const double* v);
  // Component c (0: A11, 1: A12, 2: A22) of the current state from node (0, j) on.
  const double* Row(int c, int j) const { return a_[c] + Padded(0, j); }
  // The current node value.
  SymTensor At(int i, int j) const {
    const std::size_t p = Padded(i, j);
    return SymTensor{a_[0][p], a_[1][p], a_[2][p]};
  }

  // Comparison option, for tests only: the unlimited third-order scheme (no SPD blend), which is
  // what construction A guards against.
  void DisableBlendForComparison() { blend_enabled_ = false; }
  // The blend on or off: off for the log and sqrt representations, whose advected variables need
  // not be SPD (conformation_representation.h).
  void SetSpdBlend(bool enabled) { blend_enabled_ = enabled; }

 private:
  std::size_t Padded(int i, int j) const {
    return std::size_t(j + kGhost) * std::size_t(padded_nx_) + std::size_t(i + kGhost);
  }
  void FillGhosts(double* f) const;
  void RestoreFixedAndGhosts(double* const f[3]) const;
  // out = w_base * base + w_in * (in + tau R(in)), R the third-order advection operator.
  void Stage(double tau, const double* u, const double* v, double w_base, double* const base[3],
             double w_in, double* const in[3], double* const out[3]) const;

  static constexpr int kGhost = 2;
  Grid grid_;
  bool periodic_x_, periodic_y_;
  double kappa_;
  bool blend_enabled_ = true;
  int padded_nx_, padded_ny_;
  std::vector<double> storage_;  // 9 padded arrays: A, stage 1, stage 2 (3 components each)
  double* a_[3];
  double* s1_[3];
  double* s2_[3];
  std::vector<std::size_t> fixed_index_;
  std::vector<SymTensor> fixed_value_;
};

}  // namespace dlmfd
