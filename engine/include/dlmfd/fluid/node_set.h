// The unknown nodes of a grid under a boundary topology, as the fluid solvers need them: Euclidean
// dot products over unknowns only (dual residuals live there), zeroing of the known (Dirichlet and
// periodic-duplicate) entries, and copying of the first periodic column/row onto its duplicate.
// Kernels are OpenMP loops over the node arrays; nothing allocates after construction.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/mesh/boundary_topology.h"

namespace dlmfd {

class NodeSet {
 public:
  NodeSet(const Grid& grid, const BoundaryTopology& topo);

  std::size_t size() const { return unknown_.size(); }
  // 1 at unknown nodes, 0 elsewhere.
  const std::vector<double>& unknown() const { return unknown_; }
  // 1 at every distinct node (periodic duplicates 0): weights of integrals of full fields.
  const std::vector<double>& distinct() const { return distinct_; }
  bool IsUnknown(std::size_t id) const { return unknown_[id] != 0.0; }

  // sum over unknown nodes of a b.
  double Dot(const double* a, const double* b) const;
  // sum over unknown nodes of (a1 b1 + a2 b2).
  double Dot2(const double* a1, const double* b1, const double* a2, const double* b2) const;
  // Sets the entries of non-unknown nodes to zero.
  void ZeroKnown(double* x) const;
  // Copies each periodic first node onto its duplicate.
  void SyncPeriodic(double* x) const;
  // max over distinct nodes of sqrt(u^2 + v^2).
  double MaxNorm(const double* u, const double* v) const;

 private:
  std::vector<double> unknown_;
  std::vector<double> distinct_;
  std::vector<std::pair<std::size_t, std::size_t>> duplicates_;  // (duplicate, first)
};

}  // namespace dlmfd
