// LineChart: axis ranges and ticks from the usable points, then layout, grid, frame, labels,
// series and legend drawn into a RasterImage.
#include "dlmfd/viz/line_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "dlmfd/core/errors.h"
#include "dlmfd/viz/bitmap_font.h"

namespace dlmfd {
namespace {

// Okabe-Ito without its yellow, which is too pale on white: blue, vermillion, bluish green,
// reddish purple, orange, sky blue, black.
constexpr Rgb kPalette[kPaletteSize] = {{0, 114, 178},   {213, 94, 0},  {0, 158, 115},
                                        {204, 121, 167}, {230, 159, 0}, {86, 180, 233},
                                        {0, 0, 0}};
constexpr Rgb kGridColour{225, 225, 225};
constexpr Rgb kAxisColour{0, 0, 0};
// Relative slack when deciding whether a computed tick lies inside the range.
constexpr double kRoundOff = 1e-9;

double Transform(double value, AxisScale scale) {
  return scale == AxisScale::kLog10 ? std::log10(value) : value;
}

std::string Printf(const char* format, int digits, double value) {
  char text[48];
  std::snprintf(text, sizeof(text), format, digits, value);
  return text;
}

// A label for a multiple of `step` on an axis reaching `magnitude`: fixed decimals as the step
// needs, or scientific notation when the axis values are all very large or very small.
std::string LinearLabel(double value, double step, double magnitude) {
  const int step_exponent = int(std::floor(std::log10(step) + kRoundOff));
  if (magnitude >= 1e6 || magnitude < 1e-3) {
    if (std::abs(value) < kRoundOff * step) return "0";
    const int exponent = int(std::floor(std::log10(magnitude)));
    return Printf("%.*e", std::max(0, exponent - step_exponent), value);
  }
  return Printf("%.*f", std::max(0, -step_exponent), value);
}

// m * 10^k (m in 1, 2, 5): plain digits for moderate k, "me" k otherwise.
std::string LogLabel(int mantissa, int exponent) {
  if (exponent >= -3 && exponent <= 4) {
    return Printf("%.*f", std::max(0, -exponent), mantissa * std::pow(10.0, exponent));
  }
  return std::to_string(mantissa) + "e" + std::to_string(exponent);
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

double PixelAlong(double value, double lo, double hi, AxisScale scale, int first, int count,
                  bool reversed) {
  if (!Usable(value, scale)) return std::numeric_limits<double>::quiet_NaN();
  const double t_lo = Transform(lo, scale);
  const double fraction = (Transform(value, scale) - t_lo) / (Transform(hi, scale) - t_lo);
  return first + 0.5 + (reversed ? 1.0 - fraction : fraction) * (count - 1);
}

int LabelsWidth(const AxisTicks& ticks) {
  int width = 0;
  for (const std::string& label : ticks.labels) width = std::max(width, TextWidth(label));
  return width;
}

// A legend entry no wider than `max_chars` characters.
std::string Shortened(const std::string& name, int max_chars) {
  if (int(name.size()) <= max_chars) return name;
  return name.substr(0, std::size_t(std::max(1, max_chars - 2))) + "..";
}

}  // namespace

Rgb SeriesColour(std::size_t index) { return kPalette[index % kPaletteSize]; }

bool Usable(double value, AxisScale scale) {
  return std::isfinite(value) && (scale == AxisScale::kLinear || value > 0.0);
}

AxisTicks LinearTicks(double lo, double hi, int wanted) {
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo < hi)) {
    throw InvalidParameter("axis range", "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]",
                           "finite ends with lo < hi");
  }
  wanted = std::max(2, wanted);
  const double raw = (hi - lo) / wanted;
  const double base = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * base;
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * base >= raw * (1.0 - kRoundOff)) {
      step = m * base;
      break;
    }
  }
  AxisTicks ticks;
  const double magnitude = std::max(std::abs(lo), std::abs(hi));
  for (double k = std::ceil(lo / step - kRoundOff); k <= std::floor(hi / step + kRoundOff);
       k += 1.0) {
    const double value = std::abs(k) < 0.5 ? 0.0 : k * step;
    ticks.values.push_back(value);
    ticks.labels.push_back(LinearLabel(value, step, magnitude));
  }
  return ticks;
}

AxisTicks LogTicks(double lo, double hi, int wanted) {
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo > 0.0 && lo < hi)) {
    throw InvalidParameter("log axis range",
                           "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]",
                           "finite ends with 0 < lo < hi");
  }
  wanted = std::max(2, wanted);
  const int k_lo = int(std::ceil(std::log10(lo) - kRoundOff));
  const int k_hi = int(std::floor(std::log10(hi) + kRoundOff));
  const int decades = k_hi - k_lo + 1;
  if (decades < 3) {
    AxisTicks multiples;
    for (int k = k_lo - 2; k <= k_hi + 1; ++k) {
      for (const int m : {1, 2, 5}) {
        const double value = m * std::pow(10.0, k);
        if (value >= lo * (1.0 - kRoundOff) && value <= hi * (1.0 + kRoundOff)) {
          multiples.values.push_back(value);
          multiples.labels.push_back(LogLabel(m, k));
        }
      }
    }
    const std::size_t count = multiples.values.size();
    if (count >= 2 && (count <= std::size_t(wanted) + 1 || decades < 2)) return multiples;
  }
  AxisTicks ticks;
  if (decades >= 2) {
    const int every = std::max(1, (k_hi - k_lo + wanted - 1) / wanted);
    // Decades that are multiples of `every` when that leaves two or more, else from k_lo.
    int first = int(std::ceil(double(k_lo) / every)) * every;
    if (first + every > k_hi) first = k_lo;
    for (int k = first; k <= k_hi; k += every) {
      ticks.values.push_back(std::pow(10.0, k));
      ticks.labels.push_back(LogLabel(1, k));
    }
    return ticks;
  }
  return LinearTicks(lo, hi, wanted);
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

ChartPicture LineChart::Draw() const {
  const AxisScale xs = options_.x_axis.scale;
  const AxisScale ys = options_.y_axis.scale;
  if (series_.empty())
    throw InvalidParameter("chart", "no series", "at least one series of points");
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

  // Vertical layout first: it does not depend on the tick labels.
  const int width = options_.width;
  const int height = options_.height;
  const int s = std::clamp(std::min(width, height) / 300, 1, 4);
  const int margin = 8 * s;
  const int tick = 4 * s;
  const int line_height = (kGlyphHeight + 5) * s;
  const int title_scale = TextWidth(options_.title) * (s + 1) <= width - 2 * margin ? s + 1 : s;
  const int title_height = options_.title.empty() ? 0 : (kGlyphHeight + 6) * title_scale;
  const int y_title_height = options_.y_axis.title.empty() ? 4 * s : line_height;
  const int x_title_height = options_.x_axis.title.empty() ? 0 : line_height;
  p.panel_top = margin + title_height + y_title_height;
  p.panel_height = height - p.panel_top - margin - x_title_height - line_height - tick - 1;
  if (p.panel_height < 32) {
    throw InvalidParameter("chart height", std::to_string(height),
                           "room for a panel of at least 32 pixels");
  }
  p.y_ticks = ys == AxisScale::kLog10
                  ? LogTicks(p.y_lo, p.y_hi, std::clamp(p.panel_height / (40 * s), 2, 8))
                  : LinearTicks(p.y_lo, p.y_hi, std::clamp(p.panel_height / (40 * s), 2, 8));

  // Horizontal layout: y labels on the left, the legend on the right.
  const int swatch = 16 * s;
  const int max_name_chars = std::max(4, (width * 2 / 5) / (kGlyphAdvance * s));
  int name_width = 0;
  for (const ChartSeries& series : series_) {
    name_width = std::max(name_width, TextWidth(Shortened(series.name, max_name_chars)));
  }
  const int legend_width = swatch + 4 * s + name_width * s + margin;
  p.panel_left = margin + LabelsWidth(p.y_ticks) * s + 3 * s + tick + 1;
  p.panel_width = width - p.panel_left - margin - legend_width - 1;
  if (p.panel_width < 32) {
    throw InvalidParameter("chart width", std::to_string(width),
                           "room for a panel of at least 32 pixels");
  }
  // The most x ticks whose labels do not collide.
  for (int wanted = std::clamp(p.panel_width / (60 * s), 2, 10);; --wanted) {
    p.x_ticks = xs == AxisScale::kLog10 ? LogTicks(p.x_lo, p.x_hi, wanted)
                                        : LinearTicks(p.x_lo, p.x_hi, wanted);
    const int needed = int(p.x_ticks.values.size()) * (LabelsWidth(p.x_ticks) + 4) * s;
    if (needed <= p.panel_width || wanted == 2) break;
  }

  p.image = RasterImage(width, height);
  RasterImage& image = p.image;
  const int panel_bottom = p.panel_top + p.panel_height;  // the frame row
  const int panel_right = p.panel_left + p.panel_width;   // the frame column
  for (const double v : p.x_ticks.values)
    image.FillRect(int(p.PixelX(v)), p.panel_top, 1, p.panel_height, kGridColour);
  for (const double v : p.y_ticks.values)
    image.FillRect(p.panel_left, int(p.PixelY(v)), p.panel_width, 1, kGridColour);
  image.FrameRect(p.panel_left - 1, p.panel_top - 1, p.panel_width + 2, p.panel_height + 2,
                  kAxisColour);
  for (std::size_t k = 0; k < p.x_ticks.values.size(); ++k) {
    const int px = int(p.PixelX(p.x_ticks.values[k]));
    image.FillRect(px, panel_bottom + 1, 1, tick, kAxisColour);
    const int label_width = TextWidth(p.x_ticks.labels[k]) * s;
    image.DrawText(px - label_width / 2, panel_bottom + 1 + tick + 2 * s, p.x_ticks.labels[k], s,
                   kAxisColour);
  }
  for (std::size_t k = 0; k < p.y_ticks.values.size(); ++k) {
    const int py = int(p.PixelY(p.y_ticks.values[k]));
    image.FillRect(p.panel_left - 1 - tick, py, tick, 1, kAxisColour);
    const int label_width = TextWidth(p.y_ticks.labels[k]) * s;
    image.DrawText(p.panel_left - 1 - tick - 2 * s - label_width, py - kGlyphHeight * s / 2,
                   p.y_ticks.labels[k], s, kAxisColour);
  }
  if (!options_.title.empty()) {
    image.DrawText((width - TextWidth(options_.title) * title_scale) / 2, margin, options_.title,
                   title_scale, kAxisColour);
  }
  if (!options_.y_axis.title.empty()) {
    image.DrawText(margin, p.panel_top - line_height, options_.y_axis.title, s, kAxisColour);
  }
  if (!options_.x_axis.title.empty()) {
    image.DrawText(p.panel_left + (p.panel_width - TextWidth(options_.x_axis.title) * s) / 2,
                   height - margin - kGlyphHeight * s, options_.x_axis.title, s, kAxisColour);
  }

  // Series: runs of consecutive usable points joined; an unusable point breaks the run.
  const double line_width = s;
  const double marker_radius = 2.0 * s + 1.0;
  for (std::size_t n = 0; n < series_.size(); ++n) {
    const ChartSeries& series = series_[n];
    const Rgb colour = SeriesColour(n);
    const std::size_t count = series.x.size();
    for (std::size_t k = 0; k < count; ++k) {
      const double px = p.PixelX(series.x[k]);
      const double py = p.PixelY(series.y[k]);
      if (!std::isfinite(px) || !std::isfinite(py)) continue;
      if (!series.lines) {
        image.FillDisk(px, py, marker_radius, colour);
        continue;
      }
      const bool next_usable = k + 1 < count && std::isfinite(p.PixelX(series.x[k + 1])) &&
                               std::isfinite(p.PixelY(series.y[k + 1]));
      const bool previous_usable = k > 0 && std::isfinite(p.PixelX(series.x[k - 1])) &&
                                   std::isfinite(p.PixelY(series.y[k - 1]));
      if (next_usable) {
        image.DrawLine(px, py, p.PixelX(series.x[k + 1]), p.PixelY(series.y[k + 1]), line_width,
                       colour);
      } else if (!previous_usable) {
        image.FillDisk(px, py, std::max(1.5, line_width), colour);
      }
      if (series.markers) image.FillDisk(px, py, marker_radius, colour);
    }
  }

  // Legend, to the right of the panel, top aligned with it.
  const int legend_left = panel_right + 1 + margin;
  for (std::size_t n = 0; n < series_.size(); ++n) {
    const int row_top = p.panel_top + int(n) * line_height;
    const double mid = row_top + 0.5 * kGlyphHeight * s;
    const Rgb colour = SeriesColour(n);
    if (series_[n].lines)
      image.DrawLine(legend_left, mid, legend_left + swatch, mid, line_width, colour);
    if (series_[n].markers || !series_[n].lines)
      image.FillDisk(legend_left + 0.5 * swatch, mid, marker_radius, colour);
    image.DrawText(legend_left + swatch + 4 * s, row_top,
                   Shortened(series_[n].name, max_name_chars), s, kAxisColour);
  }
  return p;
}

}  // namespace dlmfd
