// dlmfd chart RUN_DIR... --y Q [--x Q] [--particle ID|all] [--label TEXT]... [--title T] [--logx]
//             [--logy] [--equal] [--legend-title T] [--markers] [--out FILE.png|.svg|.pdf]
//             [--width W] [--height H]
// dlmfd chart --csv FILE --xcol NAME --ycol NAME [--group NAME] [--points] [same drawing flags]
// Line charts of particle quantities (particles.h5 of results directories, design.md 3.2) against
// time or each other, several runs overlaid, or of two columns of any CSV file with a header (one
// series per value of a group column: work-precision charts). Local files only: no daemon.
// Series of several runs are named by the parameters in which their scenes differ (the swept
// parameters, scene_differences.h), the keys in the legend's title; --label names them instead.
// `gap` is the smallest surface-to-surface distance over the pairs of particles of a run at each
// record, min |xi - xj| - ri - rj, not taking periodic images into account.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "command.h"
#include "connection.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/io/particle_history.h"
#include "dlmfd/io/results_format.h"
#include "dlmfd/viz/line_chart.h"
#include "exit_codes.h"
#include "figure_panel.h"
#include "rpc_status.h"
#include "scene_differences.h"

namespace dlmfd::cli {
namespace {

namespace fs = std::filesystem;

struct Quantity {
  const char* name;
  const char* title;       // axis title
  const char* dimensions;  // in the scene's units (results_format.h)
};

const Quantity kQuantities[] = {
    {"t", "t", "T"},
    {"x", "x of centre", "L"},
    {"y", "y of centre", "L"},
    {"u", "u (velocity x)", "L T-1"},
    {"v", "v (velocity y)", "L T-1"},
    {"omega", "omega (angular velocity)", "T-1"},
    {"angle", "angle theta (radians, from t = 0)", ""},
    {"fx", "fx (force x per unit length)", "M T-2"},
    {"fy", "fy (force y per unit length)", "M T-2"},
    {"torque", "torque per unit length", "M L T-2"},
    {"speed", "speed |U|", "L T-1"},
    {"gap", "gap: min |xi - xj| - ri - rj", "L"},
};

// "u (velocity x) [cm s-1]" with --units, else the title.
std::string TitleWithUnits(const Quantity& q, const std::string& units) {
  const std::string names = units.empty() ? "" : UnitsIn(q.dimensions, units);
  return names.empty() ? q.title : std::string(q.title) + " [" + names + "]";
}

std::string AllowedQuantities() {
  std::string text;
  for (const Quantity& q : kQuantities) text += (text.empty() ? "" : ", ") + std::string(q.name);
  return text;
}

const Quantity& FindQuantity(const std::string& name, const std::string& flag) {
  for (const Quantity& q : kQuantities) {
    if (name == q.name) return q;
  }
  throw UsageError(flag + " " + name +
                   " is not a quantity of particles.h5; allowed: " + AllowedQuantities());
}

// The value of `quantity` of particle p at record r (gap: of the whole run, p ignored).
double Value(const ParticleHistory& h, const std::string& quantity, std::size_t r, std::size_t p) {
  const std::size_t k = r * h.particles + p;
  if (quantity == "t") return h.time[r];
  if (quantity == "x") return h.position[2 * k];
  if (quantity == "y") return h.position[2 * k + 1];
  if (quantity == "u") return h.velocity[2 * k];
  if (quantity == "v") return h.velocity[2 * k + 1];
  if (quantity == "omega") return h.angular_velocity[k];
  if (quantity == "angle") return h.angle[k];
  if (quantity == "fx") return h.force[2 * k];
  if (quantity == "fy") return h.force[2 * k + 1];
  if (quantity == "torque") return h.torque[k];
  if (quantity == "speed") return std::hypot(h.velocity[2 * k], h.velocity[2 * k + 1]);
  // gap
  double gap = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < h.particles; ++i) {
    for (std::size_t j = i + 1; j < h.particles; ++j) {
      const std::size_t a = 2 * (r * h.particles + i);
      const std::size_t b = 2 * (r * h.particles + j);
      const double centres =
          std::hypot(h.position[a] - h.position[b], h.position[a + 1] - h.position[b + 1]);
      gap = std::min(gap, centres - h.radius[i] - h.radius[j]);
    }
  }
  return gap;
}

// The name of a run directory as given ("runs/pair/" -> "pair").
std::string RunName(const std::string& dir) {
  fs::path path = fs::path(dir).lexically_normal();
  if (path.filename().empty()) path = path.parent_path();
  const std::string name = path.filename().string();
  return name.empty() || name == "." ? dir : name;
}

std::string IdList(const ParticleHistory& h) {
  std::string text;
  for (const std::int64_t id : h.id) text += (text.empty() ? "" : ", ") + std::to_string(id);
  return text;
}

struct RunRequest {
  std::vector<std::string> dirs;
  std::vector<std::string> labels;
  std::string x = "t";
  std::string y;
  std::string particle = "all";
  bool markers = false;
};

ParticleHistory ReadRun(const std::string& dir) {
  const fs::path file = fs::path(dir) / "particles.h5";
  if (!fs::is_regular_file(file)) {
    throw UsageError("no " + file.string() + " (is " + dir +
                     " a results directory of dlmfd-solve?)");
  }
  try {
    return ReadParticleHistory(file.string());
  } catch (const Error& e) {
    throw UsageError("cannot read " + file.string() + ": " + e.what());
  }
}

// The particle indices of `h` that --particle selects.
std::vector<std::size_t> SelectParticles(const ParticleHistory& h, const std::string& particle,
                                         const std::string& dir) {
  std::vector<std::size_t> selected;
  if (particle == "all") {
    for (std::size_t p = 0; p < h.particles; ++p) selected.push_back(p);
    return selected;
  }
  char* end = nullptr;
  const long long id = std::strtoll(particle.c_str(), &end, 10);
  if (particle.empty() || *end != '\0')
    throw UsageError("--particle " + particle + ": expected a particle id or all");
  for (std::size_t p = 0; p < h.particles; ++p) {
    if (h.id[p] == id) selected.push_back(p);
  }
  if (selected.empty()) {
    throw UsageError("--particle " + particle + ": " + dir +
                     " has no such particle; its ids: " + IdList(h));
  }
  return selected;
}

// The series names of the runs: --label, else the values of the parameters in which their scenes
// differ (their keys become the legend's title), else the directory names.
std::vector<std::string> RunNames(const RunRequest& request, std::string& legend_title) {
  std::vector<std::string> names;
  std::vector<FlatScene> scenes;
  for (const std::string& dir : request.dirs) scenes.push_back(ReadFlatScene(dir));
  const std::vector<std::string> keys =
      request.dirs.size() > 1 ? DifferingKeys(scenes) : std::vector<std::string>{};
  for (std::size_t n = 0; n < request.dirs.size(); ++n) {
    if (n < request.labels.size()) {
      names.push_back(request.labels[n]);
    } else if (!keys.empty()) {
      names.push_back(ValuesOf(scenes[n], keys));
    } else {
      names.push_back(RunName(request.dirs[n]));
    }
  }
  if (legend_title.empty() && !keys.empty() && request.labels.size() < request.dirs.size()) {
    for (const std::string& key : keys) legend_title += (legend_title.empty() ? "" : ", ") + key;
  }
  return names;
}

void AddRunSeries(const RunRequest& request, const std::vector<std::string>& names,
                  LineChart& chart) {
  const bool per_run = request.x == "gap" || request.y == "gap";
  const bool particle_free = request.x == "t" && request.y == "t";
  for (std::size_t n = 0; n < request.dirs.size(); ++n) {
    const std::string& dir = request.dirs[n];
    const std::string& name = names[n];
    const ParticleHistory h = ReadRun(dir);
    if (h.records == 0) throw UsageError(dir + "/particles.h5 holds no records yet");
    if (per_run && h.particles < 2) {
      throw UsageError("gap needs two or more particles; " + dir + " has " +
                       std::to_string(h.particles));
    }
    if (!particle_free && h.particles == 0) throw UsageError(dir + " has no particles");
    if ((request.x == "angle" || request.y == "angle") && h.angle.empty()) {
      throw UsageError(dir + "/particles.h5 has no /angle (format version 1, an older solver)");
    }
    std::vector<std::size_t> selected = per_run || particle_free
                                            ? std::vector<std::size_t>{0}
                                            : SelectParticles(h, request.particle, dir);
    for (const std::size_t p : selected) {
      ChartSeries series;
      series.name = name;
      if (selected.size() > 1) series.name += " #" + std::to_string(h.id[p]);
      series.markers = request.markers;
      series.x.resize(h.records);
      series.y.resize(h.records);
      for (std::size_t r = 0; r < h.records; ++r) {
        series.x[r] = Value(h, request.x, r, p);
        series.y[r] = Value(h, request.y, r, p);
      }
      chart.AddSeries(std::move(series));
    }
  }
}

// One CSV record: fields separated by commas, optionally in double quotes ("" is a quote).
std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    if (quoted) {
      if (c == '"' && k + 1 < line.size() && line[k + 1] == '"') {
        fields.back() += '"';
        ++k;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  for (std::string& f : fields) {
    const auto first = f.find_first_not_of(" \t");
    f = first == std::string::npos ? "" : f.substr(first, f.find_last_not_of(" \t") - first + 1);
  }
  return fields;
}

// A numeric cell; empty, nan and inf cells are NaN or Inf (they break the line), other text is an
// error.
double CsvNumber(const std::string& cell, const std::string& where) {
  if (cell.empty()) return std::numeric_limits<double>::quiet_NaN();
  char* end = nullptr;
  const double value = std::strtod(cell.c_str(), &end);
  if (end == cell.c_str() || *end != '\0')
    throw UsageError(where + ": '" + cell + "' is not a number");
  return value;
}

struct CsvRequest {
  std::string file;
  std::string x_column;
  std::string y_column;
  std::string group_column;
  bool markers = false;
  bool points_only = false;
  std::string label;  // the series name without --group (default: the y column)
};

void AddCsvSeries(const CsvRequest& request, LineChart& chart) {
  std::istringstream text(ReadInputFile(request.file));
  std::string line;
  std::vector<std::string> header;
  std::size_t line_number = 0;
  while (header.empty() && std::getline(text, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty()) header = SplitCsvLine(line);
  }
  if (header.empty())
    throw UsageError(request.file + " is empty: expected a header line of column names");
  std::string columns;
  for (const std::string& h : header) columns += (columns.empty() ? "" : ", ") + h;
  const auto column = [&](const std::string& name, const std::string& flag) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end())
      throw UsageError(flag + " " + name + ": " + request.file + " has columns " + columns);
    return std::size_t(it - header.begin());
  };
  const std::size_t xc = column(request.x_column, "--xcol");
  const std::size_t yc = column(request.y_column, "--ycol");
  const bool grouped = !request.group_column.empty();
  const std::size_t gc = grouped ? column(request.group_column, "--group") : 0;

  std::vector<ChartSeries> series;
  std::map<std::string, std::size_t> index_of_group;
  while (std::getline(text, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string> fields = SplitCsvLine(line);
    const std::string where = request.file + ":" + std::to_string(line_number);
    if (fields.size() != header.size()) {
      throw UsageError(where + " has " + std::to_string(fields.size()) +
                       " fields; the header has " + std::to_string(header.size()));
    }
    const std::string group =
        grouped ? fields[gc] : (request.label.empty() ? request.y_column : request.label);
    auto [it, added] = index_of_group.emplace(group, series.size());
    if (added) {
      series.emplace_back();
      series.back().name = group;
      series.back().markers = request.markers || request.points_only;
      series.back().lines = !request.points_only;
    }
    series[it->second].x.push_back(CsvNumber(fields[xc], where + " column " + request.x_column));
    series[it->second].y.push_back(CsvNumber(fields[yc], where + " column " + request.y_column));
  }
  if (series.empty()) throw UsageError(request.file + " has a header but no rows");
  for (ChartSeries& s : series) chart.AddSeries(std::move(s));
}

// Letters, digits, '-', '_' and '.' of `text`; anything else becomes '_'.
std::string FileStem(const std::string& text) {
  std::string stem = text;
  for (char& c : stem) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  }
  return stem;
}

}  // namespace

// NOLINTNEXTLINE(readability-function-size): predates the limit; split it when you change it
int RunChartCommand(int argc, char** argv, const PanelRequest* panel) {
  CLI::App app{
      "Draw particle quantities of results directories, or columns of a CSV file, as a line chart "
      "(PNG, SVG or PDF)."};
  ConnectionFlags
      unused_connection;  // accepted for `dlmfd --server ... chart`; chart reads local files only
  AddConnectionFlags(app, unused_connection);
  for (const char* flag : {"--server", "--token", "--timeout"}) app.get_option(flag)->group("");
  RunRequest runs;
  CsvRequest csv;
  LineChartOptions options;
  options.width = 1000;
  options.height = 700;
  bool log_x = false, log_y = false, markers = false, points_only = false;
  std::string out, units, x_title, y_title;
  std::vector<double> x_limits, y_limits, size;
  double dpi = 0.0, font_points = 0.0;
  app.add_option("runs", runs.dirs, "results directories (dlmfd-solve --out, or fetched)");
  app.add_option("--y", runs.y, "quantity on the y axis: " + AllowedQuantities());
  app.add_option("--x", runs.x,
                 "quantity on the x axis (default t; --x x --y y is the trajectory)");
  app.add_option("--particle", runs.particle, "a particle id, or all (default)");
  // One value per --label, so that `--label a RUN` does not take RUN as a second label.
  app.add_option("--label", runs.labels,
                 "series name of each run directory, in order (default: its name)")
      ->allow_extra_args(false);
  app.add_option("--csv", csv.file, "chart two columns of this CSV file (header line of names)");
  app.add_option("--xcol", csv.x_column, "CSV column on the x axis");
  app.add_option("--ycol", csv.y_column, "CSV column on the y axis");
  app.add_option("--group", csv.group_column, "CSV column whose values split the rows into series");
  app.add_option("--title", options.title, "title above the chart");
  app.add_flag("--logx", log_x, "log10 x axis (points with x <= 0 are skipped)");
  app.add_flag("--logy", log_y, "log10 y axis (points with y <= 0 are skipped)");
  app.add_flag("--markers", markers, "a marker at every point as well as the line");
  app.add_flag("--equal", options.equal_scale,
               "the same scale on both axes (trajectories keep their shape; linear axes only)");
  app.add_option("--legend-title", options.legend_title,
                 "title above the legend (default: the parameters in which the runs differ)");
  app.add_flag("--points", points_only,
               "with --csv: a dot at every point and no lines (scatter plot)");
  app.add_option("--csv-label", csv.label,
                 "legend entry of the CSV's series without --group (default: the y column)");
  app.add_option("--xlim", x_limits, "x axis range LO,HI (default: the data's, padded)")
      ->expected(2)
      ->delimiter(',');
  app.add_option("--ylim", y_limits, "y axis range LO,HI (default: the data's, padded)")
      ->expected(2)
      ->delimiter(',');
  app.add_option("--xtitle", x_title, "x axis title (default: the quantity, with --units)");
  app.add_option("--ytitle", y_title, "y axis title (default: the quantity, with --units)");
  app.add_option("--units", units,
                 "unit names on the axis titles: cgs (cm, g, s), si (m, kg, s) or none")
      ->check(CLI::IsMember({"cgs", "si", "none"}));
  app.add_option("--size", size,
                 "chart size in inches W,H (with --dpi; replaces --width and --height)")
      ->expected(2)
      ->delimiter(',');
  app.add_option("--dpi", dpi, "resolution (default 300 with --size, else 72)")
      ->check(CLI::Range(10.0, 4800.0));
  app.add_option("--font-size", font_points, "text size in points at --dpi")
      ->check(CLI::Range(2.0, 200.0));
  app.add_option("--out,-o", out,
                 "file to write: .png, .svg or .pdf (default chart_<y>_<x>.png here)");
  app.add_option("--width", options.width, "image width in pixels")->check(CLI::Range(200, 8192));
  app.add_option("--height", options.height, "image height in pixels")
      ->check(CLI::Range(150, 8192));
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("chart", [&] {
    if (panel != nullptr) {
      for (const char* flag : {"--width", "--height", "--size", "--dpi", "--font-size", "--out"}) {
        if (app.count(flag) > 0)
          throw UsageError(std::string(flag) + " is the figure's, not a panel's");
      }
      options.width = panel->width;
      options.height = panel->height;
    }
    const bool csv_mode = !csv.file.empty() && runs.dirs.empty();
    const bool reference = !csv.file.empty() && !runs.dirs.empty();  // CSV data over the runs
    if (csv.file.empty() && runs.dirs.empty())
      throw UsageError("name results directories, --csv FILE, or both (reference data over runs)");
    if (reference && (csv.x_column.empty() || csv.y_column.empty()))
      throw UsageError("--csv over results directories needs --xcol and --ycol");
    const double out_dpi = dpi > 0.0 ? dpi : (size.empty() ? 72.0 : 300.0);
    if (!size.empty()) {
      if (app.count("--width") > 0 || app.count("--height") > 0)
        throw UsageError("--size sets the chart's size; give --width and --height or --size");
      if (!(size[0] > 0.0 && size[1] > 0.0)) throw UsageError("--size W,H needs W, H > 0 inches");
      options.width = int(std::lround(size[0] * out_dpi));
      options.height = int(std::lround(size[1] * out_dpi));
      if (options.width < 200 || options.height < 150 || options.width > 16384 ||
          options.height > 16384) {
        throw UsageError("--size at " + std::to_string(int(out_dpi)) + " dpi is " +
                         std::to_string(options.width) + "x" + std::to_string(options.height) +
                         " pixels: expected 200x150 to 16384 a side");
      }
    }
    if (font_points > 0.0) options.font_size = font_points * out_dpi / 72.0;
    if (panel != nullptr) options.font_size = panel->font_size;
    if (units == "none") units.clear();
    std::string x_name, y_name;
    if (csv_mode) {
      if (csv.x_column.empty() || csv.y_column.empty())
        throw UsageError("--csv needs --xcol and --ycol");
      if (!runs.y.empty() || runs.x != "t" || runs.particle != "all" || !runs.labels.empty()) {
        throw UsageError(
            "--x, --y, --particle and --label apply to results directories, not to --csv");
      }
      csv.markers = markers;
      csv.points_only = points_only;
      if (options.legend_title.empty()) options.legend_title = csv.group_column;
      x_name = csv.x_column;
      y_name = csv.y_column;
      options.x_axis.title = x_name;
      options.y_axis.title = y_name;
    } else {
      if (!reference && (!csv.x_column.empty() || !csv.y_column.empty() ||
                         !csv.group_column.empty() || points_only)) {
        throw UsageError("--xcol, --ycol, --group and --points apply to --csv");
      }
      if (runs.y.empty())
        throw UsageError("--y QUANTITY is required; allowed: " + AllowedQuantities());
      if (runs.labels.size() > runs.dirs.size()) {
        throw UsageError(std::to_string(runs.labels.size()) + " labels for " +
                         std::to_string(runs.dirs.size()) + " results directories");
      }
      options.x_axis.title = TitleWithUnits(FindQuantity(runs.x, "--x"), units);
      options.y_axis.title = TitleWithUnits(FindQuantity(runs.y, "--y"), units);
      runs.markers = markers;
      x_name = runs.x;
      y_name = runs.y;
    }
    options.x_axis.scale = log_x ? AxisScale::kLog10 : AxisScale::kLinear;
    options.y_axis.scale = log_y ? AxisScale::kLog10 : AxisScale::kLinear;
    if (!x_title.empty()) options.x_axis.title = x_title;
    if (!y_title.empty()) options.y_axis.title = y_title;
    if (!x_limits.empty()) {
      options.x_axis.fixed = true;
      options.x_axis.lo = x_limits[0];
      options.x_axis.hi = x_limits[1];
    }
    if (!y_limits.empty()) {
      options.y_axis.fixed = true;
      options.y_axis.lo = y_limits[0];
      options.y_axis.hi = y_limits[1];
    }
    // --title "" draws none.
    if (options.title.empty() && app.count("--title") == 0)
      options.title = y_name + " against " + x_name;
    const std::string path =
        out.empty() ? "chart_" + FileStem(y_name) + "_" + FileStem(x_name) + ".png" : out;
    ChartPicture picture;
    std::string legend;
    try {
      FormatOfPath(path);
      const std::vector<std::string> names =
          csv_mode ? std::vector<std::string>{} : RunNames(runs, options.legend_title);
      LineChart chart(options);
      if (csv_mode) {
        AddCsvSeries(csv, chart);
      } else {
        AddRunSeries(runs, names, chart);
        if (reference) {
          csv.markers = true;  // reference data: markers over the runs' lines
          csv.points_only = points_only || !markers;
          AddCsvSeries(csv, chart);
        }
      }
      picture = chart.Draw();
      picture.image.SetResolution(out_dpi);
      legend = chart.LegendText();
    } catch (const InvalidParameter& e) {
      throw UsageError(e.what());
    }
    if (panel != nullptr) {
      *panel->result = std::move(picture.image);
      std::cerr << "legend"
                << (options.legend_title.empty() ? "" : " (" + options.legend_title + ")") << ": "
                << legend << "\n";
      return kExitOk;
    }
    try {
      picture.image.Write(path);
    } catch (const Error& e) {
      return ReportError("chart", e.what(), kExitLocalIo);
    }
    std::cout << path << "\n";
    // The legend as text, for logs and scripts (the picture's text is not searchable in a PNG).
    std::cerr << "legend" << (options.legend_title.empty() ? "" : " (" + options.legend_title + ")")
              << ": " << legend << "\n";
    return kExitOk;
  });
}

int RunChart(int argc, char** argv) {
  if (IsStudyChart(argc, argv)) return RunStudyChart(argc, argv);  // chart_study.cc
  return RunChartCommand(argc, argv, nullptr);
}

int RunChartPanel(int argc, char** argv, const PanelRequest& request) {
  return RunChartCommand(argc, argv, &request);
}

}  // namespace dlmfd::cli
