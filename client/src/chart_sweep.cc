// dlmfd chart --sweep S --x KEY --y COLUMN [--group KEY] [--title T] [--logx] [--logy] [--out F]
//             [--width W] [--height H]
// A quantity of a study against one of its parameters: one point per job of the sweep that has the
// column, from the Table rpc (study_table.h names the columns); --group draws one line per value of
// a second parameter, named by its values under a legend titled by its key (printed on stderr too),
// in increasing value. Points are joined in increasing x.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>

#include "command.h"
#include "connection.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/viz/line_chart.h"
#include "exit_codes.h"
#include "rpc_status.h"
#include "study_table.h"

namespace dlmfd::cli {
namespace {

// A line of the chart: the jobs with one value of the --group parameter, named by that value (the
// legend's title names the parameter), in increasing value (then text) order.
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

bool IsSweepChart(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--sweep" || arg.rfind("--sweep=", 0) == 0) return true;
  }
  return false;
}

int RunSweepChart(int argc, char** argv) {
  CLI::App app{"Draw a quantity of a sweep's jobs against one of its parameters as a PNG."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string sweep, x_key, y_column, group_key, out;
  LineChartOptions options;
  options.width = 1000;
  options.height = 700;
  bool log_x = false, log_y = false;
  app.add_option("--sweep", sweep, "the sweep id")->required();
  app.add_option("--x", x_key, "a parameter of the sweep (a column of dlmfd table)")->required();
  app.add_option("--y", y_column, "a column of dlmfd table (fall_speed, min_gap, p0.y, ...)")
      ->required();
  app.add_option("--group", group_key, "one line per value of this parameter");
  app.add_option("--title", options.title, "title above the chart");
  app.add_flag("--logx", log_x, "log10 x axis");
  app.add_flag("--logy", log_y, "log10 y axis");
  app.add_option("--out,-o", out, "PNG file to write (default chart_<sweep>.png here)");
  app.add_option("--width", options.width, "image width in pixels")->check(CLI::Range(200, 8192));
  app.add_option("--height", options.height, "image height in pixels")
      ->check(CLI::Range(150, 8192));
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("chart", [&] {
    Connection connection(connection_flags);
    v1::TableResponse response;
    const grpc::Status status = FetchTableRows(connection, sweep, {}, &response);
    if (!status.ok()) return ReportRpcError("chart", status);
    const StudyTable table = FlattenTable(response);
    const size_t xc = table.Column(x_key, "--x");
    const size_t yc = table.Column(y_column, "--y");
    const bool grouped = !group_key.empty();
    const size_t gc = grouped ? table.Column(group_key, "--group") : 0;
    std::vector<Group> groups;
    std::map<std::string, size_t> group_index;
    for (const auto& row : table.rows) {
      const double x = CellNumber(row[xc]), y = CellNumber(row[yc]);
      if (std::isnan(x) || std::isnan(y)) continue;
      Group group = grouped ? GroupOf(row[gc]) : Group{0.0, y_column, {}};
      const auto [at, added] = group_index.emplace(group.name, groups.size());
      if (added) groups.push_back(std::move(group));
      groups[at->second].xy.emplace_back(x, y);
    }
    if (groups.empty()) {
      throw UsageError("no job of sweep " + sweep + " has both " + x_key + " and " + y_column +
                       " (dlmfd table --sweep " + sweep + " shows them)");
    }
    options.x_axis.title = x_key;
    options.y_axis.title = y_column;
    options.x_axis.scale = log_x ? AxisScale::kLog10 : AxisScale::kLinear;
    options.y_axis.scale = log_y ? AxisScale::kLog10 : AxisScale::kLinear;
    if (options.title.empty()) options.title = y_column + " against " + x_key + " (" + sweep + ")";
    std::sort(groups.begin(), groups.end(), GroupBefore);
    if (grouped) {
      options.legend_title = group_key;
      std::string names;
      for (const Group& group : groups) names += (names.empty() ? "" : "; ") + group.name;
      std::cerr << "legend (" << group_key << "): " << names << "\n";
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
    ChartPicture picture;
    try {
      picture = chart.Draw();
    } catch (const InvalidParameter& e) {
      throw UsageError(e.what());
    }
    // A sweep id is the daemon's ("s-" and hex digits): a safe file name.
    const std::string path = out.empty() ? "chart_" + sweep + ".png" : out;
    try {
      picture.image.Write(path);
    } catch (const Error& e) {
      return ReportError("chart", e.what(), kExitLocalIo);
    }
    std::cout << path << "\n";
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
