// The drawing flags that `dlmfd plot` and `dlmfd movie` share (quantity, size, colour scale,
// window, isolines, arrows) and the captions that name a run: its scene title and directory, or a
// job's name and overrides (the swept parameters of a sweep's job; also for a directory that
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
};

void AddPlotFlags(CLI::App& app, PlotFlags& flags);
// Applies --range and --lines-only to the options; throws UsageError for inconsistent flags.
void CheckPlotFlags(PlotFlags& flags);
// The field (and the velocity) inside the window, or the whole field when no window was given.
NodeField Windowed(const NodeField& field, const std::vector<double>& window);
// Whether `quantity` is drawn on the diverging map: a signed quantity (node_quantities.h) on a
// linear scale; with --log it stays on viridis (its positive values only).
bool DrawsDiverging(const std::string& quantity, const PictureOptions& options);
// Draws a results frame with the flags (window applied to the field and the arrows), on the
// diverging map for a signed quantity.
FieldPicture DrawFrame(const ResultsFrame& frame, const PlotFlags& flags,
                       const PictureOptions& options);

// "trA  t = 1.5  step 3750".
std::string FrameCaption(const std::string& quantity, double time, long step);
// A fetched directory (its job.json, fetched_job.h): JobCaption of its job, as for the job on the
// daemon; else "<scene title>  |  <directory name>" (the title only when the scene has one).
// Throws InvalidParameter for a job.json that is not a job's JSON.
std::string DirectoryCaption(const std::string& results_dir);
// "<job name>  |  key=value, ..." (the overrides as submitted; a sweep's point is among them).
std::string JobCaption(const v1::Job& job);
// The quantity as a file-name part: letters, digits, '-' and '_' ("log10(trA/2)" -> "log10_trA_2").
std::string FileStemOf(const std::string& quantity);

}  // namespace dlmfd::cli
