#include "sweep_expansion.h"

#include <set>

#include "service_error.h"

namespace dlmfd::server {

std::vector<SweepPoint> ExpandSweep(const v1::SubmitSweepRequest& request, int64_t max_points) {
  Require(request.axes_size() > 0, "axes: at least one axis is needed");
  std::set<std::string> keys;
  int64_t points = 1;
  for (const auto& axis : request.axes()) {
    Require(!axis.key().empty(), "axes: an axis has no key");
    Require(axis.key().find_first_of("=\n") == std::string::npos,
            "axes: key \"" + axis.key() + "\" contains '=' or a line break");
    Require(keys.insert(axis.key()).second, "axes: key " + axis.key() + " appears twice");
    Require(axis.values_size() > 0, "axes: " + axis.key() + " has no values");
    points *= axis.values_size();
    if (points > max_points) {
      throw ServiceError(
          grpc::StatusCode::RESOURCE_EXHAUSTED,
          "the sweep has more points than max_queued = " + std::to_string(max_points));
    }
  }
  const std::vector<std::string> base(request.overrides().begin(), request.overrides().end());
  std::vector<SweepPoint> grid;
  grid.reserve(static_cast<size_t>(points));
  std::vector<int> index(static_cast<size_t>(request.axes_size()), 0);
  for (int64_t p = 0; p < points; ++p) {
    SweepPoint point{base, ""};
    for (int a = 0; a < request.axes_size(); ++a) {
      const auto& axis = request.axes(a);
      const std::string pair = axis.key() + "=" + axis.values(index[static_cast<size_t>(a)]);
      point.overrides.push_back(pair);
      point.label += (a ? "," : "") + pair;
    }
    grid.push_back(std::move(point));
    for (int a = request.axes_size() - 1; a >= 0; --a) {
      auto& i = index[static_cast<size_t>(a)];
      if (++i < request.axes(a).values_size()) break;
      i = 0;
    }
  }
  return grid;
}

}  // namespace dlmfd::server
