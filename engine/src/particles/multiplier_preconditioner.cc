// The block-Jacobi preconditioner of the multiplier CG; see particles/multiplier_preconditioner.h.
#include "dlmfd/particles/multiplier_preconditioner.h"

#include <algorithm>

#include <Eigen/LU>
#include <Eigen/OrderingMethods>

namespace dlmfd {

void MultiplierPreconditioner::Order(const MultiplierPoints& points,
                                     const CouplingOperator& coupling, std::size_t p,
                                     Block& block) const {
  const std::size_t first = points.Begin(p), end = points.End(p);
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t q = first; q < end; ++q) {
    for (std::size_t e = coupling.StencilBegin(q); e < coupling.StencilBegin(q + 1); ++e) {
      const std::uint32_t slot = coupling.EntrySlot(e);
      if (slot == 0) continue;
      for (std::size_t c = coupling.SpreadBegin(slot); c < coupling.SpreadBegin(slot + 1); ++c) {
        const std::size_t l = coupling.SpreadSource(c);
        if (l < first || l >= end) continue;
        entries.emplace_back(static_cast<int>(q - first), static_cast<int>(l - first), 1.0);
      }
    }
  }
  const int n = points.Count(p);
  Eigen::SparseMatrix<double> pattern(n, n);
  pattern.setFromTriplets(entries.begin(), entries.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
  Eigen::AMDOrdering<int>()(pattern, inverse);  // Eigen's P^-1: row i <- point inverse(i)
  block.point_of.assign(inverse.indices().data(), inverse.indices().data() + n);
  block.order.assign(n, 0);
  for (int i = 0; i < n; ++i) block.order[block.point_of[i]] = i;
  block.mark.assign(n, -1);
  block.row.assign(n, 0.0);
}

void MultiplierPreconditioner::Assemble(const MultiplierPoints& points,
                                        const CouplingOperator& coupling, std::size_t p,
                                        Block& block) const {
  // Row i of B_p (point k = point_of[i]): B_p[k][l] = sum_s w_ks (dt w_ls / m_s) over the entries
  // (k, s) of E and the points l of particle p that slot s spreads to; its lower part (rows
  // order[l] >= i) is column i of the compressed lower triangle.
  const std::size_t first = points.Begin(p);
  const int n = points.Count(p);
  if (static_cast<int>(block.order.size()) != n) Order(points, coupling, p, block);
  block.column_start.assign(1, 0);
  block.rows.clear();
  block.values.clear();
  for (int i = 0; i < n; ++i) {
    const std::size_t q = first + block.point_of[i];
    block.touched.clear();
    for (std::size_t e = coupling.StencilBegin(q); e < coupling.StencilBegin(q + 1); ++e) {
      const std::uint32_t slot = coupling.EntrySlot(e);
      if (slot == 0) continue;
      const double weight = coupling.EntryWeight(e);
      for (std::size_t c = coupling.SpreadBegin(slot); c < coupling.SpreadBegin(slot + 1); ++c) {
        const std::size_t l = coupling.SpreadSource(c);
        if (l < first || l >= first + n) continue;  // another particle's point: off the block
        const int j = block.order[l - first];
        if (j < i) continue;
        if (block.mark[j] != i) {
          block.mark[j] = i;
          block.row[j] = 0.0;
          block.touched.push_back(j);
        }
        block.row[j] += weight * coupling.SpreadWeight(c);
      }
    }
    std::sort(block.touched.begin(), block.touched.end());
    for (const int j : block.touched) {
      block.rows.push_back(j);
      block.values.push_back(block.row[j]);
    }
    block.column_start.push_back(static_cast<int>(block.rows.size()));
  }
  std::fill(block.mark.begin(), block.mark.end(), -1);
}

MultiplierPreconditioner::Change MultiplierPreconditioner::Compare(const MultiplierPoints& points,
                                                                   const CouplingOperator& coupling,
                                                                   std::size_t p, double dt,
                                                                   Block& block) const {
  const std::size_t begin = coupling.StencilBegin(points.Begin(p));
  const std::size_t count = coupling.StencilBegin(points.End(p)) - begin;
  // An entry's node, or kNoSlot where E^T leaves it out (a Dirichlet node or a weight of exactly 0,
  // as a point on a grid line has): B_p's pattern is that of the slots its points share.
  const auto node_of = [&coupling](std::size_t e) {
    return coupling.EntrySlot(e) == 0 ? kNoSlot : coupling.EntryNode(e);
  };
  bool same_nodes = block.factorisations > 0 && block.nodes.size() == count;
  for (std::size_t e = 0; same_nodes && e < count; ++e) {
    same_nodes = block.nodes[e] == node_of(begin + e);
  }
  bool same = same_nodes && block.dt == dt && block.points == points.Points(p);
  for (std::size_t e = 0; same && e < count; ++e) {
    same = block.weights[e] == coupling.EntryWeight(begin + e);
  }
  if (same) return Change::kNone;
  block.nodes.resize(count);
  block.weights.resize(count);
  for (std::size_t e = 0; e < count; ++e) {
    block.nodes[e] = node_of(begin + e);
    block.weights[e] = coupling.EntryWeight(begin + e);
  }
  block.dt = dt;
  block.points = points.Points(p);
  return same_nodes ? Change::kWeights : Change::kNodes;
}

void MultiplierPreconditioner::Woodbury(const MultiplierPoints& points, const RigidModes& modes,
                                        std::size_t p, double dt, Block& block) const {
  const std::vector<Vec2>& r = points.Points(p);
  const int n = points.Count(p);
  Eigen::VectorXd ones = Eigen::VectorXd::Ones(n), minus_ry(n), plus_rx(n);
  for (int k = 0; k < n; ++k) {
    minus_ry[k] = -r[k].y();
    plus_rx[k] = r[k].x();
  }
  Eigen::MatrixXd in(n, 3);
  for (int k = 0; k < n; ++k) {
    in(block.order[k], 0) = 1.0;
    in(block.order[k], 1) = minus_ry[k];
    in(block.order[k], 2) = plus_rx[k];
  }
  const Eigen::MatrixXd out = block.factor.solve(in);
  block.one.resize(n);
  block.rx.resize(n);
  block.ry.resize(n);
  for (int k = 0; k < n; ++k) {
    block.one[k] = out(block.order[k], 0);
    block.rx[k] = out(block.order[k], 1);
    block.ry[k] = out(block.order[k], 2);
  }
  // T = D / dt + C^T Y; Y's columns: (one, 0), (0, one), (rx, ry) by component.
  Eigen::Matrix3d t = Eigen::Matrix3d::Zero();
  const double sum_one = block.one.sum();
  t(0, 0) = t(1, 1) = sum_one;
  t(0, 2) = t(2, 0) = block.rx.sum();
  t(1, 2) = t(2, 1) = block.ry.sum();
  t(2, 2) = minus_ry.dot(block.rx) + plus_rx.dot(block.ry);
  if (!modes.IsNeutral(p)) {
    t(0, 0) += 1.0 / (dt * modes.InverseExcessMass(p));
    t(1, 1) += 1.0 / (dt * modes.InverseExcessMass(p));
    t(2, 2) += 1.0 / (dt * modes.InverseExcessInertia(p));
  }
  block.t_inverse = t.inverse();
}

void MultiplierPreconditioner::BuildOf(const MultiplierPoints& points,
                                       const CouplingOperator& coupling, const RigidModes& modes,
                                       std::size_t p, double dt) {
  Block& block = blocks_[p];
  const Change change = Compare(points, coupling, p, dt, block);
  if (change == Change::kNone) return;
  Assemble(points, coupling, p, block);
  const int n = points.Count(p);
  const Eigen::Map<const Eigen::SparseMatrix<double>> b(n, n, static_cast<int>(block.rows.size()),
                                                        block.column_start.data(),
                                                        block.rows.data(), block.values.data());
  if (change == Change::kNodes) {
    block.factor.analyzePattern(b);  // B_p's pattern is that of its stencils' shared nodes
    ++block.analyses;
  }
  block.factor.factorize(b);
  ++block.factorisations;
  block.factored = block.factor.info() == Eigen::Success && block.factor.vectorD().minCoeff() > 0.0;
  if (!block.factored) return;
  block.in.resize(n, 2);
  block.out.resize(n, 2);
  block.rigid = modes.IsNeutral(p) || modes.InverseExcessMass(p) > 0.0;
  if (block.rigid) Woodbury(points, modes, p, dt, block);
}

std::uint64_t MultiplierPreconditioner::Factorisations() const {
  std::uint64_t sum = 0;
  for (const Block& block : blocks_) sum += block.factorisations;
  return sum;
}

std::uint64_t MultiplierPreconditioner::Analyses() const {
  std::uint64_t sum = 0;
  for (const Block& block : blocks_) sum += block.analyses;
  return sum;
}

void MultiplierPreconditioner::ApplyOf(const MultiplierPoints& points, std::size_t p,
                                       const double* r, double* z) {
  Block& block = blocks_[p];
  const int n = points.Count(p);
  for (int k = 0; k < n; ++k) {
    block.in(block.order[k], 0) = r[2 * k];
    block.in(block.order[k], 1) = r[2 * k + 1];
  }
  block.out = block.factor.solve(block.in);
  for (int k = 0; k < n; ++k) {
    z[2 * k] = block.out(block.order[k], 0);
    z[2 * k + 1] = block.out(block.order[k], 1);
  }
  if (!block.rigid) return;
  // z -= Y T^-1 Y^T r.
  double mx = 0.0, my = 0.0, mr = 0.0;
  for (int k = 0; k < n; ++k) {
    mx += block.one[k] * r[2 * k];
    my += block.one[k] * r[2 * k + 1];
    mr += block.rx[k] * r[2 * k] + block.ry[k] * r[2 * k + 1];
  }
  const Eigen::Vector3d t = block.t_inverse * Eigen::Vector3d(mx, my, mr);
  for (int k = 0; k < n; ++k) {
    z[2 * k] -= block.one[k] * t[0] + block.rx[k] * t[2];
    z[2 * k + 1] -= block.one[k] * t[1] + block.ry[k] * t[2];
  }
}

}  // namespace dlmfd
