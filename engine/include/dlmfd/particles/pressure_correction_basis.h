// The cut-cell step's pressure corrections of earlier steps, and the start they give the next
// step's Uzawa / CG (particles/cut_cell_stokes.h; issue 32 point 5).
//
// Around fixed bodies the Schur complement S = B A^-1 B^T + G_p / phi_p of step (33) is the same
// operator at every step of one dt, and only its right side c moves. Each step's CG finds a
// correction dp of the start p^n (S dp = r_0, the start's residual); kept S-orthonormal,
//   q_i (q_i^T S q_j = delta_ij),  S q_i,  A^-1 B^T q_i,
// they give the next step's start the Galerkin correction in their span at no Stokes solve:
//   a_i = q_i^T r,   p += sum a_i q_i,   u -= sum a_i A^-1 B^T q_i,   r -= sum a_i S q_i,
// the S-norm's best start in p^n + span{q_i}, which holds the extrapolations of p from the last
// steps (p^n + (p^n - p^{n-1}) among them). This is Fischer's projection for the pressure of
// successive time steps (P. F. Fischer, Comput. Methods Appl. Mech. Engrg. 163 (1998) 193-204),
// with the corrections (not the solutions) kept, as the start p^n is already the last solution.
// A correction enters after its step's CG, S-orthonormalised against the basis by classical
// Gram-Schmidt done twice; S dp and A^-1 B^T dp come from the CG's recurrences (r_0 - r, u_0 - u),
// no solve. A full basis starts over with the newest correction alone.
// Memory: kCapacity x (2 velocity unknowns + 2 pressure unknowns) doubles.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "dlmfd/core/state.h"

namespace dlmfd {

class PressureCorrectionBasis {
 public:
  static constexpr int kCapacity = 16;

  int Count() const { return static_cast<int>(data_.q.size()); }
  // What a checkpoint keeps (core/state.h), and the basis again from it.
  const PressureCorrections& Data() const { return data_; }
  void Restore(PressureCorrections data) { data_ = std::move(data); }
  // Forgets the basis: S changed (the forms, the unknowns or dt).
  void Clear();
  // The Galerkin start in p + span{q_i} for the residual r = c - S p of p, with the velocity
  // u = A^-1 (f - B^T p) that goes with it.
  void Project(Eigen::VectorXd& p, Eigen::VectorXd& u, Eigen::VectorXd& r) const;
  // A step's correction dp with s = S dp and w = A^-1 B^T dp.
  void Add(Eigen::VectorXd dp, Eigen::VectorXd s, Eigen::VectorXd w);

 private:
  PressureCorrections data_;
};

}  // namespace dlmfd
