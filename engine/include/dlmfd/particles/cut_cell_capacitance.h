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
// a solve is two fast solves, a sparse product over the k rows and a dense k x k solve. The second
// fast solve, A_0^-1 P y = sum_s y_s A_0^-1 e_s, is a sum of the k responses where they are kept
// (CutCellLocalResponses below): they decay away from their row, by a factor of about
// exp(-acosh(1 + a h^2 / (2 b))) a cell along the axes (0.15 at nu dt / h^2 = b / (a h^2) = 0.2),
// so that with a mass term they stand above round-off on a patch of nodes (about 1000 at nu dt /
// h^2 = 0.2), not on the whole grid. Exact for
// fixed bodies; a moving body changes P and C every step. Its columns A_0^-1 e_s depend on the row
// s only (A_0 does not move), so a moving body keeps them between steps (CutCellResponses): a step
// makes fast solves only for the rows that enter the cut band, then forms C A_0^-1 P and factorises
// it (docs/evidence/cut_cell_boundary.md, "A body in prescribed motion").
// References: Buzbee, Dorr, George & Golub, SIAM J. Numer. Anal. 8 (1971) 722-736 (the
// capacitance matrix of a fast Poisson solver on irregular regions); Proskurowski & Widlund, Math.
// Comp. 30 (1976) 433-468; Hager, SIAM Rev. 31 (1989) 221-239 (the Woodbury formula).
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <cstddef>
#include <unordered_map>
#include <vector>

#include "dlmfd/solvers/separable_helmholtz.h"

namespace dlmfd {

// The fast solver's responses to unit loads, A_0^-1 e_s (full node arrays), kept between the
// capacitance matrices of a moving body's steps: n doubles a row held. Each also with its entries
// above the unit round-off times its largest (CutCellLocalResponses::EntriesOf, found once, when
// it is made) where they are at most n / kLocalShare: a moving body's capacitance solve then sums
// them instead of its second fast solve, as a fixed body's does (12 bytes an entry).
class CutCellResponses {
 public:
  static constexpr std::size_t kLocalShare = 8;  // at most n / kLocalShare entries a response
  explicit CutCellResponses(const SeparableHelmholtz& fast)
      : fast_(fast) {}
  // Holds A_0^-1 e_s for every s of rows, by fast solves two at a time for the ones not held (in
  // the order of rows), and forgets the others. Returns the number of fast solves made.
  int Update(const std::vector<int>& rows);
  const std::vector<double>& Of(int s) const { return held_.at(s).full; }
  // The entries of A_0^-1 e_s above round-off (index, value), or false where it has more than
  // n / kLocalShare (then both are empty).
  bool Local(int s, const std::vector<int>** index, const std::vector<double>** value) const;

 private:
  struct Held {
    std::vector<double> full;
    std::vector<int> index;
    std::vector<double> value;
    bool local = false;
  };
  const SeparableHelmholtz& fast_;
  std::unordered_map<int, Held> held_;
  std::vector<std::vector<double>> spare_;  // arrays of rows that left, for new ones
  void Hold(int s, std::vector<double> full);
};

// The responses A_0^-1 e_s of the capacitance rows, each without its entries at or below the unit
// round-off times its largest (those are below the fast solver's own round-off on that response:
// its transforms spread an error of that size over every node). The correction A_0^-1 P y is then
// sum_s y_s r_s over the kept entries, the same up to round-off as the fast solve of P y. They are
// kept only while they have at most kEntriesPerNode entries a node of the grid in all; beyond,
// the sum would cost more than half the fast solve (a fast solve pair costs about 450 instructions
// a node, the sum about 16 an entry for both components: callgrind, Schaefer-Turek at D/h = 20,
// docs/evidence/cut_cell_boundary.md, "The fixed body's step: the second fast solve as a sum of
// responses"). Creeping flows (nu dt / h^2 of 1 and more) keep the fast solve. A moving body's
// solves sum too, from the entries its held responses keep (CutCellResponses: found once, when a
// response is made, not every step).
class CutCellLocalResponses {
 public:
  static constexpr int kEntriesPerNode = 16;
  explicit CutCellLocalResponses(std::size_t nodes)
      : nodes_(nodes),
        budget_(kEntriesPerNode * nodes) {}
  // The entries of a response (a full node array of `nodes`) above the unit round-off times its
  // largest, in the order of the nodes; false (and index, value cut short) beyond `cap` of them.
  static bool EntriesOf(const double* response, std::size_t nodes, std::size_t cap,
                        std::vector<int>& index, std::vector<double>& value);
  // Appends the next response (a full node array); false, and forgets all, once over the budget.
  bool Add(const double* response);
  // The same with a response's entries (EntriesOf's).
  bool Append(const std::vector<int>& index, const std::vector<double>& value);
  void Clear();  // forgets all: the fast solve is used
  bool Kept() const { return kept_; }
  // u -= sum_s ys[s] r_s, v -= sum_s zs[s] r_s.
  void SubtractPair(const double* ys, const double* zs, double* u, double* v) const;
  void Subtract(const double* ys, double* u) const;  // u -= sum_s ys[s] r_s
  std::size_t Entries() const { return value_.size(); }

 private:
  std::size_t nodes_, budget_;
  bool kept_ = true;
  std::vector<std::size_t> start_{0};
  std::vector<int> index_;
  std::vector<double> value_;
};

class CutCellCapacitance {
 public:
  // difference: A_e - A_0 over the velocity nodes of the fast solver's grid (full node indices;
  // nonzero only in rows and columns of unknown nodes). Entries below `drop` times the largest
  // entry are the two assemblies' round-off and are left out. The fast solver (and responses) must
  // outlive this. With responses, the columns A_0^-1 e_s are taken from it (Update with the rows);
  // without, they are solved for here and not kept (the same bits).
  CutCellCapacitance(const SeparableHelmholtz& fast, const Eigen::SparseMatrix<double>& difference,
                     double drop, CutCellResponses* responses = nullptr);

  // Solves A_e (u, v) = (fu, fv) (full node arrays, f read at the unknown nodes; u and v are 0 at
  // the other nodes on return, and hold the extension's values at inactive ones). The two
  // components side by side (SeparableHelmholtz::SolvePair).
  void SolvePair(const double* fu, double* u, const double* fv, double* v);
  // One field: A_e x = f, by one fast solve and a second or the kept responses' sum.
  void Solve(const double* f, double* x);

  int Rank() const { return static_cast<int>(rows_.size()); }
  int FastSolvesAtSetUp() const { return set_up_solves_; }  // responses made by the constructor
  // Whether a solve sums the kept responses instead of its second fast solve.
  bool LocalCorrection() const { return local_.Kept(); }

 private:
  const SeparableHelmholtz& fast_;
  std::vector<int> rows_;       // s_1 ... s_k
  std::vector<int> dirichlet_;  // the fast solver's Dirichlet nodes (zeroed before a solve)
  Eigen::SparseMatrix<double, Eigen::RowMajor> coupling_;  // C: k x n
  Eigen::PartialPivLU<Eigen::MatrixXd> capacitance_;       // I_k + C A_0^-1 P
  std::vector<double> zero_, tu_, tv_, cu_, cv_;           // work
  Eigen::MatrixXd y_;                                      // work: k x 2
  CutCellLocalResponses local_;                            // r_s of s_1 ... s_k, if kept
  int set_up_solves_ = 0;
};

}  // namespace dlmfd
