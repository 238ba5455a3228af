// The exact velocity solve of the cut-cell operator by a capacitance matrix (issue 33 point 4;
// docs/evidence/cut_cell_boundary.md, "The time loop's cost"): the fast solver of the uniform
// operator A_0 = a M_l + b K (solvers/separable_helmholtz.h) plus a dense solve of rank k, k the
// number of rows in which the cut operator differs from the uniform one (the unknowns next to the
// cut elements, a few hundred at D/h = 20).
// The cut operator A acts on the active unknowns; extend it to every unknown of the fast solver by
// the uniform rows at the inactive nodes (inside a body): A_e = [[A, 0], [A_0,ia, A_0,ii]] (active,
// inactive), block lower-triangular, so A_e [x; y] = [f; 0] gives x = A^-1 f. Then
//   A_e = A_0 + P C,   P = [e_s1 ... e_sk],   C = the k nonzero rows of A_e - A_0,
// and by the Sherman-Morrison-Woodbury formula
//   A_e^-1 f = w - A_0^-1 P y,   w = A_0^-1 f,   (I_k + C A_0^-1 P) y = C w.
// The capacitance matrix I_k + C A_0^-1 P is built once (k fast solves) and factorised (dense LU);
// a solve is two fast solves, a sparse product over the k rows and a dense k x k solve. Exact for
// fixed bodies; a moving body changes P and C every step.
// References: Buzbee, Dorr, George & Golub, SIAM J. Numer. Anal. 8 (1971) 722-736 (the
// capacitance matrix of a fast Poisson solver on irregular regions); Proskurowski & Widlund, Math.
// Comp. 30 (1976) 433-468; Hager, SIAM Rev. 31 (1989) 221-239 (the Woodbury formula).
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <vector>

#include "dlmfd/solvers/separable_helmholtz.h"

namespace dlmfd {

class CutCellCapacitance {
 public:
  // difference: A_e - A_0 over the velocity nodes of the fast solver's grid (full node indices;
  // nonzero only in rows and columns of unknown nodes). Entries below `drop` times the largest
  // entry are the two assemblies' round-off and are left out. The fast solver must outlive this.
  CutCellCapacitance(const SeparableHelmholtz& fast, const Eigen::SparseMatrix<double>& difference,
                     double drop);

  // Solves A_e (u, v) = (fu, fv) (full node arrays, f read at the unknown nodes; u and v are 0 at
  // the other nodes on return, and hold the extension's values at inactive ones). The two
  // components side by side (SeparableHelmholtz::SolvePair).
  void SolvePair(const double* fu, double* u, const double* fv, double* v);

  int Rank() const { return static_cast<int>(rows_.size()); }

 private:
  const SeparableHelmholtz& fast_;
  std::vector<int> rows_;                                  // s_1 ... s_k
  Eigen::SparseMatrix<double, Eigen::RowMajor> coupling_;  // C: k x n
  Eigen::PartialPivLU<Eigen::MatrixXd> capacitance_;       // I_k + C A_0^-1 P
  std::vector<double> zero_, tu_, tv_, cu_, cv_;           // work
  Eigen::MatrixXd y_;                                      // work: k x 2
};

}  // namespace dlmfd
