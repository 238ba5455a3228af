// The block-Jacobi preconditioner of the multiplier CG; see particles/multiplier_preconditioner.h.
#include "dlmfd/particles/multiplier_preconditioner.h"

#include <Eigen/LU>

namespace dlmfd {

void MultiplierPreconditioner::Assemble(const MultiplierPoints& points,
                                        const CouplingOperator& coupling, std::size_t p,
                                        Block& block) const {
  // B_p[k][l] = sum_s w_ks (dt w_ls / m_s): for each entry (k, s) of E, the points l of particle p
  // that slot s spreads to.
  const std::size_t first = points.Begin(p), end = points.End(p);
  block.entries.clear();
  for (std::size_t q = first; q < end; ++q) {
    for (std::size_t e = coupling.StencilBegin(q); e < coupling.StencilBegin(q + 1); ++e) {
      const std::uint32_t slot = coupling.EntrySlot(e);
      if (slot == 0) continue;
      const double weight = coupling.EntryWeight(e);
      for (std::size_t c = coupling.SpreadBegin(slot); c < coupling.SpreadBegin(slot + 1); ++c) {
        const std::size_t l = coupling.SpreadSource(c);
        if (l < first || l >= end) continue;  // another particle's point: off the block
        block.entries.emplace_back(static_cast<int>(q - first), static_cast<int>(l - first),
                                   weight * coupling.SpreadWeight(c));
      }
    }
  }
  const int n = points.Count(p);
  Eigen::SparseMatrix<double> b(n, n);
  b.setFromTriplets(block.entries.begin(), block.entries.end());
  block.factor.compute(b);
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
  block.one = block.factor.solve(ones);
  block.rx = block.factor.solve(minus_ry);
  block.ry = block.factor.solve(plus_rx);
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
  Assemble(points, coupling, p, block);
  block.factored = block.factor.info() == Eigen::Success && block.factor.vectorD().minCoeff() > 0.0;
  if (!block.factored) return;
  const int n = points.Count(p);
  block.in.resize(n);
  block.out.resize(n);
  block.rigid = modes.IsNeutral(p) || modes.InverseExcessMass(p) > 0.0;
  if (block.rigid) Woodbury(points, modes, p, dt, block);
}

void MultiplierPreconditioner::ApplyOf(const MultiplierPoints& points, std::size_t p,
                                       const double* r, double* z) {
  Block& block = blocks_[p];
  const int n = points.Count(p);
  for (int c = 0; c < 2; ++c) {
    for (int k = 0; k < n; ++k) block.in[k] = r[2 * k + c];
    block.out = block.factor.solve(block.in);
    for (int k = 0; k < n; ++k) z[2 * k + c] = block.out[k];
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
