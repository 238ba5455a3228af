// The block-Jacobi preconditioner of the multiplier CG of (37): each particle's own block of the
// Schur complement, factored exactly, so that the CG's iteration count no longer depends on where
// a particle's points sit in the grid's cells (nor on the number of particles).
//
// Why: the response A = P (E dt M^-1 E^T + C dt D^-1 C^T) of particles/multiplier_cg.h has, for
// points on cell centres (a disk's lattice when its centre sits in a cell), near-null modes (the
// checkerboard that the four 1/4 weights hide from the nodes); unpreconditioned, the CG took 6 / 13
// / 24 iterations a step at 0, 1/4, 1/2 of a cell off a node at h = 1/32 and 7 / 17 / 47 at h =
// 1/48 (docs/evidence/validation_particles.md, "A multiplier solve whose cost does not depend on
// sub-grid position").
// Blocks: A couples two particles only through fluid nodes that both their stencils reach, so
// A = diag(A_p) + (those couplings), and per particle p, with B_p = E_p dt M^-1 E_p^T (a sparse
// symmetric matrix of the points, the same for both velocity components: B_p[k][l] = sum over the
// slots s of both stencils of w_ks dt w_ls / m_s, from E and E^T's lists by slot) and C_p its rigid
// modes (particles/rigid_modes.h):
//   fixed or prescribed (D^-1 = 0):  K_p r = B_p^-1 r;
//   heavy free:   A_p = B_p + C dt D^-1 C^T, by Woodbury
//                 K_p r = B_p^-1 r - Y T^-1 Y^T r,  Y = B_p^-1 C,  T = D / dt + C^T Y;
//   neutral free: A_p on ker(C^T) -> range(P): K_p r solves B_p z + C mu = r, C^T z = 0, which is
//                 the same formula with T = C^T Y (D = 0); C^T K_p r = 0, and P B_p K_p r = r for r
//                 in range(P) (any G: P = I - C S^-1 C^T G), so K_p is A_p's inverse there.
// K = diag(K_p) is symmetric and positive on the CG's space, and replaces G in the CG's direction
// update (the unpreconditioned CG is the CG preconditioned by G); the stopping rule stays
// <g, g>_G. An isolated particle's block is the whole operator, so the CG takes one iteration to
// the tolerance (two with round-off); particles that share nodes take a few more.
// Factorisation: Eigen's SimplicialLDLT of B_p in an approximate minimum degree order found on the
// particle's first factorisation and kept, per particle on the OpenMP threads from
// kParallelParticles particles on. B_p depends only on the particle's stencils (fluid nodes and
// weights: the masses are the nodes'), dt and, through the Woodbury term, its points and rigid
// modes; each Build of E (CouplingOperator::BuildCount) compares them with those of the last
// factorisation: unchanged (a fixed particle; a second Build at the same positions), the block is
// kept; the same nodes reached by E^T with other weights (a particle that moved within its
// stencils' cells), the numeric factorisation alone is redone on the kept symbolic analysis; other
// nodes (a weight of exactly 0 leaves its node out of E^T), both. Either
// way K_p is exactly this Build's, so the answer does not depend on what was kept.
// B_p is positive definite when the points' stencils are independent; where a pivot is <= 0 (more
// points than nodes in some stencils) that particle's block of K is G, the unpreconditioned CG's.
// Cost: a factorisation costs about 10 to 25 unpreconditioned iterations (h = 1/32 to 1/48), and a
// moving particle's weights change every step, so it pays where the CG was dear (a centre in a
// cell) and not where it was cheap (a quarter cell off; the lagged multiplier of a moving bed):
// opt-in (solvers.multiplier_preconditioner = "blocks") until it is cheaper
// (docs/evidence/validation_particles.md, "A multiplier solve whose cost does not depend on
// sub-grid position").
// References: Saad, Iterative Methods for Sparse Linear Systems (2003), 10.1 (block Jacobi) and 9.2
// (the preconditioned CG in a non-Euclidean product); Woodbury (1950).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include "dlmfd/particles/coupling_operator.h"
#include "dlmfd/particles/multiplier_points.h"
#include "dlmfd/particles/rigid_modes.h"

namespace dlmfd {

class MultiplierPreconditioner {
 public:
  MultiplierPreconditioner() = default;
  explicit MultiplierPreconditioner(std::size_t particles)
      : blocks_(particles) {}

  // Whether the blocks are those of the coupling's last Build.
  bool Current(const CouplingOperator& coupling) const {
    return built_ && build_ == coupling.BuildCount();
  }
  void MarkBuilt(const CouplingOperator& coupling) {
    build_ = coupling.BuildCount();
    built_ = true;
  }
  // Particle p's block for this step's E (after CouplingOperator::Build) and dt: kept, or factored
  // again where its stencils, dt or points changed (see the header).
  void BuildOf(const MultiplierPoints& points, const CouplingOperator& coupling,
               const RigidModes& modes, std::size_t p, double dt);
  // The numeric factorisations of blocks, and the symbolic analyses among them, since construction
  // (a count for the tests and the measurements).
  std::uint64_t Factorisations() const;
  std::uint64_t Analyses() const;
  // Whether particle p's B_p was positive definite (else its block of K is G: the CG as before).
  bool Factored(std::size_t p) const { return blocks_[p].factored; }
  // z = K_p r on particle p's block (r, z: its stacked values, 2 per point).
  void ApplyOf(const MultiplierPoints& points, std::size_t p, const double* r, double* z);

 private:
  struct Block {
    // B_p in the order of a minimum-degree permutation found once (on the first factorisation).
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>>
        factor;
    std::vector<int> order, point_of;  // point k -> row order[k]; row i -> point point_of[i]
    std::vector<int> column_start, rows, mark, touched;  // B_p's lower part, compressed; scratch
    std::vector<double> values, row;
    // What B_p and the Woodbury term were built from (the stencils' nodes, kNoSlot where E^T
    // leaves an entry out, and weights, in entry order; dt; the points relative to the centre),
    // and how often.
    std::vector<std::uint32_t> nodes;
    std::vector<double> weights;
    std::vector<Vec2> points;
    double dt = 0.0;
    std::uint64_t factorisations = 0, analyses = 0;
    bool factored = false;        // B_p positive definite
    bool rigid = false;           // heavy or neutral: the Woodbury term
    Eigen::VectorXd one, rx, ry;  // B^-1 of 1, -r_y and r_x (the columns of Y, per component)
    Eigen::Matrix3d t_inverse;    // T^-1
    Eigen::MatrixXd in, out;      // scratch: both components, in row order
  };
  // The minimum-degree order of B_p's pattern (from triplets, once per particle).
  void Order(const MultiplierPoints& points, const CouplingOperator& coupling, std::size_t p,
             Block& block) const;
  static constexpr std::uint32_t kNoSlot = 0xffffffffu;
  // What changed since the block's last factorisation (and records the new stencils, dt, points).
  enum class Change { kNone, kWeights, kNodes };
  Change Compare(const MultiplierPoints& points, const CouplingOperator& coupling, std::size_t p,
                 double dt, Block& block) const;
  // B_p from E's stencils and E^T's slot lists, in row order, lower part.
  void Assemble(const MultiplierPoints& points, const CouplingOperator& coupling, std::size_t p,
                Block& block) const;
  void Woodbury(const MultiplierPoints& points, const RigidModes& modes, std::size_t p, double dt,
                Block& block) const;

  std::vector<Block> blocks_;
  std::uint64_t build_ = 0;
  bool built_ = false;
};

}  // namespace dlmfd
