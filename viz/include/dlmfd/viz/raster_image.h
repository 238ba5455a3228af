// An 8-bit RGB raster, row 0 at the top, with the few drawing operations the field pictures need.
//
// Drawing clips to the image: shapes partly outside are drawn partly, never out of bounds.
// Not supported: alpha, anti-aliasing, dashed lines.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dlmfd/viz/colour_map.h"

namespace dlmfd {

class RasterImage {
 public:
  // Throws InvalidParameter unless 1 <= width, height <= kMaxSide.
  RasterImage(int width, int height, Rgb background = kWhite);

  static constexpr int kMaxSide = 16384;

  int Width() const { return width_; }
  int Height() const { return height_; }
  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  Rgb At(int x, int y) const;
  void Set(int x, int y, Rgb colour);
  void FillRect(int x, int y, int w, int h, Rgb colour);
  // One-pixel rectangle outline.
  void FrameRect(int x, int y, int w, int h, Rgb colour);
  // Fills every pixel whose centre lies within `radius` of (cx, cy) (pixel units, y down).
  void FillDisk(double cx, double cy, double radius, Rgb colour);
  // A ring: pixels whose centre is at a distance in [radius - width/2, radius + width/2].
  void DrawCircle(double cx, double cy, double radius, double width, Rgb colour);
  // A straight segment of the given width (>= 1 pixel): every pixel whose centre lies within
  // width/2 of the segment from (x0, y0) to (x1, y1) (pixel units, y down; pixel (i, j) has its
  // centre at (i + 0.5, j + 0.5)). Consecutive pixels of a width-1 line touch at least at a corner.
  // A segment with a non-finite end, or too long for its squared length to be finite (~1e154), is
  // not drawn.
  void DrawLine(double x0, double y0, double x1, double y1, double width, Rgb colour);
  // Text in the built-in 5x7 font, each font pixel a scale x scale block; (x, y) the top left.
  void DrawText(int x, int y, const std::string& text, int scale, Rgb colour);
  // Rows of width*3 bytes, top row first.
  const std::vector<std::uint8_t>& Bytes() const { return bytes_; }

 private:
  int width_;
  int height_;
  std::vector<std::uint8_t> bytes_;
};

}  // namespace dlmfd
