// A panel of `dlmfd figure`: a `plot` or `chart` command line drawn into a canvas of exactly the
// panel's size with the figure's text size, instead of a file. The commands parse their own flags
// (the same code as `dlmfd plot` and `dlmfd chart`), so a panel takes every flag they take, except
// the size flags (--width, --height, --size, --dpi, --font-size), which the figure sets.
#pragma once

#include <optional>

#include "dlmfd/viz/canvas.h"

namespace dlmfd::cli {

struct PanelRequest {
  int width = 0;  // pixels
  int height = 0;
  double font_size = 0.0;                   // pixels
  std::optional<Canvas>* result = nullptr;  // receives the drawn panel
};

// RunPlot / RunChart with a panel request: nothing is written, the picture goes to
// request.result; the exit code and messages are the commands' own.
int RunPlotPanel(int argc, char** argv, const PanelRequest& request);
int RunChartPanel(int argc, char** argv, const PanelRequest& request);

}  // namespace dlmfd::cli
