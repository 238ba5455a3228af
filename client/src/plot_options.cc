// The shared drawing flags of plot and movie, and the captions naming a run.
#include "plot_options.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include "connection.h"
#include "dlmfd/io/results_format.h"
#include "dlmfd/viz/node_quantities.h"
#include "fetched_job.h"
#include "scene_differences.h"

namespace dlmfd::cli {

void AddPlotFlags(CLI::App& app, PlotFlags& f) {
  f.options.max_width = 1000;
  f.options.max_height = 1000;
  app.add_option("--quantity", f.quantity,
                 "field to draw: " + PictureQuantityList() + " (default: trA when present)")
      ->check(CLI::IsMember(PictureQuantities()));
  app.add_option("--width", f.options.max_width, "largest image width in pixels")
      ->check(CLI::Range(64, 8192));
  app.add_option("--height", f.options.max_height, "largest image height in pixels")
      ->check(CLI::Range(64, 8192));
  app.add_option(
      "--caption", f.options.caption,
      "the caption's lines naming the run (default: the scene title and directory, or the job's "
      "name and overrides, then the run's mesh, time step and liquid); quantity, time and step "
      "follow; --caption \"\" draws no caption");
  app.add_flag("--no-caption", f.no_caption, "draw no caption at all");
  app.add_option("--size", f.size,
                 "figure size in inches W,H (with --dpi: the image is W*dpi x H*dpi pixels, "
                 "PDF and SVG pages W x H inches); replaces --width and --height")
      ->expected(2)
      ->delimiter(',');
  app.add_option("--dpi", f.dpi,
                 "resolution in dots per inch (default 300 with --size, else 72: one pixel a "
                 "point); text and lines scale with it")
      ->check(CLI::Range(10.0, 4800.0));
  app.add_option("--font-size", f.font_points,
                 "text size in points at --dpi (default: grows with the picture)")
      ->check(CLI::Range(2.0, 200.0));
  app.add_option("--units", f.units,
                 "unit names for axis titles, the colour bar and the arrow key: cgs (cm, g, s), "
                 "si (m, kg, s) or none (default: no units; the files hold the dimensions)")
      ->check(CLI::IsMember({"cgs", "si", "none"}));
  app.add_option("--xtitle", f.x_title, "title of the x axis (default: x, with units)");
  app.add_option("--ytitle", f.y_title, "title of the y axis (default: y, with units)");
  app.add_option("--percentile", f.percentile,
                 "automatic colour range from this percentile of the values (|values| of a signed "
                 "quantity); beyond it the end colours, marked on the bar (default: 99 for "
                 "vorticity, A12 and pressure, 100 otherwise)")
      ->check(CLI::Range(50.0, 100.0));
  app.add_option("--streamlines", f.options.streamlines,
                 "evenly spaced streamlines seeded on a lattice of N columns (0: none)")
      ->check(CLI::Range(0, 200));
  app.add_flag("--log", f.options.log_colours,
               "logarithmic colour scale (ticks at 1-2-5 multiples or decades); with trA-2 it "
               "shows the stretch over decades");
  app.add_option("--range", f.range, "fixed colour range MIN,MAX (default: the field's extremes)")
      ->expected(2)
      ->delimiter(',');
  app.add_option("--window", f.window, "draw only [X0, X1] x [Y0, Y1] of the domain: X0,Y0,X1,Y1")
      ->expected(4)
      ->delimiter(',');
  app.add_option("--isolines", f.options.isolines,
                 "draw N isovalues evenly spaced inside the colour range (0: none)")
      ->check(CLI::Range(0, 100));
  app.add_flag("--lines-only", f.lines_only,
               "with --isolines: the isolines in black on white, no colours (the paper's figures)");
  app.add_option("--arrows", f.options.arrows,
                 "velocity arrows on a lattice of N columns (0: none)")
      ->check(CLI::Range(0, 200));
}

void CheckPlotFlags(PlotFlags& f, const CLI::App& app) {
  if (f.lines_only && f.options.isolines == 0)
    throw UsageError("--lines-only needs --isolines N (N > 0)");
  f.options.fill = !f.lines_only;
  f.caption_given = app.count("--caption") > 0;
  if (f.caption_given && f.options.caption.empty()) f.no_caption = true;
  if (!f.size.empty()) {
    if (!(f.size[0] > 0.0 && f.size[1] > 0.0))
      throw UsageError("--size W,H needs W > 0 and H > 0 inches");
    if (app.count("--width") > 0 || app.count("--height") > 0)
      throw UsageError("--size sets the image size; give --width and --height or --size, not both");
    const double dpi = OutputDpi(f);
    f.options.max_width = int(std::lround(f.size[0] * dpi));
    f.options.max_height = int(std::lround(f.size[1] * dpi));
    if (f.options.max_width < 64 || f.options.max_height < 64 || f.options.max_width > 16384 ||
        f.options.max_height > 16384) {
      throw UsageError("--size " + FormatLabel(f.size[0]) + "," + FormatLabel(f.size[1]) + " at " +
                       FormatLabel(dpi) + " dpi is " + std::to_string(f.options.max_width) + "x" +
                       std::to_string(f.options.max_height) +
                       " pixels: expected 64 to 16384 pixels a side");
    }
  }
  if (f.font_points > 0.0) f.options.font_size = f.font_points * OutputDpi(f) / 72.0;
  if (!f.range.empty()) {
    if (!(f.range[0] < f.range[1])) throw UsageError("--range MIN,MAX needs MIN < MAX");
    if (f.options.log_colours && !(f.range[0] > 0.0))
      throw UsageError("--range with --log needs 0 < MIN < MAX");
    f.options.fixed_range = true;
    f.options.range_min = f.range[0];
    f.options.range_max = f.range[1];
  }
}

NodeField Windowed(const NodeField& field, const std::vector<double>& window) {
  if (window.empty()) return field;
  return CropField(field, window[0], window[1], window[2], window[3]);
}

double OutputDpi(const PlotFlags& f) {
  if (f.dpi > 0.0) return f.dpi;
  return f.size.empty() ? 72.0 : 300.0;
}

PictureOptions FrameOptions(const PlotFlags& f, const std::string& quantity,
                            const std::string& run_caption, const std::string& frame_caption) {
  PictureOptions options = f.options;
  const auto with_units = [&](const std::string& title, const std::string& dimensions) {
    const std::string units = f.units.empty() ? "" : UnitsIn(dimensions, f.units);
    return units.empty() ? title : title + " (" + units + ")";
  };
  options.x_title = f.x_title.empty() ? with_units("x", "L") : f.x_title;
  options.y_title = f.y_title.empty() ? with_units("y", "L") : f.y_title;
  options.colour_label = with_units(quantity, QuantityDimensions(quantity));
  options.speed_units = f.units.empty() ? "" : UnitsIn("L T-1", f.units);
  options.percentile =
      f.percentile > 0.0 ? f.percentile : (IsSignedQuantity(quantity) ? 99.0 : 100.0);
  if (f.no_caption) {
    options.caption.clear();
  } else {
    const std::string run = f.caption_given ? f.options.caption : run_caption;
    options.caption = run.empty() ? frame_caption : run + "\n" + frame_caption;
  }
  return options;
}

std::string SettingText(const std::string& value, bool reciprocal) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || end == value.c_str() || *end != '\0' || !std::isfinite(v)) return value;
  if (reciprocal && v > 0.0 && v < 1.0) {
    const double n = 1.0 / v;
    if (n <= 100000.0 && std::abs(n - std::round(n)) <= 1e-9 * n)
      return "1/" + std::to_string(std::lround(n));
  }
  return FormatLabel(v);
}

std::string SettingsCaption(const std::string& results_dir) {
  const FlatScene scene = ReadFlatScene(results_dir);
  if (scene.empty()) return "";
  std::string text;
  const auto add = [&](const char* label, const char* key, bool mesh = false) {
    const auto it = scene.find(key);
    if (it == scene.end()) return;
    text +=
        (text.empty() ? "" : ",  ") + std::string(label) + " = " + SettingText(it->second, mesh);
  };
  add("h", "domain.h", true);
  add("dt", "time.dt");
  if (scene.count("particles.0.density") > 0) add("h_p", "particle_mesh.h", true);
  add("eta", "fluid.viscosity");
  const auto lambda = scene.find("fluid.relaxation_time");
  if (lambda != scene.end() && std::strtod(lambda->second.c_str(), nullptr) > 0.0) {
    add("lambda", "fluid.relaxation_time");
    add("beta", "fluid.solvent_ratio");
  }
  return text;
}

bool DrawsDiverging(const std::string& quantity, const PictureOptions& options) {
  return IsSignedQuantity(quantity) && !options.log_colours;
}

FieldPicture DrawFrame(const ResultsFrame& frame, const PlotFlags& flags,
                       const PictureOptions& frame_options) {
  const NodeField field = Windowed(frame.field, flags.window);
  PictureOptions options = frame_options;
  options.diverging = DrawsDiverging(field.quantity, options);
  if ((options.arrows > 0 || options.streamlines > 0) && !frame.has_velocity) {
    throw UsageError(std::string(options.arrows > 0 ? "--arrows: " : "--streamlines: ") +
                     frame.snapshot_path + " has no velocity (/u, /v)");
  }
  if (options.arrows == 0 && options.streamlines == 0)
    return DrawFieldPicture(field, frame.disks, options);
  const NodeVelocity velocity{Windowed(frame.velocity.u, flags.window),
                              Windowed(frame.velocity.v, flags.window)};
  return DrawFieldPicture(field, frame.disks, options, &velocity);
}

std::string FrameCaption(const std::string& quantity, double time, long step) {
  return quantity + "   t = " + FormatLabel(time) + "   step " + std::to_string(step);
}

std::string DirectoryCaption(const std::string& results_dir) {
  std::string run;
  if (const std::optional<v1::Job> job = ReadFetchedJob(results_dir)) {
    run = JobCaption(*job);
  } else {
    std::filesystem::path path = std::filesystem::path(results_dir).lexically_normal();
    if (path.filename().empty()) path = path.parent_path();
    const std::string name = path.filename().string();
    const std::string title = SceneTitle(results_dir);
    run = title.empty() ? name : title + "   |   " + name;
  }
  const std::string settings = SettingsCaption(results_dir);
  return settings.empty() ? run : run + "\n" + settings;
}

std::string JobCaption(const v1::Job& job) {
  std::string text = job.name().empty() ? "job " + job.id() : job.name();
  std::string overrides;
  for (const std::string& o : job.overrides()) {
    const std::size_t equals = o.find('=');
    const std::string shown =
        equals == std::string::npos
            ? o
            : o.substr(0, equals) + " = " +
                  SettingText(o.substr(equals + 1),
                              o.substr(0, equals).find(".h") != std::string::npos);
    overrides += (overrides.empty() ? "" : ", ") + shown;
  }
  return overrides.empty() ? text : text + "   |   " + overrides;
}

std::string FileStemOf(const std::string& quantity) {
  std::string stem;
  for (const char c : quantity) {
    const bool plain = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
    if (plain) {
      stem += c;
    } else if (!stem.empty() && stem.back() != '_') {
      stem += '_';
    }
  }
  while (!stem.empty() && stem.back() == '_') stem.pop_back();
  return stem;
}

}  // namespace dlmfd::cli
