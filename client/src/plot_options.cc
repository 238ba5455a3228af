// The shared drawing flags of plot and movie, and the captions naming a run.
#include "plot_options.h"

#include <cctype>
#include <filesystem>
#include <optional>

#include "connection.h"
#include "dlmfd/viz/node_quantities.h"
#include "fetched_job.h"

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
      "first caption line, naming the run (default: the scene title and directory, or the "
      "job's name and overrides); quantity, time and step follow");
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

void CheckPlotFlags(PlotFlags& f) {
  if (f.lines_only && f.options.isolines == 0)
    throw UsageError("--lines-only needs --isolines N (N > 0)");
  f.options.fill = !f.lines_only;
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

bool DrawsDiverging(const std::string& quantity, const PictureOptions& options) {
  return IsSignedQuantity(quantity) && !options.log_colours;
}

FieldPicture DrawFrame(const ResultsFrame& frame, const PlotFlags& flags,
                       const PictureOptions& frame_options) {
  const NodeField field = Windowed(frame.field, flags.window);
  PictureOptions options = frame_options;
  options.diverging = DrawsDiverging(field.quantity, options);
  if (options.arrows > 0 && !frame.has_velocity)
    throw UsageError("--arrows: " + frame.snapshot_path + " has no velocity (/u, /v)");
  if (options.arrows == 0) return DrawFieldPicture(field, frame.disks, options);
  const NodeVelocity velocity{Windowed(frame.velocity.u, flags.window),
                              Windowed(frame.velocity.v, flags.window)};
  return DrawFieldPicture(field, frame.disks, options, &velocity);
}

std::string FrameCaption(const std::string& quantity, double time, long step) {
  return quantity + "   t = " + FormatLabel(time) + "   step " + std::to_string(step);
}

std::string DirectoryCaption(const std::string& results_dir) {
  if (const std::optional<v1::Job> job = ReadFetchedJob(results_dir)) return JobCaption(*job);
  std::filesystem::path path = std::filesystem::path(results_dir).lexically_normal();
  if (path.filename().empty()) path = path.parent_path();
  const std::string name = path.filename().string();
  const std::string title = SceneTitle(results_dir);
  if (title.empty()) return name;
  return title + "   |   " + name;
}

std::string JobCaption(const v1::Job& job) {
  std::string text = job.name().empty() ? "job " + job.id() : job.name();
  std::string overrides;
  for (const std::string& o : job.overrides()) overrides += (overrides.empty() ? "" : ", ") + o;
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
