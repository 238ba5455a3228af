// Fischer's projection of the Uzawa start; see particles/pressure_correction_basis.h.
#include "dlmfd/particles/pressure_correction_basis.h"

#include <cmath>
#include <cstddef>

namespace dlmfd {

void PressureCorrectionBasis::Clear() {
  q_.clear();
  sq_.clear();
  wq_.clear();
}

void PressureCorrectionBasis::Project(Eigen::VectorXd& p, Eigen::VectorXd& u,
                                      Eigen::VectorXd& r) const {
  if (q_.empty()) return;
  Eigen::VectorXd a(Count());
  for (int i = 0; i < Count(); ++i) a[i] = q_[static_cast<std::size_t>(i)].dot(r);
  for (int i = 0; i < Count(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    p += a[i] * q_[k];
    u -= a[i] * wq_[k];
    r -= a[i] * sq_[k];
  }
}

void PressureCorrectionBasis::Add(Eigen::VectorXd dp, Eigen::VectorXd s, Eigen::VectorXd w) {
  if (Count() == kCapacity) Clear();
  const double before = dp.dot(s);  // |dp|_S^2
  if (!(before > 0.0)) return;
  // Classical Gram-Schmidt in the S inner product, twice; w takes both passes' coefficients at once
  // (it enters no coefficient).
  Eigen::VectorXd total = Eigen::VectorXd::Zero(Count()), c(Count());
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < Count(); ++i) c[i] = q_[static_cast<std::size_t>(i)].dot(s);  // q_i^T S dp
    for (int i = 0; i < Count(); ++i) {
      dp -= c[i] * q_[static_cast<std::size_t>(i)];
      s -= c[i] * sq_[static_cast<std::size_t>(i)];
    }
    total += c;
  }
  for (int i = 0; i < Count(); ++i) w -= total[i] * wq_[static_cast<std::size_t>(i)];
  // A correction already in the span (to round-off: 1e-10 of its S-norm left) adds nothing.
  const double after = dp.dot(s);
  if (!(after > 1e-20 * before)) return;
  const double scale = 1.0 / std::sqrt(after);
  q_.push_back(scale * dp);
  sq_.push_back(scale * s);
  wq_.push_back(scale * w);
}

}  // namespace dlmfd
