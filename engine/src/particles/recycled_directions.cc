// The viscous coupling's recycled PCG directions; see particles/recycled_directions.h.
#include "dlmfd/particles/recycled_directions.h"

#include <Eigen/Dense>
#include <algorithm>

namespace dlmfd {
namespace {

double Dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t q = 0; q < a.size(); ++q) s += a[q] * b[q];
  return s;
}

}  // namespace

bool RecycledDirections::Used(const Params& params) {
  return params.splitting.constraint.value() == ConstraintCoupling::kViscous &&
         !params.particles.empty() &&
         std::all_of(params.particles.begin(), params.particles.end(),
                     [](const ParticleParams& q) { return q.motion == Motion::kFixed; });
}

RecycledDirections::Coefficient RecycledDirections::Coefficients(
    const std::vector<double>& g) const {
  // Fixed size (no allocation): the unused rows and columns are those of the identity, with a zero
  // right side, so they give zero coefficients.
  using Square = Eigen::Matrix<double, kCapacity, kCapacity>;
  Square gram = Square::Identity();
  Coefficient rhs = Coefficient::Zero();
  const int m = Count();
  for (int i = 0; i < m; ++i) {
    rhs(i) = -Dot(At(i).d, g);
    for (int j = 0; j < m; ++j) gram(i, j) = Dot(At(i).d, At(j).sd);
  }
  const Square symmetric = 0.5 * (gram + gram.transpose());
  return Eigen::CompleteOrthogonalDecomposition<Square>(symmetric).solve(rhs);
}

void RecycledDirections::Add(const std::vector<double>& d, const std::vector<double>& sd,
                             const std::vector<double>& du, const std::vector<double>& dv,
                             const std::vector<double>& dp, const std::vector<Vec2>& dvelocity,
                             const std::vector<double>& domega, const Vec2& dgradient) {
  if (Count() < kCapacity) {
    stored_.emplace_back();
    next_ = Count() - 1;
  }
  Direction& w = stored_[static_cast<std::size_t>(next_)];
  w.d = d;
  w.sd = sd;
  w.du = du;
  w.dv = dv;
  w.dp = dp;
  w.dvelocity = dvelocity;
  w.domega = domega;
  w.dgradient = dgradient;
  next_ = (next_ + 1) % kCapacity;
}

}  // namespace dlmfd
