#include "run_movie.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>

#include "dlmfd/viz/movie_encoder.h"
#include "dlmfd/viz/results_frame.h"

namespace dlmfd::cli {
namespace {

// The q-quantile of `values` (not empty; nearest order statistic).
double QuantileOf(std::vector<double>& values, double q) {
  const std::size_t k = std::size_t(std::lround(q * double(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

// The colour range over the frames (inside the window; positive values for a log scale;
// symmetric about zero, [-m, m], for a signed quantity on the diverging map): the union of each
// frame's range, its extremes or, with a percentile below 100 (the default 99 of a signed
// quantity, --percentile), its percentiles, as each picture would take them.
void CommonRange(const std::string& dir, const std::vector<long>& steps, PlotFlags& plot) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  bool diverging = false;
  for (const long step : steps) {
    const NodeField field = Windowed(LoadResultsFrame(dir, step, plot.quantity).field, plot.window);
    diverging = DrawsDiverging(field.quantity, plot.options);
    const double p = FrameOptions(plot, field.quantity, "", "").percentile / 100.0;
    std::vector<double> usable;
    for (const double v : field.values) {
      if (!std::isfinite(v) || (plot.options.log_colours && !(v > 0.0))) continue;
      usable.push_back(diverging ? std::abs(v) : v);
    }
    if (usable.empty()) continue;
    if (diverging) {
      hi = std::max(hi, QuantileOf(usable, p));
      lo = std::min(lo, -hi);
    } else {
      lo = std::min(lo, QuantileOf(usable, 1.0 - p));
      hi = std::max(hi, QuantileOf(usable, p));
    }
  }
  if (!(lo <= hi)) return;  // no usable value anywhere: each frame's own (grey) scale
  if (diverging) {
    hi = std::max(std::abs(lo), std::abs(hi));
    lo = -hi;
  }
  plot.options.fixed_range = true;
  plot.options.range_min = lo;
  plot.options.range_max = hi;
}

}  // namespace

MovieSummary WriteRunMovie(const std::string& dir, const std::vector<long>& steps,
                           const std::string& run_caption, PlotFlags& plot, const std::string& out,
                           double fps, const std::string& ffmpeg) {
  if (!plot.options.fixed_range) CommonRange(dir, steps, plot);
  std::unique_ptr<MovieEncoder> movie;
  for (const long step : steps) {
    const ResultsFrame frame = LoadResultsFrame(dir, step, plot.quantity);
    if (!frame.particles_note.empty())
      std::cerr << "dlmfd movie: step " << step << ": " << frame.particles_note << "\n";
    PictureOptions options =
        FrameOptions(plot, frame.field.quantity, run_caption,
                     FrameCaption(frame.field.quantity, frame.time, frame.step));
    if (!movie) {
      // The first frame sets the size: its natural one, rounded up to even sides.
      const FieldPicture natural = DrawFrame(frame, plot, options);
      plot.options.exact_width = natural.image.Width() + natural.image.Width() % 2;
      plot.options.exact_height = natural.image.Height() + natural.image.Height() % 2;
      movie = std::make_unique<MovieEncoder>(out, plot.options.exact_width,
                                             plot.options.exact_height, fps, ffmpeg);
      options.exact_width = plot.options.exact_width;
      options.exact_height = plot.options.exact_height;
    }
    movie->AddFrame(DrawFrame(frame, plot, options).image.Rasterise());
  }
  MovieSummary result;
  result.frames = movie ? movie->Finish() : 0;
  result.width = plot.options.exact_width;
  result.height = plot.options.exact_height;
  return result;
}

}  // namespace dlmfd::cli
