// DrawFieldPicture: layout, P1 sampling of the field, colour bar, labels, particles.
#include "dlmfd/viz/field_picture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dlmfd/core/errors.h"
#include "dlmfd/viz/bitmap_font.h"
#include "dlmfd/viz/colour_map.h"

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

FieldPicture DrawFieldPicture(const NodeField& field, const std::vector<DiskOutline>& disks,
                              const PictureOptions& options) {
  CheckField(field);
  const Grid& g = field.grid;

  const bool log_colours = options.log_colours;
  double lo = HUGE_VAL;
  double hi = -HUGE_VAL;
  for (double v : field.values) {
    if (std::isfinite(v) && (!log_colours || v > 0.0)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  if (lo > hi) lo = hi = log_colours ? 1.0 : 0.0;  // no usable value: grey (or the bottom colour)
  const std::string max_label = FormatLabel(hi);
  const std::string min_label = FormatLabel(lo);
  const std::string mid_label = log_colours ? FormatLabel(std::sqrt(lo * hi)) : std::string();

  // Layout in pixels; the font scale grows with the picture so labels stay legible.
  const int scale = std::clamp(std::min(options.max_width, options.max_height) / 400, 1, 4);
  const int margin = 6 * scale;
  const int caption_height = options.caption.empty() ? 0 : (kGlyphHeight + 5) * scale;
  const int gap = 8 * scale;
  const int bar_width = 14 * scale;
  const int label_width =
      (std::max({TextWidth(max_label), TextWidth(min_label), TextWidth(mid_label)}) + 4) * scale;
  const int min_bar_height = 3 * kGlyphHeight * scale;
  const int room_x = options.max_width - 2 * margin - gap - bar_width - label_width;
  const int room_y = options.max_height - 2 * margin - caption_height;
  if (room_x < 8 || room_y < std::max(8, min_bar_height)) {
    throw InvalidParameter(
        "picture size",
        std::to_string(options.max_width) + "x" + std::to_string(options.max_height),
        "room for the field, the colour bar and its labels (try 400x300 or more)");
  }
  const double pixels_per_unit = std::min(room_x / g.Width(), room_y / g.Height());
  const int panel_width = std::max(1, int(std::floor(g.Width() * pixels_per_unit)));
  const int panel_height = std::max(1, int(std::floor(g.Height() * pixels_per_unit)));
  const int body_height = std::max(panel_height, min_bar_height);
  const int width = 2 * margin + panel_width + gap + bar_width + label_width;
  const int height = 2 * margin + caption_height + body_height;

  FieldPicture picture;
  picture.image = RasterImage(width, height, kWhite);
  picture.panel_left = margin;
  picture.panel_top = margin + caption_height;
  picture.panel_width = panel_width;
  picture.panel_height = panel_height;
  picture.bar_left = margin + panel_width + gap;
  picture.bar_top = picture.panel_top;
  picture.bar_width = bar_width;
  picture.bar_height = body_height;
  picture.value_min = lo;
  picture.value_max = hi;
  picture.grid = g;
  RasterImage& image = picture.image;

  // The colour coordinate: the value, or its log10, mapped from [lo, hi] onto [0, 1].
  const double bottom = log_colours ? std::log10(lo) : lo;
  const double span = (log_colours ? std::log10(hi) : hi) - bottom;
  const auto colour_of = [&](double v) {
    if (!std::isfinite(v)) return kNanColour;
    if (log_colours && !(v > 0.0)) return Viridis(0.0);
    const double c = log_colours ? std::log10(v) : v;
    return Viridis(span > 0.0 ? std::clamp((c - bottom) / span, 0.0, 1.0) : 0.5);
  };
  for (int py = 0; py < panel_height; ++py) {
    const double y = g.y0 + (1.0 - (py + 0.5) / panel_height) * g.Height();
    for (int px = 0; px < panel_width; ++px) {
      const double x = g.x0 + (px + 0.5) / panel_width * g.Width();
      image.Set(picture.panel_left + px, picture.panel_top + py,
                colour_of(InterpolateP1(field, x, y)));
    }
  }

  const double rim = std::max(1.0, 0.75 * scale);
  for (const DiskOutline& disk : disks) {
    const double cx = picture.PixelX(disk.x);
    const double cy = picture.PixelY(disk.y);
    const double r = disk.radius / g.Width() * panel_width;
    image.FillDisk(cx, cy, r, kWhite);
    image.DrawCircle(cx, cy, r, rim, kBlack);
  }
  // Particles reaching past a wall are clipped to the panel, not drawn over the margin.
  image.FillRect(0, 0, width, picture.panel_top, kWhite);
  image.FillRect(0, picture.panel_top, picture.panel_left, height, kWhite);
  image.FillRect(picture.panel_left + panel_width, picture.panel_top, width, height, kWhite);
  image.FillRect(0, picture.panel_top + panel_height, width, height, kWhite);

  for (int r = 0; r < body_height; ++r) {
    const Rgb colour = span > 0.0 ? Viridis(1.0 - (r + 0.5) / body_height) : Viridis(0.5);
    image.FillRect(picture.bar_left, picture.bar_top + r, bar_width, 1, colour);
  }
  image.FrameRect(picture.bar_left, picture.bar_top, bar_width, body_height, kBlack);
  const int label_left = picture.bar_left + bar_width + 3 * scale;
  image.DrawText(label_left, picture.bar_top, max_label, scale, kBlack);
  image.DrawText(label_left, picture.bar_top + body_height - kGlyphHeight * scale, min_label, scale,
                 kBlack);
  if (!mid_label.empty()) {
    image.DrawText(label_left, picture.bar_top + (body_height - kGlyphHeight * scale) / 2,
                   mid_label, scale, kBlack);
  }
  if (!options.caption.empty()) image.DrawText(margin, margin, options.caption, scale, kBlack);
  return picture;
}

}  // namespace dlmfd
