// Line charts of y against x, several series overlaid: particle velocities, trajectories and gaps
// against time, and log-log work-precision charts (error against cost).
//
// Discrete method: each axis maps its range linearly in the value (linear axis) or in log10 of the
// value (log axis) onto the pixel centres of the plot panel, the lower end on the first pixel
// column (row from the bottom) and the upper end on the last. The range is the data's, widened by
// kPadding of its span (in decades on a log axis) so that no point sits on the frame; a range of
// zero width is widened around its value. Consecutive usable points are joined by straight
// segments; a point with a non-finite coordinate, or a value <= 0 on a log axis, is not usable and
// breaks the line (it is skipped, never drawn and never an error). An isolated usable point is
// drawn as a dot. A series without lines is drawn as markers only (scatter).
// Ticks: axis_ticks.h. Series styles: colour from the Okabe-Ito palette (distinguishable with the
// common colour-vision deficiencies) in a fixed order, then, after kPaletteSize series, the same
// colours with another dash pattern (solid, dashed, dotted, dash-dot), then with markers of
// another shape as well: kPaletteSize x kDashCount x (1 + kMarkerShapes) distinct styles.
// With equal_scale both axes show the same data length per pixel (trajectories keep their
// shape): the range of the axis with fewer units per pixel is widened about its centre.
// An axis with a fixed range [lo, hi] (the user's limits) shows that range exactly; points outside
// it are clipped by the panel.
// Layout: title on top, y-axis title written upwards left of the y tick labels, x tick labels and
// x title below the panel, legend (with its title) to the right of the panel, in as many columns
// as the panel's height needs, or, when that would leave the panel less than half the width,
// below the x title in as many columns as the width holds; legend entries are never cut (two
// entries that differ stay different), except one wider than the whole picture. Text in DejaVu
// Sans (canvas.h), font_size pixels (default: the smaller side / 46, at least 9; no upper bound),
// lines in proportion.
// Not supported: minor ticks, a second y axis.
// References: M. Okabe, K. Ito, "Color Universal Design" (2008), https://jfly.uni-koeln.de/color/.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "dlmfd/viz/axis_ticks.h"
#include "dlmfd/viz/canvas.h"
#include "dlmfd/viz/colour_map.h"

namespace dlmfd {

struct ChartSeries {
  std::string name;  // the legend entry
  std::vector<double> x;
  std::vector<double> y;
  bool markers = false;  // a marker at every usable point as well as the line
  bool lines = true;     // false: markers only, no line (a scatter plot; implies markers)
};

struct ChartAxis {
  std::string title;
  AxisScale scale = AxisScale::kLinear;
  bool fixed = false;  // the range is [lo, hi] as given (lo < hi; > 0 on a log axis)
  double lo = 0.0;
  double hi = 1.0;
};

struct LineChartOptions {
  int width = 1000;  // pixels, whole image
  int height = 700;
  std::string title;
  ChartAxis x_axis;
  ChartAxis y_axis;
  std::string legend_title;  // above the legend entries (e.g. the swept parameter)
  bool equal_scale = false;  // the same data length per pixel on both axes (linear axes only)
  double font_size = 0.0;    // text size in pixels (0: the smaller side / 46, at least 9)
};

// The drawn chart and the mapping from data to image pixels (continuous coordinates, y down; the
// pixel containing (px, py) is (floor(px), floor(py))).
struct ChartPicture {
  Canvas image{1, 1};
  int panel_left = 0;  // the plot panel inside the image, pixels; the frame is drawn just outside
  int panel_top = 0;
  int panel_width = 0;
  int panel_height = 0;
  double x_lo = 0.0, x_hi = 1.0;  // axis ranges in data values
  double y_lo = 0.0, y_hi = 1.0;
  AxisScale x_scale = AxisScale::kLinear;
  AxisScale y_scale = AxisScale::kLinear;
  AxisTicks x_ticks;
  AxisTicks y_ticks;
  bool legend_below = false;  // the legend under the panel (too wide for its right)
  double PixelX(double x) const;
  double PixelY(double y) const;
};

inline constexpr std::size_t kPaletteSize = 7;
inline constexpr std::size_t kDashCount = 4;
inline constexpr std::size_t kMarkerShapes = 4;
inline constexpr double kPadding = 0.04;

class LineChart {
 public:
  explicit LineChart(LineChartOptions options)
      : options_(std::move(options)) {}
  // Throws InvalidParameter when x and y differ in length.
  void AddSeries(ChartSeries series);
  std::size_t SeriesCount() const { return series_.size(); }
  // The legend's entries, "; "-separated, in series order.
  std::string LegendText() const;
  // Throws InvalidParameter when there is no series, no usable point in any series, the size
  // leaves no room for the panel, or equal_scale is asked with a log axis.
  ChartPicture Draw() const;
  // Draws and writes PNG, SVG or PDF by the extension of `path` (Canvas::Write).
  ChartPicture Save(const std::string& path) const;

 private:
  LineChartOptions options_;
  std::vector<ChartSeries> series_;
};

// The colour of series `index` (cycles through the palette).
Rgb SeriesColour(std::size_t index);
// The dash pattern of series `index` (changes after each kPaletteSize series; empty: solid).
Dash SeriesDash(std::size_t index);
// The marker shape of series `index`: 0 none unless asked (circle then), 1..kMarkerShapes.
int SeriesMarker(std::size_t index);

}  // namespace dlmfd
