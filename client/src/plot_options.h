// The drawing flags that `dlmfd plot` and `dlmfd movie` share (quantity, size, colour scale,
// window, isolines, arrows) and the captions that name a run: its scene title and directory, or a
// job's name and overrides (the swept parameters of a study's job; also for a directory that
// dlmfd fetch wrote, from its job.json), then quantity, time and step.
#pragma once

#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "dlmfd/v1/jobs.pb.h"
#include "dlmfd/viz/field_picture.h"
#include "dlmfd/viz/results_frame.h"

namespace dlmfd::cli {

struct PlotFlags {
  std::string quantity;        // "" : trA when present, else the speed
  PictureOptions options;      // size, caption, log, isolines, arrows
  std::vector<double> window;  // X0, Y0, X1, Y1 or empty
  std::vector<double> range;   // MIN, MAX or empty
  bool lines_only = false;
  bool no_caption = false;     // --no-caption, or --caption ""
  bool caption_given = false;  // --caption TEXT replaces the run's lines
  std::vector<double> size;    // --size W,H in inches (with --dpi), or empty
  double dpi = 0.0;            // --dpi (default 300 with --size, else 72: pixels are points)
  double font_points = 0.0;    // --font-size in points (0: grows with the picture)
  std::string units;           // --units cgs|si|none
  double percentile = -1.0;    // --percentile (default: 99 for signed quantities, else 100)
  std::string x_title, y_title;
};

// Adds the drawing flags; `publication` adds those of a figure's size, resolution and text.
void AddPlotFlags(CLI::App& app, PlotFlags& flags);
// Applies --range, --lines-only, --size/--dpi/--font-size and --units to the options; throws
// UsageError for inconsistent flags. Call after parsing (app gives --caption's count).
void CheckPlotFlags(PlotFlags& flags, const CLI::App& app);
// The options of one frame of `quantity`: axis titles and the colour bar's label with units, the
// default percentile of a signed quantity, the caption (run lines + "\n" + frame line, none with
// --no-caption).
PictureOptions FrameOptions(const PlotFlags& flags, const std::string& quantity,
                            const std::string& run_caption, const std::string& frame_caption);
// The resolution a picture is written at (Canvas::SetResolution).
double OutputDpi(const PlotFlags& flags);
// "%.4g" of a number ("0.001" for 0.0010000000000000002); with `reciprocal` (mesh sizes) "1/24"
// for 0.041666666666666664 (1/value within 1e-9 of a whole number up to 100000). A text that is
// not a number stays as it is. Captions name settings with it.
std::string SettingText(const std::string& value, bool reciprocal = false);
// "h = 1/24   dt = 0.001   h_p = 1/18   lambda = 1.4   eta = 0.12" from results_dir/scene.toml
// (the settings as run; "" without a scene.toml).
std::string SettingsCaption(const std::string& results_dir);
// The field (and the velocity) inside the window, or the whole field when no window was given.
NodeField Windowed(const NodeField& field, const std::vector<double>& window);
// Whether `quantity` is drawn on the diverging map: a signed quantity (node_quantities.h) on a
// linear scale; with --log it stays on viridis (its positive values only).
bool DrawsDiverging(const std::string& quantity, const PictureOptions& options);
// Draws a results frame with the flags (window applied to the field and the arrows), on the
// diverging map for a signed quantity.
FieldPicture DrawFrame(const ResultsFrame& frame, const PlotFlags& flags,
                       const PictureOptions& options);

// "trA   t = 1.5   step 3750".
std::string FrameCaption(const std::string& quantity, double time, long step);
// A fetched directory (its job.json, fetched_job.h): JobCaption of its job, as for the job on the
// daemon; else "<scene title>  |  <directory name>" (the title only when the scene has one); then,
// as a paragraph of its own, SettingsCaption: the run's real mesh, time step and liquid.
// Throws InvalidParameter for a job.json that is not a job's JSON.
std::string DirectoryCaption(const std::string& results_dir);
// "<job name>  |  key = value, ..." (the overrides as submitted, numbers by SettingText; a study's
// point is among them).
std::string JobCaption(const v1::Job& job);
// The quantity as a file-name part: letters, digits, '-' and '_' ("log10(trA/2)" -> "log10_trA_2").
std::string FileStemOf(const std::string& quantity);

}  // namespace dlmfd::cli
