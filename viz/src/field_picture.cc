// DrawFieldPicture: layout, P1 sampling of the field, isolines, arrows, particles, axes, colour
// bar.
#include "dlmfd/viz/field_picture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dlmfd/core/errors.h"
#include "dlmfd/viz/caption_lines.h"
#include "dlmfd/viz/colour_map.h"
#include "dlmfd/viz/colour_scale.h"
#include "dlmfd/viz/isolines.h"
#include "dlmfd/viz/streamlines.h"

namespace dlmfd {
namespace {

// The value of the P1 interpolant in cell (i, j) at local coordinates (a, b) in [0, 1]^2; the
// SW-NE diagonal splits the cell into the triangles (SW, SE, NE), a >= b, and (SW, NE, NW).
inline double CellP1(const NodeField& f, int i, int j, double a, double b) {
  const Grid& g = f.grid;
  const double sw = f.values[g.Index(i, j)];
  const double se = f.values[g.Index(i + 1, j)];
  const double ne = f.values[g.Index(i + 1, j + 1)];
  const double nw = f.values[g.Index(i, j + 1)];
  if (a >= b) return sw + a * (se - sw) + b * (ne - se);
  return sw + b * (nw - sw) + a * (ne - nw);
}

void CheckField(const NodeField& field) {
  const Grid& g = field.grid;
  if (g.nx < 1 || g.ny < 1 || !(g.h > 0.0) || !std::isfinite(g.h)) {
    throw InvalidParameter(
        "field grid",
        std::to_string(g.nx) + "x" + std::to_string(g.ny) + " cells, h " + FormatLabel(g.h),
        "at least 1x1 cells and a finite h > 0");
  }
  if (field.values.size() != g.NodeCount()) {
    throw InvalidParameter("field values", std::to_string(field.values.size()) + " values",
                           std::to_string(g.NodeCount()) + " = (ny+1)(nx+1) node values");
  }
}

}  // namespace

std::string FormatLabel(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", value);
  return text;
}

double InterpolateP1(const NodeField& field, double x, double y) {
  const Grid& g = field.grid;
  const double s = std::clamp((x - g.x0) / g.h, 0.0, double(g.nx));
  const double t = std::clamp((y - g.y0) / g.h, 0.0, double(g.ny));
  const int i = std::min(int(s), g.nx - 1);
  const int j = std::min(int(t), g.ny - 1);
  return CellP1(field, i, j, s - i, t - j);
}

NodeField CropField(const NodeField& field, double x_min, double y_min, double x_max,
                    double y_max) {
  CheckField(field);
  const Grid& g = field.grid;
  const bool finite =
      std::isfinite(x_min) && std::isfinite(y_min) && std::isfinite(x_max) && std::isfinite(y_max);
  if (!finite || !(x_min < x_max) || !(y_min < y_max) || x_max <= g.x0 || y_max <= g.y0 ||
      x_min >= g.x0 + g.Width() || y_min >= g.y0 + g.Height()) {
    throw InvalidParameter("window",
                           FormatLabel(x_min) + "," + FormatLabel(y_min) + "," +
                               FormatLabel(x_max) + "," + FormatLabel(y_max),
                           "x_min < x_max and y_min < y_max, overlapping the domain [" +
                               FormatLabel(g.x0) + ", " + FormatLabel(g.x0 + g.Width()) + "] x [" +
                               FormatLabel(g.y0) + ", " + FormatLabel(g.y0 + g.Height()) + "]");
  }
  const int i0 = std::clamp(int(std::floor((x_min - g.x0) / g.h)), 0, g.nx - 1);
  const int j0 = std::clamp(int(std::floor((y_min - g.y0) / g.h)), 0, g.ny - 1);
  const int i1 = std::clamp(int(std::ceil((x_max - g.x0) / g.h)), i0 + 1, g.nx);
  const int j1 = std::clamp(int(std::ceil((y_max - g.y0) / g.h)), j0 + 1, g.ny);
  NodeField crop;
  crop.quantity = field.quantity;
  crop.grid = Grid{i1 - i0, j1 - j0, g.h, g.X(i0), g.Y(j0)};
  crop.values.reserve(crop.grid.NodeCount());
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) crop.values.push_back(field.values[g.Index(i, j)]);
  }
  return crop;
}

double FieldPicture::PixelX(double x) const {
  return panel_left + (x - grid.x0) / grid.Width() * panel_width;
}

double FieldPicture::PixelY(double y) const {
  return panel_top + (1.0 - (y - grid.y0) / grid.Height()) * panel_height;
}

double FieldPicture::BarY(double value) const {
  const double bottom = log_colours ? std::log10(value_min) : value_min;
  const double span = (log_colours ? std::log10(value_max) : value_max) - bottom;
  const double c = log_colours ? std::log10(value) : value;
  const double fraction = span > 0.0 ? (c - bottom) / span : 0.5;
  return bar_top + (1.0 - fraction) * bar_height;
}

namespace {

// The q-quantile (q in [0, 1]) of `values` (not empty), by linear interpolation between order
// statistics.
double Quantile(std::vector<double> values, double q) {
  const double at = q * double(values.size() - 1);
  const std::size_t k = std::size_t(std::floor(at));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  const double low = values[k];
  if (k + 1 >= values.size()) return low;
  const double high = *std::min_element(values.begin() + k + 1, values.end());
  return low + (at - double(k)) * (high - low);
}

// The colour range: fixed, or the finite (positive, on a log scale) extremes of the values, or
// their percentiles; on a diverging scale [-m, m] with m the largest (or the p-th percentile) of
// the finite |value|. Checked by ColourScale.
void ColourRange(const NodeField& field, const PictureOptions& options, double& lo, double& hi) {
  if (options.fixed_range) {
    lo = options.range_min;
    hi = options.range_max;
    return;
  }
  std::vector<double> usable;
  usable.reserve(field.values.size());
  for (double v : field.values) {
    if (std::isfinite(v) && (!options.log_colours || v > 0.0)) usable.push_back(v);
  }
  if (usable.empty()) {  // no usable value
    lo = hi = options.log_colours ? 1.0 : 0.0;
    return;
  }
  const double p = std::clamp(options.percentile, 50.0, 100.0) / 100.0;
  if (options.diverging) {
    for (double& v : usable) v = std::abs(v);
    hi = p < 1.0 ? Quantile(usable, p) : *std::max_element(usable.begin(), usable.end());
    lo = -hi;
    return;
  }
  if (p < 1.0) {
    lo = Quantile(usable, 1.0 - p);
    hi = Quantile(usable, p);
  } else {
    lo = *std::min_element(usable.begin(), usable.end());
    hi = *std::max_element(usable.begin(), usable.end());
  }
}

// The largest 1-2-5 number (1, 2 or 5 times a power of ten) not above `value` (> 0).
double RoundDown125(double value) {
  const double decade = std::pow(10.0, std::floor(std::log10(value)));
  for (const double m : {5.0, 2.0, 1.0}) {
    if (m * decade <= value * (1.0 + 1e-12)) return m * decade;
  }
  return decade;
}

double WidestLabel(const Canvas& canvas, const AxisTicks& ticks, double size) {
  double width = 0.0;
  for (const std::string& label : ticks.labels)
    width = std::max(width, canvas.MeasureText(label, size).advance);
  return width;
}

AxisTicks BarTicks(double lo, double hi, int wanted, bool log) {
  if (!(lo < hi)) return AxisTicks{{lo}, {FormatLabel(lo)}};
  return ScaleTicks(lo, hi, wanted, log ? AxisScale::kLog10 : AxisScale::kLinear);
}

// The arrows of the velocity on a lattice of `columns` columns; returns the speed of one spacing.
double DrawArrows(Canvas& canvas, const FieldPicture& p, const NodeVelocity& velocity, int columns,
                  double line_width) {
  const Grid& g = p.grid;
  const double spacing = g.Width() / columns;
  const int rows = std::max(1, int(std::floor(g.Height() / spacing)));
  const double y_start = g.y0 + 0.5 * (g.Height() - rows * spacing);
  double longest = 0.0;
  std::vector<double> points;  // x, y, u, v
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      const double x = g.x0 + (i + 0.5) * spacing;
      const double y = y_start + (j + 0.5) * spacing;
      const double u = InterpolateP1(velocity.u, x, y);
      const double v = InterpolateP1(velocity.v, x, y);
      if (!std::isfinite(u) || !std::isfinite(v)) continue;
      longest = std::max(longest, std::hypot(u, v));
      points.insert(points.end(), {x, y, u, v});
    }
  }
  if (!(longest > 0.0)) return 0.0;
  const double pixels = spacing / g.Width() * p.panel_width;
  for (std::size_t k = 0; k < points.size(); k += 4) {
    const double length = pixels * std::hypot(points[k + 2], points[k + 3]) / longest;
    if (length < 0.5) continue;
    const double head = std::max(2.0, 0.3 * length);  // in proportion: short arrows stay small
    const double x0 = p.PixelX(points[k]);
    const double y0 = p.PixelY(points[k + 1]);
    const double x1 = x0 + pixels * points[k + 2] / longest;
    const double y1 = y0 - pixels * points[k + 3] / longest;
    // Black under white: readable on the dark and the bright end of viridis.
    canvas.Arrow(x0, y0, x1, y1, line_width + 1.5, head + 1.0, kBlack);
    canvas.Arrow(x0, y0, x1, y1, line_width, head, kWhite);
  }
  return longest;
}

// Streamlines over the field: white over viridis, black over cool to warm and without fill, with
// an arrowhead at the middle of each line; returns the number of lines drawn.
int DrawStreamlines(Canvas& canvas, const FieldPicture& p, const NodeVelocity& velocity,
                    int columns, double line_width, bool fill) {
  const Rgb colour = fill && !p.diverging ? kWhite : kBlack;
  const std::vector<std::vector<double>> lines = Streamlines(velocity, columns);
  const double head = std::max(4.0, 4.0 * line_width);
  for (const std::vector<double>& line : lines) {
    std::vector<double> pixels(line.size());
    for (std::size_t k = 0; k < line.size(); k += 2) {
      pixels[k] = p.PixelX(line[k]);
      pixels[k + 1] = p.PixelY(line[k + 1]);
    }
    canvas.Polyline(pixels, line_width, colour);
    const std::size_t mid = (line.size() / 4) * 2;  // a point near the middle
    if (mid >= 2) {
      const double dx = pixels[mid] - pixels[mid - 2], dy = pixels[mid + 1] - pixels[mid - 1];
      const double length = std::hypot(dx, dy);
      if (length > 0.0) {
        canvas.Arrow(pixels[mid] - head * dx / length, pixels[mid + 1] - head * dy / length,
                     pixels[mid], pixels[mid + 1], line_width, head, colour);
      }
    }
  }
  return int(lines.size());
}

}  // namespace

// NOLINTNEXTLINE(readability-function-size): predates the limit; split it when you change it
FieldPicture DrawFieldPicture(const NodeField& field, const std::vector<DiskOutline>& disks,
                              const PictureOptions& options, const NodeVelocity* velocity) {
  CheckField(field);
  if (options.arrows > 0 || options.streamlines > 0) {
    if (velocity == nullptr) {
      throw InvalidParameter(
          options.arrows > 0 ? "arrows" : "streamlines",
          std::to_string(options.arrows > 0 ? options.arrows : options.streamlines),
          "0 for a field without velocity (the snapshot's u and v)");
    }
    CheckField(velocity->u);
    CheckField(velocity->v);
  }
  const Grid& g = field.grid;
  const bool log_colours = options.log_colours;
  double lo = 0.0, hi = 0.0;
  ColourRange(field, options, lo, hi);
  const ColourScale colours(lo, hi, log_colours, options.diverging);
  const std::string bar_label =
      options.colour_label.empty() ? field.quantity : options.colour_label;

  const int max_width = options.exact_width > 0 ? options.exact_width : options.max_width;
  const int max_height = options.exact_height > 0 ? options.exact_height : options.max_height;
  Canvas measure(1, 1);
  // Text sizes in pixels grow with the picture (18 px labels in 1000 x 1000, no upper bound: a
  // 3000-pixel figure has 55 px text), or are the caller's.
  const double fs = options.font_size > 0.0 ? options.font_size
                                            : std::max(9.0, std::min(max_width, max_height) / 55.0);
  const double margin = 0.8 * fs;
  const double tick = 0.4 * fs;
  const double line_height = 1.3 * fs;
  const double bar_width = 1.2 * fs;
  const double min_bar_height = 6.0 * fs;

  // The layout for a caption of `caption_lines` lines: the panel keeps the domain's aspect, the
  // picture shrinks around it.
  struct Layout {
    double left = 0, top = 0;
    int panel_width = 0, panel_height = 0, body_height = 0, width = 0, height = 0;
  };
  auto layout_for = [&](std::size_t caption_lines) {
    const double caption_height = caption_lines == 0 ? 0.0 : caption_lines * line_height + 0.3 * fs;
    Layout l;
    // A first guess of the ticks, for the widths of their labels.
    l.top = margin + caption_height + 0.5 * fs;
    const double bottom = tick + 0.2 * fs + (options.arrows > 0 ? 3.0 : 2.0) * line_height + margin;
    const double room_y_guess = max_height - l.top - bottom;
    const int y_wanted = std::clamp(int(room_y_guess / (3.0 * fs)), 2, 8);
    const AxisTicks y_guess = LinearTicks(g.y0, g.y0 + g.Height(), y_wanted);
    const AxisTicks bar_guess = BarTicks(lo, hi, y_wanted, log_colours);
    l.left = margin + line_height + WidestLabel(measure, y_guess, fs) + 0.3 * fs + tick + 1.0;
    const double right = 1.2 * fs + bar_width + tick + 0.3 * fs +
                         WidestLabel(measure, bar_guess, fs) + 0.6 * fs + line_height + margin;
    const double room_x = max_width - l.left - right;
    const double room_y = max_height - l.top - bottom;
    if (room_x < 16 || room_y < std::max(16.0, min_bar_height)) {
      throw InvalidParameter("picture size",
                             std::to_string(max_width) + "x" + std::to_string(max_height),
                             "room for the field, its axes, the colour bar and its labels (try "
                             "400x300 or more)");
    }
    const double pixels_per_unit = std::min(room_x / g.Width(), room_y / g.Height());
    l.panel_width = std::max(1, int(std::floor(g.Width() * pixels_per_unit)));
    l.panel_height = std::max(1, int(std::floor(g.Height() * pixels_per_unit)));
    l.body_height = std::max(l.panel_height, int(min_bar_height));
    l.width = int(std::ceil(l.left + l.panel_width + right));
    l.height = int(std::ceil(l.top + l.body_height + bottom));
    return l;
  };
  // The caption wraps in the picture's final width; more lines make the panel, and so the
  // picture, narrower: a few rounds settle it (the count of lines only grows).
  auto caption_in = [&](int picture_width) {
    return CaptionLines(measure, options.caption, picture_width - 2.0 * margin, fs);
  };
  std::vector<CaptionLine> caption = caption_in(max_width);
  Layout layout = layout_for(caption.size());
  for (int round = 0; round < 4; ++round) {
    std::vector<CaptionLine> rewrapped = caption_in(layout.width);
    if (rewrapped.size() <= caption.size()) {
      caption = std::move(rewrapped);
      break;
    }
    caption = std::move(rewrapped);
    layout = layout_for(caption.size());
  }
  const double left = layout.left;
  const double top = layout.top;
  const int panel_width = layout.panel_width;
  const int panel_height = layout.panel_height;
  const int body_height = layout.body_height;
  int width = layout.width;
  int height = layout.height;
  int shift_x = 0, shift_y = 0;
  if (options.exact_width > 0) {
    shift_x = std::max(0, (options.exact_width - width) / 2);
    shift_y = std::max(0, (options.exact_height - height) / 2);
    width = options.exact_width;
    height = options.exact_height;
  }

  FieldPicture picture;
  picture.image = Canvas(width, height);
  picture.panel_left = shift_x + int(std::ceil(left));
  picture.panel_top = shift_y + int(std::ceil(top));
  picture.panel_width = panel_width;
  picture.panel_height = panel_height;
  picture.bar_left = picture.panel_left + panel_width + int(std::round(1.2 * fs));
  picture.bar_top = picture.panel_top;
  picture.bar_width = int(std::round(bar_width));
  picture.bar_height = body_height;
  picture.value_min = lo;
  picture.value_max = hi;
  picture.log_colours = log_colours;
  picture.diverging = options.diverging;
  picture.grid = g;
  Canvas& canvas = picture.image;

  // The field, pixel by pixel, at the pixel centres.
  if (options.fill) {
    RgbImage raster;
    raster.width = panel_width;
    raster.height = panel_height;
    raster.rgb.resize(std::size_t(panel_width) * std::size_t(panel_height) * 3);
    for (int py = 0; py < panel_height; ++py) {
      const double y = g.y0 + (1.0 - (py + 0.5) / panel_height) * g.Height();
      for (int px = 0; px < panel_width; ++px) {
        const double x = g.x0 + (px + 0.5) / panel_width * g.Width();
        const Rgb c = colours.Of(InterpolateP1(field, x, y));
        const std::size_t k = (std::size_t(py) * std::size_t(panel_width) + std::size_t(px)) * 3;
        raster.rgb[k] = c.r;
        raster.rgb[k + 1] = c.g;
        raster.rgb[k + 2] = c.b;
      }
    }
    canvas.Raster(picture.panel_left, picture.panel_top, raster);
  }

  canvas.Clip(picture.panel_left, picture.panel_top, panel_width, panel_height);
  const double thin = std::max(1.25, fs / 12.0);
  // White over viridis, black over cool to warm (its middle is light) and with no fill.
  const Rgb isoline_colour = options.fill && !options.diverging ? kWhite : kBlack;
  picture.isovalues = Isovalues(lo, hi, options.isolines, log_colours);
  for (const double level : picture.isovalues) {
    const std::vector<double> segments = IsolineSegments(field, level);
    std::vector<double> pixels(segments.size());
    for (std::size_t k = 0; k < segments.size(); k += 2) {
      pixels[k] = picture.PixelX(segments[k]);
      pixels[k + 1] = picture.PixelY(segments[k + 1]);
    }
    canvas.Segments(pixels, thin, isoline_colour);
  }
  if (options.streamlines > 0) {
    picture.streamlines_drawn =
        DrawStreamlines(canvas, picture, *velocity, options.streamlines, thin, options.fill);
  }
  if (options.arrows > 0)
    picture.arrow_speed = DrawArrows(canvas, picture, *velocity, options.arrows, thin);
  const double rim = std::max(1.0, fs / 10.0);
  const double scale = panel_width / g.Width();
  for (const DiskOutline& disk : disks) {
    const double cx = picture.PixelX(disk.x);
    const double cy = picture.PixelY(disk.y);
    double r = disk.radius * scale;
    if (disk.semi_a > 0.0 && disk.semi_b > 0.0) {
      // An ellipse: a polygon of 96 points on its boundary (pixel y points down).
      std::vector<double> xy;
      const double c = std::cos(disk.angle), s = std::sin(disk.angle);
      for (int k = 0; k <= 96; ++k) {
        const double t = 2.0 * kPi * k / 96;
        const double bx = disk.semi_a * std::cos(t), by = disk.semi_b * std::sin(t);
        xy.push_back(cx + scale * (c * bx - s * by));
        xy.push_back(cy - scale * (s * bx + c * by));
      }
      canvas.FillPolygon(xy, kWhite);
      canvas.Polyline(xy, rim, kBlack);
      r = disk.semi_a * scale;  // the mark runs along the body's x axis to the boundary
    } else {
      canvas.FillCircle(cx, cy, r, kWhite);
      canvas.StrokeCircle(cx, cy, r, rim, kBlack);
    }
    if (disk.has_angle)
      canvas.Line(cx, cy, cx + r * std::cos(disk.angle), cy - r * std::sin(disk.angle), rim,
                  kBlack);
  }
  canvas.Unclip();

  // Axes: frame, ticks outwards, labels in the domain's coordinates.
  const double panel_bottom = picture.panel_top + panel_height;
  canvas.StrokeRect(picture.panel_left - 0.5, picture.panel_top - 0.5, panel_width + 1.0,
                    panel_height + 1.0, 1.0, kAxisColour);
  picture.y_ticks =
      LinearTicks(g.y0, g.y0 + g.Height(), std::clamp(int(panel_height / (3.0 * fs)), 2, 8));
  for (int wanted = std::clamp(int(panel_width / (3.5 * fs)), 2, 8);; --wanted) {
    picture.x_ticks = LinearTicks(g.x0, g.x0 + g.Width(), wanted);
    const double needed =
        picture.x_ticks.values.size() * (WidestLabel(canvas, picture.x_ticks, fs) + fs);
    if (needed <= panel_width || wanted == 2) break;
  }
  for (std::size_t k = 0; k < picture.x_ticks.values.size(); ++k) {
    const double px = picture.PixelX(picture.x_ticks.values[k]);
    canvas.FillRect(std::floor(px), panel_bottom + 1.0, 1.0, tick, kAxisColour);
    canvas.Text(px, panel_bottom + tick + 0.2 * fs, picture.x_ticks.labels[k], fs, kAxisColour,
                Align::kCentre, Align::kStart);
  }
  for (std::size_t k = 0; k < picture.y_ticks.values.size(); ++k) {
    const double py = picture.PixelY(picture.y_ticks.values[k]);
    canvas.FillRect(picture.panel_left - 1.0 - tick, std::floor(py), tick, 1.0, kAxisColour);
    canvas.Text(picture.panel_left - tick - 0.3 * fs, py, picture.y_ticks.labels[k], fs,
                kAxisColour, Align::kEnd, Align::kCentre);
  }
  canvas.Text(picture.panel_left + 0.5 * panel_width, panel_bottom + tick + 0.2 * fs + line_height,
              options.x_title, fs, kAxisColour, Align::kCentre, Align::kStart);
  canvas.Text(shift_x + margin, picture.panel_top + 0.5 * panel_height, options.y_title, fs,
              kAxisColour, Align::kCentre, Align::kStart, 90.0);
  if (picture.arrow_speed > 0.0) {
    // The key on a row of its own below the x title: a round speed at its own length.
    picture.key_speed = RoundDown125(picture.arrow_speed);
    const double pixels =
        panel_width / double(options.arrows) * picture.key_speed / picture.arrow_speed;
    const double ky = panel_bottom + tick + 0.2 * fs + 2.5 * line_height;
    const double kx = picture.panel_left + panel_width;
    canvas.Arrow(kx - pixels, ky, kx, ky, thin, std::max(3.0, 0.3 * pixels), kBlack);
    const std::string units = options.speed_units.empty() ? "" : " " + options.speed_units;
    canvas.Text(kx - pixels - 0.4 * fs, ky, "|u| = " + FormatLabel(picture.key_speed) + units, fs,
                kAxisColour, Align::kEnd, Align::kCentre);
  }

  // The colour bar: the field's scale from bottom (min) to top (max), its ticks and label, the
  // isovalues marked.
  RgbImage bar;
  bar.width = picture.bar_width;
  bar.height = body_height;
  bar.rgb.resize(std::size_t(bar.width) * std::size_t(bar.height) * 3);
  for (int r = 0; r < body_height; ++r) {
    const Rgb colour = colours.AtFraction(1.0 - (r + 0.5) / body_height);
    for (int c = 0; c < bar.width; ++c) {
      const std::size_t k = (std::size_t(r) * std::size_t(bar.width) + std::size_t(c)) * 3;
      bar.rgb[k] = colour.r;
      bar.rgb[k + 1] = colour.g;
      bar.rgb[k + 2] = colour.b;
    }
  }
  canvas.Raster(picture.bar_left, picture.bar_top, bar);
  canvas.StrokeRect(picture.bar_left - 0.5, picture.bar_top - 0.5, bar.width + 1.0,
                    body_height + 1.0, 1.0, kAxisColour);
  // Triangles at the ends of the bar that the field's values exceed (their colour is the end's).
  const double slack = 1e-12 * std::max(std::abs(lo), std::abs(hi));
  for (const double v : field.values) {
    if (!std::isfinite(v) || (log_colours && !(v > 0.0))) continue;
    picture.clipped_low = picture.clipped_low || v < lo - slack;
    picture.clipped_high = picture.clipped_high || v > hi + slack;
  }
  {
    const double w = bar.width, x0 = picture.bar_left, tip = 0.8 * w;
    const double bar_top = picture.bar_top - 1.0, bottom_y = picture.bar_top + body_height + 1.0;
    if (picture.clipped_high) {
      canvas.FillPolygon({x0, bar_top, x0 + w, bar_top, x0 + 0.5 * w, bar_top - tip},
                         colours.AtFraction(1.0));
    }
    if (picture.clipped_low) {
      canvas.FillPolygon({x0, bottom_y, x0 + w, bottom_y, x0 + 0.5 * w, bottom_y + tip},
                         colours.AtFraction(0.0));
    }
  }
  for (const double level : picture.isovalues) {
    const double y = picture.BarY(level);
    canvas.Line(picture.bar_left, y, picture.bar_left + bar.width, y, thin, isoline_colour);
  }
  picture.bar_ticks =
      BarTicks(lo, hi, std::clamp(int(body_height / (3.0 * fs)), 2, 8), log_colours);
  const double bar_right = picture.bar_left + bar.width;
  for (std::size_t k = 0; k < picture.bar_ticks.values.size(); ++k) {
    const double y = picture.BarY(picture.bar_ticks.values[k]);
    canvas.FillRect(bar_right + 1.0, std::floor(y), tick, 1.0, kAxisColour);
    canvas.Text(bar_right + tick + 0.3 * fs, y, picture.bar_ticks.labels[k], fs, kAxisColour,
                Align::kStart, Align::kCentre);
  }
  const double label_x =
      bar_right + tick + 0.9 * fs + WidestLabel(canvas, picture.bar_ticks, fs) + 0.5 * line_height;
  canvas.Text(label_x, picture.bar_top + 0.5 * body_height,
              bar_label + (log_colours ? " (log scale)" : ""), fs, kAxisColour, Align::kCentre,
              Align::kCentre, 90.0);

  for (std::size_t k = 0; k < caption.size(); ++k) {
    canvas.Text(shift_x + margin, shift_y + margin + k * line_height, caption[k].text,
                caption[k].size, kAxisColour, Align::kStart, Align::kStart, 0.0, caption[k].bold);
  }
  return picture;
}

}  // namespace dlmfd
