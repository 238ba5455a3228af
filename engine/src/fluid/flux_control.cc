// The flow rate held by a mean pressure gradient; see fluid/flux_control.h.
#include "dlmfd/fluid/flux_control.h"

#include <utility>

#include "dlmfd/core/ordered_sum.h"

namespace dlmfd {

FluxControl::FluxControl(const Grid& grid, const DomainParams& domain, std::vector<double> weights,
                         std::vector<double> ue, std::vector<double> ve)
    : along_x_(domain.PeriodicX()),
      period_(along_x_ ? grid.Width() : grid.Height()),
      target_(domain.flow_rate.value_or(0.0)),
      weights_(std::move(weights)),
      ue_(std::move(ue)),
      ve_(std::move(ve)) {
  unit_rate_ = FlowRate(ue_.data(), ve_.data());
}

double FluxControl::FlowRate(const double* u, const double* v) const {
  const double* w = weights_.data();
  const double* along = along_x_ ? u : v;
  return OrderedSum(static_cast<long>(weights_.size()), [=](long k) { return w[k] * along[k]; }) /
         period_;
}

double FluxControl::Hold(double* u, double* v) const {
  const double gradient = (target_ - FlowRate(u, v)) / unit_rate_;
  const std::size_t n = weights_.size();
  for (std::size_t k = 0; k < n; ++k) {
    u[k] += gradient * ue_[k];
    v[k] += gradient * ve_[k];
  }
  return gradient;
}

}  // namespace dlmfd
