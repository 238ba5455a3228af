// The flow rates held by a mean pressure gradient; see fluid/flux_control.h.
#include "dlmfd/fluid/flux_control.h"

#include <utility>

#include "dlmfd/core/ordered_sum.h"

namespace dlmfd {

FluxControl::FluxControl(const Grid& grid, const DomainParams& domain, std::vector<double> weights)
    : period_{grid.Width(), grid.Height()},
      target_(domain.flow_rate.value_or(0.0)),
      weights_(std::move(weights)),
      axes_(HeldAxes(domain)) {}

void FluxControl::SetResponses(std::vector<UnitResponse> responses) {
  responses_ = std::move(responses);
  // R_ab = Q_a(u_b), inverted (1 x 1 or 2 x 2).
  std::array<std::array<double, 2>, 2> rates{};
  const std::size_t m = responses_.size();
  for (std::size_t a = 0; a < m; ++a) {
    for (std::size_t b = 0; b < m; ++b) {
      rates[a][b] = FlowRate(responses_[a].axis, responses_[b].u.data(), responses_[b].v.data());
    }
  }
  if (m == 1) {
    inverse_[0][0] = 1.0 / rates[0][0];
  } else {
    const double det = rates[0][0] * rates[1][1] - rates[0][1] * rates[1][0];
    inverse_ = {{{rates[1][1] / det, -rates[0][1] / det}, {-rates[1][0] / det, rates[0][0] / det}}};
  }
}

std::vector<int> FluxControl::HeldAxes(const DomainParams& domain) {
  std::vector<int> axes;
  if (domain.PeriodicX()) axes.push_back(0);
  if (domain.PeriodicY()) axes.push_back(1);
  return axes;
}

double FluxControl::FlowRate(int axis, const double* u, const double* v) const {
  const double* w = weights_.data();
  const double* along = axis == 0 ? u : v;
  return OrderedSum(static_cast<long>(weights_.size()), [=](long k) { return w[k] * along[k]; }) /
         period_[static_cast<std::size_t>(axis)];
}

Vec2 FluxControl::Hold(double* u, double* v) const {
  const std::size_t m = responses_.size();
  std::array<double, 2> miss{};
  for (std::size_t a = 0; a < m; ++a) miss[a] = target_ - FlowRate(responses_[a].axis, u, v);
  Vec2 gradient = Vec2::Zero();
  const std::size_t n = weights_.size();
  for (std::size_t b = 0; b < m; ++b) {
    double g = 0.0;
    for (std::size_t a = 0; a < m; ++a) g += inverse_[b][a] * miss[a];
    const double* ub = responses_[b].u.data();
    const double* vb = responses_[b].v.data();
    for (std::size_t k = 0; k < n; ++k) {
      u[k] += g * ub[k];
      v[k] += g * vb[k];
    }
    gradient[responses_[b].axis] = g;
  }
  return gradient;
}

}  // namespace dlmfd
