#include "study_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

namespace dlmfd::cli {
namespace {

// A line of the chart: the jobs with one value of the group parameter, named by that value.
struct Group {
  double order = 0.0;
  std::string name;
  std::vector<std::pair<double, double>> xy;
};

Group GroupOf(const TableCell& cell) {
  if (const auto* s = std::get_if<std::string>(&cell)) return {std::nan(""), *s, {}};
  const double x = CellNumber(cell);
  if (std::isnan(x)) return {x, "not set", {}};
  char text[40];
  std::snprintf(text, sizeof text, "%.6g", x);
  return {x, text, {}};
}

bool GroupBefore(const Group& a, const Group& b) {
  // Numbers first, by value; then texts (and "not set") by name.
  if (std::isnan(a.order) != std::isnan(b.order)) return !std::isnan(a.order);
  if (!std::isnan(a.order) && a.order != b.order) return a.order < b.order;
  return a.name < b.name;
}

}  // namespace

StudyChart DrawStudyChart(const StudyTable& table, const StudyChartSpec& spec) {
  const size_t xc = table.Column(spec.x, "--x");
  const size_t yc = table.Column(spec.y, "--y");
  const bool grouped = !spec.group.empty();
  const size_t gc = grouped ? table.Column(spec.group, "--group") : 0;
  std::vector<Group> groups;
  std::map<std::string, size_t> group_index;
  for (const auto& row : table.rows) {
    const double x = CellNumber(row[xc]), y = CellNumber(row[yc]);
    if (std::isnan(x) || std::isnan(y)) continue;
    Group group = grouped ? GroupOf(row[gc]) : Group{0.0, spec.y, {}};
    const auto [at, added] = group_index.emplace(group.name, groups.size());
    if (added) groups.push_back(std::move(group));
    groups[at->second].xy.emplace_back(x, y);
  }
  if (groups.empty()) {
    throw UsageError("no job of study " + spec.study_id + " has both " + spec.x + " and " + spec.y +
                     " (dlmfd table --study " + spec.study_id + " shows them)");
  }
  LineChartOptions options = spec.options;
  options.x_axis.title = spec.x;
  options.y_axis.title = spec.y;
  options.x_axis.scale = spec.log_x ? AxisScale::kLog10 : AxisScale::kLinear;
  options.y_axis.scale = spec.log_y ? AxisScale::kLog10 : AxisScale::kLinear;
  if (options.title.empty())
    options.title = spec.y + " against " + spec.x + " (" + spec.study_id + ")";
  std::sort(groups.begin(), groups.end(), GroupBefore);
  StudyChart out;
  if (grouped) {
    options.legend_title = spec.group;
    for (const Group& group : groups) out.legend.push_back(group.name);
  }
  LineChart chart(options);
  for (Group& group : groups) {
    std::sort(group.xy.begin(), group.xy.end());
    ChartSeries series;
    series.name = group.name;
    series.markers = true;
    for (const auto& [x, y] : group.xy) {
      series.x.push_back(x);
      series.y.push_back(y);
    }
    chart.AddSeries(std::move(series));
  }
  out.picture = chart.Draw();
  return out;
}

}  // namespace dlmfd::cli
