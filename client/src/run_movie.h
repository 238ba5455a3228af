// The movie of a results directory that `dlmfd movie` writes and the web dashboard shows: one
// frame per chosen snapshot, each a field picture (plot_options.h: DrawFrame) with the particles,
// its caption (the run's lines, then quantity, time and step; FrameOptions) and the colour bar, the
// colour range the same in every frame (the flags' --range, else the union of the frames' own
// ranges, inside the window: extremes, or percentiles for a signed quantity, [-m, m] on the
// diverging map), encoded by Debian's ffmpeg
// (viz/movie_encoder.h). The frame size is the first frame's, rounded up to even sides (H.264).
#pragma once

#include <string>
#include <vector>

#include "plot_options.h"

namespace dlmfd::cli {

struct MovieSummary {
  long frames = 0;
  int width = 0;
  int height = 0;
};

// Writes the movie of `steps` (snapshot steps of `dir`) to `out` at `fps` frames a second. Sets
// plot's fixed range and exact size as drawn. Throws InvalidParameter (flags, sizes), Error
// (files, ffmpeg).
MovieSummary WriteRunMovie(const std::string& dir, const std::vector<long>& steps,
                           const std::string& run_caption, PlotFlags& plot, const std::string& out,
                           double fps, const std::string& ffmpeg);

}  // namespace dlmfd::cli
