#include "study_expansion.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "scene_values.h"
#include "service_error.h"

namespace dlmfd::server {
namespace {

// A range value with 12 significant digits (0.1 + 0.4 / 2 is written 0.3, the value a user means,
// not 0.30000000000000004), as a TOML float ("2.0", not the integer "2").
std::string FloatText(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.12g", value);
  std::string out = text;
  if (out.find_first_of(".eE") == std::string::npos) out += ".0";
  return out;
}

std::string NumberText(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::vector<std::string> RangeValues(const std::string& key, const v1::AxisRange& range) {
  const double a = range.start(), b = range.stop();
  const int n = range.count();
  Require(n >= 2 && n <= kMaxRangeCount, "axes: " + key + " range count = " + std::to_string(n) +
                                             " is not allowed: expected 2 to " +
                                             std::to_string(kMaxRangeCount));
  Require(std::isfinite(a) && std::isfinite(b),
          "axes: " + key + " range bounds must be finite numbers");
  if (range.logarithmic()) {
    Require(a != 0 && b != 0 && (a > 0) == (b > 0),
            "axes: " + key + " logarithmic range from " + NumberText(a) + " to " + NumberText(b) +
                " is not allowed: expected start and stop of one sign, neither zero");
  }
  std::vector<std::string> values;
  for (int k = 0; k < n; ++k) {
    const double s = static_cast<double>(k) / (n - 1);
    double v = range.logarithmic()
                   ? std::copysign(std::exp(std::log(std::fabs(a)) + s * std::log(b / a)), a)
                   : a + (b - a) * s;
    if (k == 0) v = a;
    if (k == n - 1) v = b;
    values.push_back(FloatText(v));
  }
  return values;
}

StoredAxis CheckedAxis(const v1::StudyAxis& axis, std::set<std::string>& keys) {
  Require(!axis.key().empty(), "axes: an axis has no key");
  Require(axis.key().find_first_of("=\n\t") == std::string::npos,
          "axes: key \"" + CutForMessage(axis.key()) + "\" contains '=', a tab or a line break");
  Require(keys.insert(axis.key()).second, "axes: key " + axis.key() + " appears twice");
  Require(axis.zip().find_first_of("\n\t") == std::string::npos,
          "axes: " + axis.key() + " zip name contains a tab or a line break");
  StoredAxis out;
  out.key = axis.key();
  out.zip = axis.zip();
  if (axis.has_range()) {
    Require(axis.values_size() == 0, "axes: " + axis.key() + " has both values and a range");
    out.values = RangeValues(axis.key(), axis.range());
    out.is_range = true;
    out.start = axis.range().start();
    out.stop = axis.range().stop();
    out.count = axis.range().count();
    out.logarithmic = axis.range().logarithmic();
  } else {
    Require(axis.values_size() > 0, "axes: " + axis.key() + " has no values");
    out.values.assign(axis.values().begin(), axis.values().end());
  }
  for (const auto& value : out.values) {
    Require(value.find_first_of("\n\t") == std::string::npos,
            "axes: " + axis.key() + " value \"" + CutForMessage(value) +
                "\" contains a tab or a line break");
  }
  return out;
}

}  // namespace

StudyPlan ExpandStudy(const v1::SubmitStudyRequest& request, int64_t max_points) {
  Require(request.axes_size() > 0, "axes: at least one axis is needed");
  StudyPlan plan;
  std::set<std::string> keys;
  // Dimensions of the grid: the axes (by index) that step together.
  std::vector<std::vector<size_t>> dimensions;
  std::map<std::string, size_t> zip_dimension;
  for (const auto& axis : request.axes()) {
    plan.axes.push_back(CheckedAxis(axis, keys));
    const size_t a = plan.axes.size() - 1;
    if (axis.zip().empty()) {
      dimensions.push_back({a});
      continue;
    }
    auto [it, added] = zip_dimension.emplace(axis.zip(), dimensions.size());
    if (added) {
      dimensions.push_back({a});
      continue;
    }
    const StoredAxis& first = plan.axes[dimensions[it->second].front()];
    Require(first.values.size() == plan.axes[a].values.size(),
            "axes: zipped axes of \"" + axis.zip() + "\" must have equal lengths: " + first.key +
                " has " + std::to_string(first.values.size()) + " values, " + axis.key() + " has " +
                std::to_string(plan.axes[a].values.size()));
    dimensions[it->second].push_back(a);
  }
  int64_t points = 1;
  for (const auto& dimension : dimensions) {
    points *= static_cast<int64_t>(plan.axes[dimension.front()].values.size());
    if (points > max_points) {
      throw ServiceError(
          grpc::StatusCode::RESOURCE_EXHAUSTED,
          "the study has more points than max_queued = " + std::to_string(max_points));
    }
  }
  const std::vector<std::string> base(request.overrides().begin(), request.overrides().end());
  plan.points.reserve(static_cast<size_t>(points));
  std::vector<size_t> index(dimensions.size(), 0);  // per dimension
  std::vector<size_t> at(plan.axes.size(), 0);      // per axis
  for (int64_t p = 0; p < points; ++p) {
    for (size_t d = 0; d < dimensions.size(); ++d) {
      for (size_t a : dimensions[d]) at[a] = index[d];
    }
    StudyPoint point{base, "", {}};
    for (size_t a = 0; a < plan.axes.size(); ++a) {
      const StoredAxis& axis = plan.axes[a];
      const std::string& value = axis.values[at[a]];
      const std::string pair = axis.key + "=" + value;
      point.overrides.push_back(pair);
      point.label += (a ? "," : "") + pair;
      point.parameters.push_back(TypedValue(axis.key, value));
    }
    plan.points.push_back(std::move(point));
    for (size_t d = dimensions.size(); d-- > 0;) {
      if (++index[d] < plan.axes[dimensions[d].front()].values.size()) break;
      index[d] = 0;
    }
  }
  return plan;
}

}  // namespace dlmfd::server
