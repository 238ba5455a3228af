// LineChart: axis ranges and ticks from the usable points, then layout, grid, frame, labels,
// series and legend drawn on a Canvas.
#include "dlmfd/viz/line_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>

#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

// Okabe-Ito without its yellow, which is too pale on white: blue, vermillion, bluish green,
// reddish purple, orange, sky blue, black.
constexpr Rgb kPalette[kPaletteSize] = {{0, 114, 178},   {213, 94, 0},  {0, 158, 115},
                                        {204, 121, 167}, {230, 159, 0}, {86, 180, 233},
                                        {0, 0, 0}};
constexpr Rgb kGridColour{225, 225, 225};

double Transform(double value, AxisScale scale) {
  return scale == AxisScale::kLog10 ? std::log10(value) : value;
}

// The widened range [lo, hi] of the usable values of one axis.
void AxisRange(double data_lo, double data_hi, AxisScale scale, double& lo, double& hi) {
  double t_lo = Transform(data_lo, scale);
  double t_hi = Transform(data_hi, scale);
  if (t_hi - t_lo <= 1e-12 * std::max(1.0, std::abs(t_lo))) {
    const double half =
        scale == AxisScale::kLog10 ? 0.5 : (t_lo != 0.0 ? 0.1 * std::abs(t_lo) : 1.0);
    t_lo -= half;
    t_hi += half;
  } else {
    const double pad = kPadding * (t_hi - t_lo);
    t_lo -= pad;
    t_hi += pad;
  }
  lo = scale == AxisScale::kLog10 ? std::pow(10.0, t_lo) : t_lo;
  hi = scale == AxisScale::kLog10 ? std::pow(10.0, t_hi) : t_hi;
}

std::string Short(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

double PixelAlong(double value, double lo, double hi, AxisScale scale, int first, int count,
                  bool reversed) {
  if (!Usable(value, scale)) return std::numeric_limits<double>::quiet_NaN();
  const double t_lo = Transform(lo, scale);
  const double fraction = (Transform(value, scale) - t_lo) / (Transform(hi, scale) - t_lo);
  return first + 0.5 + (reversed ? 1.0 - fraction : fraction) * (count - 1);
}

}  // namespace

Rgb SeriesColour(std::size_t index) { return kPalette[index % kPaletteSize]; }

Dash SeriesDash(std::size_t index) {
  static const Dash kDashes[kDashCount] = {{}, {5.0, 2.5}, {1.0, 2.0}, {5.0, 2.0, 1.0, 2.0}};
  return kDashes[(index / kPaletteSize) % kDashCount];
}

int SeriesMarker(std::size_t index) {
  return int((index / (kPaletteSize * kDashCount)) % (kMarkerShapes + 1));
}

double ChartPicture::PixelX(double x) const {
  return PixelAlong(x, x_lo, x_hi, x_scale, panel_left, panel_width, false);
}

double ChartPicture::PixelY(double y) const {
  return PixelAlong(y, y_lo, y_hi, y_scale, panel_top, panel_height, true);
}

void LineChart::AddSeries(ChartSeries series) {
  if (series.x.size() != series.y.size()) {
    throw InvalidParameter("series " + series.name,
                           std::to_string(series.x.size()) + " x values and " +
                               std::to_string(series.y.size()) + " y values",
                           "as many x values as y values");
  }
  series_.push_back(std::move(series));
}

namespace {

// A marker of shape 1 (disk), 2 (square), 3 (triangle) or 4 (diamond) of half-size r.
void DrawMarker(Canvas& canvas, int shape, double x, double y, double r, Rgb colour) {
  switch (shape) {
    case 2:
      canvas.FillRect(x - 0.85 * r, y - 0.85 * r, 1.7 * r, 1.7 * r, colour);
      break;
    case 3:
      canvas.FillPolygon({x, y - 1.15 * r, x + r, y + 0.65 * r, x - r, y + 0.65 * r}, colour);
      break;
    case 4:
      canvas.FillPolygon({x, y - 1.2 * r, x + r, y, x, y + 1.2 * r, x - r, y}, colour);
      break;
    default:
      canvas.FillCircle(x, y, r, colour);
  }
}

double LabelsWidth(const Canvas& canvas, const AxisTicks& ticks, double size) {
  double width = 0.0;
  for (const std::string& label : ticks.labels)
    width = std::max(width, canvas.MeasureText(label, size).advance);
  return width;
}

// `name` cut (with "..") to fit in `width` pixels.
std::string Fitted(const Canvas& canvas, const std::string& name, double size, double width) {
  if (canvas.MeasureText(name, size).advance <= width) return name;
  std::string cut = name;
  while (cut.size() > 1 && canvas.MeasureText(cut + "..", size).advance > width) cut.pop_back();
  return cut + "..";
}

// Widens the range of the axis with fewer data units per pixel about its centre so that both
// show the same units per pixel.
void EqualiseScales(ChartPicture& p) {
  const double x_per_pixel = (p.x_hi - p.x_lo) / std::max(1, p.panel_width - 1);
  const double y_per_pixel = (p.y_hi - p.y_lo) / std::max(1, p.panel_height - 1);
  if (x_per_pixel < y_per_pixel) {
    const double half = 0.5 * y_per_pixel * std::max(1, p.panel_width - 1);
    const double centre = 0.5 * (p.x_lo + p.x_hi);
    p.x_lo = centre - half;
    p.x_hi = centre + half;
  } else {
    const double half = 0.5 * x_per_pixel * std::max(1, p.panel_height - 1);
    const double centre = 0.5 * (p.y_lo + p.y_hi);
    p.y_lo = centre - half;
    p.y_hi = centre + half;
  }
}

}  // namespace

// NOLINTNEXTLINE(readability-function-size): predates the limit; split it when you change it
ChartPicture LineChart::Draw() const {
  const AxisScale xs = options_.x_axis.scale;
  const AxisScale ys = options_.y_axis.scale;
  if (series_.empty())
    throw InvalidParameter("chart", "no series", "at least one series of points");
  if (options_.equal_scale && (xs != AxisScale::kLinear || ys != AxisScale::kLinear)) {
    throw InvalidParameter("chart axes", "equal scales with a log axis",
                           "equal scales on two linear axes only");
  }
  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
  double y_min = x_min, y_max = -x_min;
  for (const ChartSeries& s : series_) {
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      if (!Usable(s.x[k], xs) || !Usable(s.y[k], ys)) continue;
      x_min = std::min(x_min, s.x[k]);
      x_max = std::max(x_max, s.x[k]);
      y_min = std::min(y_min, s.y[k]);
      y_max = std::max(y_max, s.y[k]);
    }
  }
  if (!(x_min <= x_max)) {
    const bool log = xs == AxisScale::kLog10 || ys == AxisScale::kLog10;
    throw InvalidParameter("chart",
                           "no usable point in " + std::to_string(series_.size()) + " series",
                           log ? "at least one point with finite coordinates, > 0 on a log axis"
                               : "at least one point with finite coordinates");
  }

  ChartPicture p;
  p.x_scale = xs;
  p.y_scale = ys;
  AxisRange(x_min, x_max, xs, p.x_lo, p.x_hi);
  AxisRange(y_min, y_max, ys, p.y_lo, p.y_hi);
  for (const auto& [axis, lo, hi, name] : {std::tuple{&options_.x_axis, &p.x_lo, &p.x_hi, "x"},
                                           std::tuple{&options_.y_axis, &p.y_lo, &p.y_hi, "y"}}) {
    if (!axis->fixed) continue;
    if (!(axis->lo < axis->hi) || !std::isfinite(axis->lo) || !std::isfinite(axis->hi) ||
        (axis->scale == AxisScale::kLog10 && !(axis->lo > 0.0))) {
      throw InvalidParameter(std::string(name) + " limits", Short(axis->lo) + "," + Short(axis->hi),
                             "finite LO < HI (LO > 0 on a log axis)");
    }
    *lo = axis->lo;
    *hi = axis->hi;
  }

  const int width = options_.width;
  const int height = options_.height;
  p.image = Canvas(width, height);
  Canvas& canvas = p.image;
  // Text sizes in pixels grow with the picture (15 px labels on a 1000 x 700 chart, no upper
  // bound), or are the caller's.
  const double fs =
      options_.font_size > 0.0 ? options_.font_size : std::max(9.0, std::min(width, height) / 46.0);
  const double title_fs = 1.2 * fs;
  const double margin = 0.8 * fs;
  const double tick = 0.4 * fs;
  const double line_height = 1.35 * fs;

  // The legend: to the right of the panel in columns of the panel's height, or, when that takes
  // more than half the width, below the x title in rows of as many columns as the width holds.
  const double swatch = 2.4 * fs;
  double name_width = 0.0;
  for (const ChartSeries& series : series_)
    name_width = std::max(name_width, canvas.MeasureText(series.name, fs).advance);
  const double title_width = options_.legend_title.empty()
                                 ? 0.0
                                 : canvas.MeasureText(options_.legend_title, fs, true).advance;
  const double legend_title_height = options_.legend_title.empty() ? 0.0 : line_height;
  const double column_width =
      std::min(swatch + 0.5 * fs + name_width + margin, width - 2.0 * margin);
  const double title_height = options_.title.empty() ? 0.0 : 1.6 * title_fs;
  const double x_title_height = options_.x_axis.title.empty() ? 0.0 : line_height;
  const double top = std::ceil(margin + title_height + 0.5 * fs);
  const double side_panel_height = height - top - margin - x_title_height - line_height - tick - 1;
  const int side_rows = std::max(1, int((side_panel_height - legend_title_height) / line_height));
  const int side_columns = int((series_.size() + side_rows - 1) / side_rows);
  const double side_width =
      std::max(side_columns * column_width, title_width == 0.0 ? 0.0 : title_width + margin);
  p.legend_below = side_width > 0.5 * width;
  int rows_per_column = side_rows;
  int legend_columns = side_columns;
  double legend_width = side_width;
  double below_height = 0.0;
  if (p.legend_below) {
    legend_columns = std::max(1, int((width - 2.0 * margin) / column_width));
    const int rows = int((series_.size() + legend_columns - 1) / legend_columns);
    rows_per_column = rows;
    legend_width = 0.0;
    below_height = 0.5 * fs + legend_title_height + rows * line_height;
  }

  // Vertical layout: it does not depend on the tick labels.
  p.panel_top = int(top);
  p.panel_height =
      int(height - p.panel_top - margin - x_title_height - line_height - tick - 1 - below_height);
  if (p.panel_height < 32) {
    throw InvalidParameter("chart height", std::to_string(height),
                           "room for a panel of at least 32 pixels (a taller chart, or fewer "
                           "series in the legend)");
  }
  const int y_wanted = std::clamp(int(p.panel_height / (3.0 * fs)), 2, 8);
  p.y_ticks = ScaleTicks(p.y_lo, p.y_hi, y_wanted, ys);

  // Horizontal layout: y title and labels on the left, the legend on the right (or below).
  const double y_title_width = options_.y_axis.title.empty() ? 0.0 : line_height;
  const double y_labels = LabelsWidth(canvas, p.y_ticks, fs);
  p.panel_left = int(std::ceil(margin + y_title_width + y_labels + 0.4 * fs + tick + 1));
  p.panel_width = int(width - p.panel_left - margin - legend_width - 1);
  if (p.panel_width < 32) {
    throw InvalidParameter("chart width", std::to_string(width),
                           "room for a panel of at least 32 pixels (a wider chart)");
  }
  if (options_.equal_scale) {
    EqualiseScales(p);
    p.y_ticks = ScaleTicks(p.y_lo, p.y_hi, y_wanted, ys);
  }
  // The most x ticks whose labels do not collide.
  for (int wanted = std::clamp(int(p.panel_width / (4.0 * fs)), 2, 10);; --wanted) {
    p.x_ticks = ScaleTicks(p.x_lo, p.x_hi, wanted, xs);
    const double needed = p.x_ticks.values.size() * (LabelsWidth(canvas, p.x_ticks, fs) + fs);
    if (needed <= p.panel_width || wanted == 2) break;
  }

  const double panel_bottom = p.panel_top + p.panel_height;
  const double panel_right = p.panel_left + p.panel_width;
  // Grid lines and ticks on whole pixels: crisp, and never reaching into the panel's neighbours.
  for (const double v : p.x_ticks.values)
    canvas.FillRect(std::floor(p.PixelX(v)), p.panel_top, 1.0, p.panel_height, kGridColour);
  for (const double v : p.y_ticks.values)
    canvas.FillRect(p.panel_left, std::floor(p.PixelY(v)), p.panel_width, 1.0, kGridColour);
  canvas.StrokeRect(p.panel_left - 0.5, p.panel_top - 0.5, p.panel_width + 1.0,
                    p.panel_height + 1.0, 1.0, kAxisColour);
  for (std::size_t k = 0; k < p.x_ticks.values.size(); ++k) {
    const double px = p.PixelX(p.x_ticks.values[k]);
    canvas.FillRect(std::floor(px), panel_bottom + 1.0, 1.0, tick, kAxisColour);
    canvas.Text(px, panel_bottom + tick + 0.2 * fs, p.x_ticks.labels[k], fs, kAxisColour,
                Align::kCentre, Align::kStart);
  }
  for (std::size_t k = 0; k < p.y_ticks.values.size(); ++k) {
    const double py = p.PixelY(p.y_ticks.values[k]);
    canvas.FillRect(p.panel_left - 1.0 - tick, std::floor(py), tick, 1.0, kAxisColour);
    canvas.Text(p.panel_left - tick - 0.3 * fs, py, p.y_ticks.labels[k], fs, kAxisColour,
                Align::kEnd, Align::kCentre);
  }
  if (!options_.title.empty()) {
    canvas.Text(0.5 * width, margin, options_.title, title_fs, kAxisColour, Align::kCentre,
                Align::kStart, 0.0, true);
  }
  if (!options_.y_axis.title.empty()) {
    canvas.Text(margin, p.panel_top + 0.5 * p.panel_height, options_.y_axis.title, fs, kAxisColour,
                Align::kCentre, Align::kStart, 90.0);
  }
  const double x_title_bottom = height - margin - below_height;
  if (!options_.x_axis.title.empty()) {
    canvas.Text(p.panel_left + 0.5 * p.panel_width, x_title_bottom, options_.x_axis.title, fs,
                kAxisColour, Align::kCentre, Align::kEnd);
  }

  // Series, clipped to the panel: runs of consecutive usable points joined; an unusable point
  // breaks the run.
  const double line_width = std::max(2.0, fs / 6.0);  // 2 px or more: a full pixel on the line
  const double marker_radius = 0.3 * fs;
  canvas.Clip(p.panel_left, p.panel_top, p.panel_width, p.panel_height);
  for (std::size_t n = 0; n < series_.size(); ++n) {
    const ChartSeries& series = series_[n];
    const Rgb colour = SeriesColour(n);
    const Dash dash = SeriesDash(n);
    const int own_marker = SeriesMarker(n);
    const int marker = (series.markers || !series.lines) ? std::max(1, own_marker) : own_marker;
    std::vector<double> run;
    const auto flush = [&] {
      if (run.size() == 2) canvas.FillCircle(run[0], run[1], std::max(1.5, line_width), colour);
      canvas.Polyline(run, line_width, colour, dash);
      run.clear();
    };
    // Style markers (not asked for) at about a dozen points along the series.
    const std::size_t every =
        series.markers || !series.lines ? 1 : std::max<std::size_t>(1, series.x.size() / 12);
    for (std::size_t k = 0; k < series.x.size(); ++k) {
      const double px = p.PixelX(series.x[k]);
      const double py = p.PixelY(series.y[k]);
      if (!std::isfinite(px) || !std::isfinite(py)) {
        if (series.lines) flush();
        continue;
      }
      if (series.lines) {
        run.push_back(px);
        run.push_back(py);
      }
      if (marker > 0 && k % every == 0) DrawMarker(canvas, marker, px, py, marker_radius, colour);
    }
    if (series.lines) flush();
  }
  canvas.Unclip();

  // Legend, to the right of the panel, top aligned with it; or below the x title, entries in rows.
  const double legend_left = p.legend_below ? margin : panel_right + 1 + margin;
  const double legend_top = p.legend_below ? x_title_bottom + 0.5 * fs : p.panel_top;
  if (!options_.legend_title.empty()) {
    canvas.Text(legend_left, legend_top,
                Fitted(canvas, options_.legend_title, fs, width - legend_left - margin), fs,
                kAxisColour, Align::kStart, Align::kStart, 0.0, true);
  }
  const double entry_room = column_width - swatch - 0.5 * fs - margin + 1.0;  // + 1: rounding
  for (std::size_t n = 0; n < series_.size(); ++n) {
    const std::size_t column =
        p.legend_below ? n % std::size_t(legend_columns) : n / std::size_t(rows_per_column);
    const std::size_t row =
        p.legend_below ? n / std::size_t(legend_columns) : n % std::size_t(rows_per_column);
    const double left = legend_left + double(column) * column_width;
    const double mid = legend_top + legend_title_height + (double(row) + 0.5) * line_height;
    const Rgb colour = SeriesColour(n);
    const int own_marker = SeriesMarker(n);
    const bool asked = series_[n].markers || !series_[n].lines;
    if (series_[n].lines)
      canvas.Line(left, mid, left + swatch, mid, line_width, colour, SeriesDash(n));
    if (asked || own_marker > 0)
      DrawMarker(canvas, std::max(asked ? 1 : 0, own_marker), left + 0.5 * swatch, mid,
                 marker_radius, colour);
    canvas.Text(left + swatch + 0.5 * fs, mid, Fitted(canvas, series_[n].name, fs, entry_room), fs,
                kAxisColour, Align::kStart, Align::kCentre);
  }
  return p;
}

std::string LineChart::LegendText() const {
  std::string text;
  for (const ChartSeries& s : series_) text += (text.empty() ? "" : "; ") + s.name;
  return text;
}

ChartPicture LineChart::Save(const std::string& path) const {
  FormatOfPath(path);  // a bad extension fails before any drawing
  ChartPicture picture = Draw();
  picture.image.Write(path);
  return picture;
}

}  // namespace dlmfd
