// A drawing surface for pictures and charts on cairo (design.md 2: a well-kept drawing library,
// real fonts), written as PNG, SVG or PDF by the output file's extension.
//
// Method: every drawing operation goes to a cairo recording surface of the canvas's size (in
// pixels); Write replays the recording onto an
// image, SVG or PDF surface, so one drawing gives all three formats with vector lines and text in
// SVG and PDF. The canvas has a resolution (dots per inch, default 72): an SVG or PDF page is
// width x height pixels at that resolution (width * 72 / dpi points), so a figure drawn at
// 3.5 in x 300 dpi is a 3.5 in page whose embedded field raster has 300 pixels an inch. PNG
// files are the pixels. Text uses cairo's toy font API with DejaVu Sans (fonts-dejavu-core, found
// through fontconfig): real outlines with descenders, any size. Coordinates are continuous, y down;
// the pixel (i, j) covers [i, i+1) x [j, j+1). Lines, circles and text are antialiased; Raster
// paints a block of pixels exactly (nearest filter at scale 1), so field pictures keep exact
// colours. Files are written through a temporary name and renamed (design.md 3.2). Not supported:
// other formats, text layout beyond one line (no pango), transparency in output. References:
// cairo 1.16 manual, https://www.cairographics.org/manual/.
#pragma once

#include <cairo.h>

#include <cstdint>
#include <string>
#include <vector>

#include "dlmfd/viz/colour_map.h"

namespace dlmfd {

enum class FileFormat { kPng, kSvg, kPdf };
// The format named by the path's extension (.png, .svg, .pdf, any case); throws InvalidParameter
// naming the output file and the allowed extensions otherwise.
FileFormat FormatOfPath(const std::string& path);

// 8-bit RGB pixels, row 0 at the top: a rasterised canvas, or a PNG file read back.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // width * 3 bytes per row
  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  Rgb At(int x, int y) const;
};
// Reads a PNG file with cairo; throws dlmfd::Error naming the file when it cannot.
RgbImage ReadPng(const std::string& path);

enum class Align { kStart, kCentre, kEnd };
// Font metrics and ink extents of a string, in pixels relative to its origin on the baseline
// (y down: ink_bottom > 0 means ink below the baseline, as in p, g and y).
struct TextMetrics {
  double advance = 0.0;     // horizontal advance of the whole string
  double ascent = 0.0;      // of the font, above the baseline
  double descent = 0.0;     // of the font, below the baseline
  double ink_top = 0.0;     // y of the highest ink (< 0 above the baseline)
  double ink_bottom = 0.0;  // y of the lowest ink
};

// A dash pattern: lengths in line widths, on then off; empty is solid.
using Dash = std::vector<double>;

class Canvas {
 public:
  // Throws InvalidParameter unless 1 <= width, height <= kMaxSide. The background is white.
  Canvas(int width, int height);
  ~Canvas();
  Canvas(Canvas&& other) noexcept;
  Canvas& operator=(Canvas&& other) noexcept;
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  static constexpr int kMaxSide = 16384;
  static constexpr const char* kFontFamily = "DejaVu Sans";

  int Width() const { return width_; }
  int Height() const { return height_; }
  // Dots per inch of SVG and PDF output (see the header); throws InvalidParameter unless in
  // [10, 4800].
  void SetResolution(double dpi);
  double Resolution() const { return dpi_; }
  // Draws `other` (its recording: vectors stay vectors) with its top left corner at (x, y).
  void Place(const Canvas& other, double x, double y);

  void FillRect(double x, double y, double w, double h, Rgb colour);
  void StrokeRect(double x, double y, double w, double h, double line_width, Rgb colour);
  void Line(double x0, double y0, double x1, double y1, double line_width, Rgb colour,
            const Dash& dash = {});
  // A polyline through the points (x0, y0, x1, y1, ...).
  void Polyline(const std::vector<double>& xy, double line_width, Rgb colour,
                const Dash& dash = {});
  // Disjoint segments (x0, y0, x1, y1 per segment) stroked as one path (isolines).
  void Segments(const std::vector<double>& xyxy, double line_width, Rgb colour);
  void FillCircle(double cx, double cy, double radius, Rgb colour);
  void StrokeCircle(double cx, double cy, double radius, double line_width, Rgb colour);
  // A closed polygon through the points, filled.
  void FillPolygon(const std::vector<double>& xy, Rgb colour);
  // An arrow from (x0, y0) to (x1, y1) with a head of the given length.
  void Arrow(double x0, double y0, double x1, double y1, double line_width, double head,
             Rgb colour);

  TextMetrics MeasureText(const std::string& text, double size, bool bold = false) const;
  // One line of text: (x, y) is its anchor, the start, centre or end of the advance along the
  // text's direction (h_align) and its top (font ascent), baseline middle or bottom (v_align);
  // angle in degrees, counter-clockwise (90: reading upwards).
  void Text(double x, double y, const std::string& text, double size, Rgb colour,
            Align h_align = Align::kStart, Align v_align = Align::kStart, double angle = 0.0,
            bool bold = false);

  // Pixels of `image` painted exactly at integer (x, y), one image pixel per canvas pixel.
  void Raster(int x, int y, const RgbImage& image);
  // Later drawing is limited to the rectangle until Unclip.
  void Clip(double x, double y, double w, double h);
  void Unclip();

  // Writes PNG, SVG or PDF by the extension of `path` (FormatOfPath); throws InvalidParameter for
  // another extension, dlmfd::Error with the path when writing fails.
  void Write(const std::string& path) const;
  // The picture as pixels (what the PNG file holds).
  RgbImage Rasterise() const;

 private:
  void SetColour(Rgb colour) const;
  void SetFont(double size, bool bold) const;

  int width_;
  int height_;
  double dpi_ = 72.0;
  cairo_surface_t* recording_ = nullptr;
  cairo_t* cr_ = nullptr;
};

}  // namespace dlmfd
