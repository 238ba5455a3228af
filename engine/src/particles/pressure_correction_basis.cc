// Fischer's projection of the Uzawa start; see particles/pressure_correction_basis.h.
#include "dlmfd/particles/pressure_correction_basis.h"

#include <cmath>
#include <cstddef>

namespace dlmfd {

void PressureCorrectionBasis::Clear() {
  data_.q.clear();
  data_.sq.clear();
  data_.wq.clear();
}

void PressureCorrectionBasis::Project(Eigen::VectorXd& p, Eigen::VectorXd& u,
                                      Eigen::VectorXd& r) const {
  const std::vector<Eigen::VectorXd>& q = data_.q;
  const std::vector<Eigen::VectorXd>& sq = data_.sq;
  const std::vector<Eigen::VectorXd>& wq = data_.wq;
  if (q.empty()) return;
  Eigen::VectorXd a(Count());
  for (int i = 0; i < Count(); ++i) a[i] = q[static_cast<std::size_t>(i)].dot(r);
  for (int i = 0; i < Count(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    p += a[i] * q[k];
    u -= a[i] * wq[k];
    r -= a[i] * sq[k];
  }
}

void PressureCorrectionBasis::Add(Eigen::VectorXd dp, Eigen::VectorXd s, Eigen::VectorXd w) {
  if (Count() == kCapacity) Clear();
  std::vector<Eigen::VectorXd>& q = data_.q;
  std::vector<Eigen::VectorXd>& sq = data_.sq;
  std::vector<Eigen::VectorXd>& wq = data_.wq;
  const double before = dp.dot(s);  // |dp|_S^2
  if (!(before > 0.0)) return;
  // Classical Gram-Schmidt in the S inner product, twice; w takes both passes' coefficients at once
  // (it enters no coefficient).
  Eigen::VectorXd total = Eigen::VectorXd::Zero(Count()), c(Count());
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < Count(); ++i) c[i] = q[static_cast<std::size_t>(i)].dot(s);  // q_i^T S dp
    for (int i = 0; i < Count(); ++i) {
      dp -= c[i] * q[static_cast<std::size_t>(i)];
      s -= c[i] * sq[static_cast<std::size_t>(i)];
    }
    total += c;
  }
  for (int i = 0; i < Count(); ++i) w -= total[i] * wq[static_cast<std::size_t>(i)];
  // A correction already in the span (to round-off: 1e-10 of its S-norm left) adds nothing.
  const double after = dp.dot(s);
  if (!(after > 1e-20 * before)) return;
  const double scale = 1.0 / std::sqrt(after);
  q.push_back(scale * dp);
  sq.push_back(scale * s);
  wq.push_back(scale * w);
}

}  // namespace dlmfd
