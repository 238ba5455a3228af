#include "dlmfd/fluid/node_set.h"

#include <algorithm>
#include <cmath>

#include "dlmfd/core/ordered_sum.h"

namespace dlmfd {

NodeSet::NodeSet(const Grid& grid, const BoundaryTopology& topo)
    : unknown_(grid.NodeCount(), 0.0),
      distinct_(grid.NodeCount(), 1.0) {
  const bool px = topo.x.low == EndKind::kPeriodic;
  const bool py = topo.y.low == EndKind::kPeriodic;
  for (int j = 0; j <= grid.ny; ++j) {
    for (int i = 0; i <= grid.nx; ++i) {
      const std::size_t id = grid.Index(i, j);
      unknown_[id] = topo.IsUnknown(grid, i, j) ? 1.0 : 0.0;
      const int fi = (px && i == grid.nx) ? 0 : i;
      const int fj = (py && j == grid.ny) ? 0 : j;
      if (fi != i || fj != j) {
        distinct_[id] = 0.0;
        duplicates_.emplace_back(id, grid.Index(fi, fj));
      }
    }
  }
}

double NodeSet::Dot(const double* a, const double* b) const {
  const long n = static_cast<long>(unknown_.size());
  const double* w = unknown_.data();
  return OrderedSum(n, [=](long k) { return w[k] * a[k] * b[k]; });
}

double NodeSet::Dot2(const double* a1, const double* b1, const double* a2, const double* b2) const {
  const long n = static_cast<long>(unknown_.size());
  const double* w = unknown_.data();
  return OrderedSum(n, [=](long k) { return w[k] * (a1[k] * b1[k] + a2[k] * b2[k]); });
}

void NodeSet::ZeroKnown(double* x) const {
  const long n = static_cast<long>(unknown_.size());
  const double* w = unknown_.data();
#pragma omp parallel for schedule(static)
  for (long k = 0; k < n; ++k) x[k] = w[k] != 0.0 ? x[k] : 0.0;
}

void NodeSet::SyncPeriodic(double* x) const {
  for (const auto& [dup, first] : duplicates_) x[dup] = x[first];
}

double NodeSet::MaxNorm(const double* u, const double* v) const {
  const long n = static_cast<long>(unknown_.size());
  double m = 0.0;
#pragma omp parallel for reduction(max : m) schedule(static)
  for (long k = 0; k < n; ++k) m = std::max(m, u[k] * u[k] + v[k] * v[k]);
  return std::sqrt(m);
}

}  // namespace dlmfd
