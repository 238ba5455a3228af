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
// Ticks: on a linear axis the multiples of a 1-2-5 step (1, 2 or 5 times a power of ten) inside the
// range, the step the smallest giving no more than the wanted count; on a log axis the 1, 2 and 5
// multiples of the decades when the range holds fewer than three decades and those are not too
// many, else the decades inside the range (every k-th decade when there are many), or linear
// 1-2-5 ticks when the range holds fewer than two of either. Series colours come from the
// Okabe-Ito palette (distinguishable with the common colour-vision deficiencies) in a fixed order
// and repeat after kPaletteSize series.
// Layout: title on top, y-axis title above the y tick labels, x tick labels and x title below the
// panel, legend to the right of the panel; the font scale grows with the picture.
// Not supported: minor ticks, dashed lines, user-set axis ranges, a second y axis, rotated text,
// legends taller than the panel (the entries that do not fit are cut off at the image edge).
// References: P. Heckbert, "Nice numbers for graph labels", Graphics Gems (1990); M. Okabe,
// K. Ito, "Color Universal Design" (2008), https://jfly.uni-koeln.de/color/.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "dlmfd/viz/colour_map.h"
#include "dlmfd/viz/raster_image.h"

namespace dlmfd {

enum class AxisScale { kLinear, kLog10 };

struct ChartSeries {
  std::string name;  // the legend entry
  std::vector<double> x;
  std::vector<double> y;
  bool markers = false;  // a filled disk at every usable point as well as the line
  bool lines = true;     // false: markers only, no line (a scatter plot; implies markers)
};

struct ChartAxis {
  std::string title;
  AxisScale scale = AxisScale::kLinear;
};

struct AxisTicks {
  std::vector<double> values;  // increasing, inside the axis range
  std::vector<std::string> labels;
};

struct LineChartOptions {
  int width = 1000;  // pixels, whole image
  int height = 700;
  std::string title;
  ChartAxis x_axis;
  ChartAxis y_axis;
};

// The drawn chart and the mapping from data to image pixels (continuous coordinates, y down; the
// pixel containing (px, py) is (floor(px), floor(py))).
struct ChartPicture {
  RasterImage image{1, 1};
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
  double PixelX(double x) const;
  double PixelY(double y) const;
};

inline constexpr std::size_t kPaletteSize = 7;
inline constexpr double kPadding = 0.04;

class LineChart {
 public:
  explicit LineChart(LineChartOptions options)
      : options_(std::move(options)) {}
  // Throws InvalidParameter when x and y differ in length.
  void AddSeries(ChartSeries series);
  std::size_t SeriesCount() const { return series_.size(); }
  // Throws InvalidParameter when there is no series, no usable point in any series, or the size
  // leaves no room for the panel.
  ChartPicture Draw() const;

 private:
  LineChartOptions options_;
  std::vector<ChartSeries> series_;
};

// The colour of series `index` (cycles through the palette).
Rgb SeriesColour(std::size_t index);
// Whether a value can be placed on an axis of this scale (finite, and > 0 on a log axis).
bool Usable(double value, AxisScale scale);
// 1-2-5 ticks inside [lo, hi] (lo < hi, finite), at most max(2, wanted) + 1 of them.
AxisTicks LinearTicks(double lo, double hi, int wanted);
// Ticks of a log axis on [lo, hi] (0 < lo < hi, finite), see the header block.
AxisTicks LogTicks(double lo, double hi, int wanted);

}  // namespace dlmfd
