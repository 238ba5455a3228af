// Canvas: a cairo recording surface, replayed onto an image, SVG or PDF surface when written.
#include "dlmfd/viz/canvas.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <utility>

#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/io/atomic_file.h"

namespace dlmfd {
namespace {

cairo_status_t AppendToString(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

// Paints the recording onto `target` (white background first), `scale` target units a canvas
// pixel, and finishes the target.
void Replay(cairo_surface_t* recording, cairo_surface_t* target, double scale = 1.0) {
  cairo_t* cr = cairo_create(target);
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_paint(cr);
  cairo_scale(cr, scale, scale);
  cairo_set_source_surface(cr, recording, 0.0, 0.0);
  cairo_paint(cr);
  cairo_destroy(cr);
  cairo_surface_flush(target);
}

void CheckSurface(cairo_surface_t* surface, const std::string& what) {
  const cairo_status_t status = cairo_surface_status(surface);
  if (status != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(surface);
    throw Error(what + ": " + cairo_status_to_string(status));
  }
}

RgbImage FromImageSurface(cairo_surface_t* surface) {
  RgbImage image;
  image.width = cairo_image_surface_get_width(surface);
  image.height = cairo_image_surface_get_height(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const cairo_format_t format = cairo_image_surface_get_format(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  image.rgb.resize(std::size_t(image.width) * std::size_t(image.height) * 3);
  for (int y = 0; y < image.height; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + std::ptrdiff_t(y) * stride);
    for (int x = 0; x < image.width; ++x) {
      // ARGB32 is premultiplied: composite onto white so transparent pixels read as white.
      const std::uint32_t p = row[x];
      const unsigned a = format == CAIRO_FORMAT_ARGB32 ? (p >> 24) & 0xff : 0xff;
      const std::size_t k = (std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3;
      image.rgb[k] = std::uint8_t(((p >> 16) & 0xff) + (255 - a));
      image.rgb[k + 1] = std::uint8_t(((p >> 8) & 0xff) + (255 - a));
      image.rgb[k + 2] = std::uint8_t((p & 0xff) + (255 - a));
    }
  }
  return image;
}

}  // namespace

FileFormat FormatOfPath(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".png") return FileFormat::kPng;
  if (extension == ".svg") return FileFormat::kSvg;
  if (extension == ".pdf") return FileFormat::kPdf;
  throw InvalidParameter("output file", path, "a name ending in .png, .svg or .pdf");
}

Rgb RgbImage::At(int x, int y) const {
  if (!Contains(x, y)) return kWhite;
  const std::size_t k = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
  return Rgb{rgb[k], rgb[k + 1], rgb[k + 2]};
}

RgbImage ReadPng(const std::string& path) {
  cairo_surface_t* surface = cairo_image_surface_create_from_png(path.c_str());
  CheckSurface(surface, "cannot read the PNG file " + path);
  RgbImage image = FromImageSurface(surface);
  cairo_surface_destroy(surface);
  return image;
}

Canvas::Canvas(int width, int height)
    : width_(width),
      height_(height) {
  if (width < 1 || width > kMaxSide || height < 1 || height > kMaxSide) {
    throw InvalidParameter("image size", std::to_string(width) + "x" + std::to_string(height),
                           "1 to " + std::to_string(kMaxSide) + " pixels per side");
  }
  const cairo_rectangle_t extents{0.0, 0.0, double(width), double(height)};
  recording_ = cairo_recording_surface_create(CAIRO_CONTENT_COLOR_ALPHA, &extents);
  CheckSurface(recording_, "cannot create a drawing surface");
  cr_ = cairo_create(recording_);
  // Unhinted metrics: advances scale linearly with the size and measure what the SVG, PDF and PNG
  // show alike.
  cairo_font_options_t* font = cairo_font_options_create();
  cairo_font_options_set_hint_metrics(font, CAIRO_HINT_METRICS_OFF);
  cairo_font_options_set_hint_style(font, CAIRO_HINT_STYLE_NONE);
  cairo_set_font_options(cr_, font);
  cairo_font_options_destroy(font);
  FillRect(0, 0, width, height, kWhite);
}

Canvas::~Canvas() {
  if (cr_ != nullptr) cairo_destroy(cr_);
  if (recording_ != nullptr) cairo_surface_destroy(recording_);
}

Canvas::Canvas(Canvas&& other) noexcept
    : width_(other.width_),
      height_(other.height_),
      dpi_(other.dpi_),
      recording_(std::exchange(other.recording_, nullptr)),
      cr_(std::exchange(other.cr_, nullptr)) {}

Canvas& Canvas::operator=(Canvas&& other) noexcept {
  std::swap(width_, other.width_);
  std::swap(height_, other.height_);
  std::swap(dpi_, other.dpi_);
  std::swap(recording_, other.recording_);
  std::swap(cr_, other.cr_);
  return *this;
}

void Canvas::SetColour(Rgb c) const {
  cairo_set_source_rgb(cr_, c.r / 255.0, c.g / 255.0, c.b / 255.0);
}

void Canvas::SetFont(double size, bool bold) const {
  cairo_select_font_face(cr_, kFontFamily, CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr_, size);
}

void Canvas::FillRect(double x, double y, double w, double h, Rgb colour) {
  SetColour(colour);
  cairo_rectangle(cr_, x, y, w, h);
  cairo_fill(cr_);
}

void Canvas::StrokeRect(double x, double y, double w, double h, double line_width, Rgb colour) {
  SetColour(colour);
  cairo_set_line_width(cr_, line_width);
  cairo_set_dash(cr_, nullptr, 0, 0.0);
  cairo_rectangle(cr_, x, y, w, h);
  cairo_stroke(cr_);
}

void Canvas::Line(double x0, double y0, double x1, double y1, double line_width, Rgb colour,
                  const Dash& dash) {
  Polyline({x0, y0, x1, y1}, line_width, colour, dash);
}

void Canvas::Polyline(const std::vector<double>& xy, double line_width, Rgb colour,
                      const Dash& dash) {
  if (xy.size() < 4) return;
  for (const double v : xy) {
    if (!std::isfinite(v)) return;
  }
  SetColour(colour);
  cairo_set_line_width(cr_, line_width);
  cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr_, dash.empty() ? CAIRO_LINE_CAP_ROUND : CAIRO_LINE_CAP_BUTT);
  std::vector<double> lengths(dash.size());
  for (std::size_t k = 0; k < dash.size(); ++k) lengths[k] = dash[k] * line_width;
  cairo_set_dash(cr_, lengths.data(), int(lengths.size()), 0.0);
  cairo_move_to(cr_, xy[0], xy[1]);
  for (std::size_t k = 2; k + 1 < xy.size(); k += 2) cairo_line_to(cr_, xy[k], xy[k + 1]);
  cairo_stroke(cr_);
  cairo_set_dash(cr_, nullptr, 0, 0.0);
}

void Canvas::Segments(const std::vector<double>& xyxy, double line_width, Rgb colour) {
  if (xyxy.size() < 4) return;
  SetColour(colour);
  cairo_set_line_width(cr_, line_width);
  cairo_set_line_cap(cr_, CAIRO_LINE_CAP_ROUND);
  cairo_set_dash(cr_, nullptr, 0, 0.0);
  for (std::size_t k = 0; k + 3 < xyxy.size(); k += 4) {
    cairo_move_to(cr_, xyxy[k], xyxy[k + 1]);
    cairo_line_to(cr_, xyxy[k + 2], xyxy[k + 3]);
  }
  cairo_stroke(cr_);
}

void Canvas::FillCircle(double cx, double cy, double radius, Rgb colour) {
  SetColour(colour);
  cairo_new_sub_path(cr_);
  cairo_arc(cr_, cx, cy, radius, 0.0, 2.0 * kPi);
  cairo_fill(cr_);
}

void Canvas::StrokeCircle(double cx, double cy, double radius, double line_width, Rgb colour) {
  SetColour(colour);
  cairo_set_line_width(cr_, line_width);
  cairo_set_dash(cr_, nullptr, 0, 0.0);
  cairo_new_sub_path(cr_);
  cairo_arc(cr_, cx, cy, radius, 0.0, 2.0 * kPi);
  cairo_stroke(cr_);
}

void Canvas::FillPolygon(const std::vector<double>& xy, Rgb colour) {
  if (xy.size() < 6) return;
  SetColour(colour);
  cairo_move_to(cr_, xy[0], xy[1]);
  for (std::size_t k = 2; k + 1 < xy.size(); k += 2) cairo_line_to(cr_, xy[k], xy[k + 1]);
  cairo_close_path(cr_);
  cairo_fill(cr_);
}

void Canvas::Arrow(double x0, double y0, double x1, double y1, double line_width, double head,
                   Rgb colour) {
  const double length = std::hypot(x1 - x0, y1 - y0);
  if (!(length > 0.0) || !std::isfinite(length)) return;
  const double ux = (x1 - x0) / length;
  const double uy = (y1 - y0) / length;
  head = std::min(head, length);
  // The shaft stops where the head begins, so the tip stays sharp.
  Line(x0, y0, x1 - 0.8 * head * ux, y1 - 0.8 * head * uy, line_width, colour);
  const double half = 0.45 * head;
  FillPolygon({x1, y1, x1 - head * ux - half * uy, y1 - head * uy + half * ux,
               x1 - head * ux + half * uy, y1 - head * uy - half * ux},
              colour);
}

TextMetrics Canvas::MeasureText(const std::string& text, double size, bool bold) const {
  SetFont(size, bold);
  cairo_font_extents_t font;
  cairo_font_extents(cr_, &font);
  cairo_text_extents_t ink;
  cairo_text_extents(cr_, text.c_str(), &ink);
  TextMetrics m;
  m.advance = ink.x_advance;
  m.ascent = font.ascent;
  m.descent = font.descent;
  m.ink_top = ink.y_bearing;
  m.ink_bottom = ink.y_bearing + ink.height;
  return m;
}

void Canvas::Text(double x, double y, const std::string& text, double size, Rgb colour,
                  Align h_align, Align v_align, double angle, bool bold) {
  if (text.empty()) return;
  const TextMetrics m = MeasureText(text, size, bold);
  const double dx = h_align == Align::kStart ? 0.0 : (h_align == Align::kCentre ? -0.5 : -1.0);
  const double baseline = v_align == Align::kStart    ? m.ascent
                          : v_align == Align::kCentre ? 0.5 * (m.ascent - m.descent)
                                                      : -m.descent;
  cairo_save(cr_);
  cairo_translate(cr_, x, y);
  cairo_rotate(cr_, -angle * kPi / 180.0);
  SetColour(colour);
  cairo_move_to(cr_, dx * m.advance, baseline);
  cairo_show_text(cr_, text.c_str());
  cairo_restore(cr_);
}

void Canvas::Raster(int x, int y, const RgbImage& image) {
  if (image.width < 1 || image.height < 1) return;
  cairo_surface_t* surface =
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, image.width, image.height);
  CheckSurface(surface, "cannot create a raster of " + std::to_string(image.width) + "x" +
                            std::to_string(image.height) + " pixels");
  cairo_surface_flush(surface);
  unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  for (int j = 0; j < image.height; ++j) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + std::ptrdiff_t(j) * stride);
    for (int i = 0; i < image.width; ++i) {
      const Rgb c = image.At(i, j);
      row[i] = 0xff000000u | (std::uint32_t(c.r) << 16) | (std::uint32_t(c.g) << 8) | c.b;
    }
  }
  cairo_surface_mark_dirty(surface);
  cairo_save(cr_);
  cairo_set_source_surface(cr_, surface, x, y);
  cairo_pattern_set_filter(cairo_get_source(cr_), CAIRO_FILTER_NEAREST);
  cairo_rectangle(cr_, x, y, image.width, image.height);
  cairo_fill(cr_);
  cairo_restore(cr_);
  cairo_surface_destroy(surface);
}

void Canvas::SetResolution(double dpi) {
  if (!(dpi >= 10.0 && dpi <= 4800.0))
    throw InvalidParameter("dpi", std::to_string(dpi), "10 to 4800 dots per inch");
  dpi_ = dpi;
}

void Canvas::Place(const Canvas& other, double x, double y) {
  cairo_surface_flush(other.recording_);
  cairo_save(cr_);
  cairo_rectangle(cr_, x, y, other.width_, other.height_);
  cairo_clip(cr_);
  cairo_set_source_surface(cr_, other.recording_, x, y);
  cairo_paint(cr_);
  cairo_restore(cr_);
}

void Canvas::Clip(double x, double y, double w, double h) {
  cairo_save(cr_);
  cairo_rectangle(cr_, x, y, w, h);
  cairo_clip(cr_);
}

void Canvas::Unclip() { cairo_restore(cr_); }

RgbImage Canvas::Rasterise() const {
  cairo_surface_flush(recording_);
  cairo_surface_t* image = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_, height_);
  CheckSurface(image, "cannot create an image of " + std::to_string(width_) + "x" +
                          std::to_string(height_) + " pixels");
  Replay(recording_, image);
  RgbImage pixels = FromImageSurface(image);
  cairo_surface_destroy(image);
  return pixels;
}

void Canvas::Write(const std::string& path) const {
  const FileFormat format = FormatOfPath(path);
  cairo_surface_flush(recording_);
  std::string bytes;
  cairo_surface_t* target = nullptr;
  const double points = 72.0 / dpi_;  // points a pixel on a page
  if (format == FileFormat::kPng) {
    target = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_, height_);
  } else if (format == FileFormat::kSvg) {
    target = cairo_svg_surface_create_for_stream(AppendToString, &bytes, width_ * points,
                                                 height_ * points);
  } else {
    target = cairo_pdf_surface_create_for_stream(AppendToString, &bytes, width_ * points,
                                                 height_ * points);
  }
  CheckSurface(target, "cannot write " + path);
  Replay(recording_, target, format == FileFormat::kPng ? 1.0 : points);
  cairo_status_t status = CAIRO_STATUS_SUCCESS;
  if (format == FileFormat::kPng) {
    status = cairo_surface_write_to_png_stream(target, AppendToString, &bytes);
  } else {
    cairo_surface_finish(target);
    status = cairo_surface_status(target);
  }
  cairo_surface_destroy(target);
  if (status != CAIRO_STATUS_SUCCESS)
    throw Error("cannot write " + path + ": " + cairo_status_to_string(status));
  try {
    WriteTextAtomically(path, bytes);
  } catch (const Error& e) {
    throw Error("cannot write " + path + " (" + e.what() + ")");
  }
}

}  // namespace dlmfd
