// RasterImage: clipped pixel operations on an RGB byte buffer.
#include "dlmfd/viz/raster_image.h"

#include <algorithm>
#include <cmath>

#include "dlmfd/core/errors.h"
#include "dlmfd/viz/bitmap_font.h"

namespace dlmfd {

RasterImage::RasterImage(int width, int height, Rgb background)
    : width_(width),
      height_(height) {
  if (width < 1 || width > kMaxSide || height < 1 || height > kMaxSide) {
    throw InvalidParameter("image size", std::to_string(width) + "x" + std::to_string(height),
                           "1 to " + std::to_string(kMaxSide) + " pixels per side");
  }
  bytes_.resize(std::size_t(width) * std::size_t(height) * 3);
  FillRect(0, 0, width, height, background);
}

Rgb RasterImage::At(int x, int y) const {
  if (!Contains(x, y)) return kWhite;
  const std::size_t k = (std::size_t(y) * std::size_t(width_) + std::size_t(x)) * 3;
  return Rgb{bytes_[k], bytes_[k + 1], bytes_[k + 2]};
}

void RasterImage::Set(int x, int y, Rgb colour) {
  if (!Contains(x, y)) return;
  const std::size_t k = (std::size_t(y) * std::size_t(width_) + std::size_t(x)) * 3;
  bytes_[k] = colour.r;
  bytes_[k + 1] = colour.g;
  bytes_[k + 2] = colour.b;
}

void RasterImage::FillRect(int x, int y, int w, int h, Rgb colour) {
  const int x_end = std::min(width_, x + w);
  const int y_end = std::min(height_, y + h);
  for (int py = std::max(0, y); py < y_end; ++py) {
    for (int px = std::max(0, x); px < x_end; ++px) Set(px, py, colour);
  }
}

void RasterImage::FrameRect(int x, int y, int w, int h, Rgb colour) {
  FillRect(x, y, w, 1, colour);
  FillRect(x, y + h - 1, w, 1, colour);
  FillRect(x, y, 1, h, colour);
  FillRect(x + w - 1, y, 1, h, colour);
}

void RasterImage::FillDisk(double cx, double cy, double radius, Rgb colour) {
  DrawCircle(cx, cy, 0.5 * radius, radius, colour);
}

void RasterImage::DrawCircle(double cx, double cy, double radius, double width, Rgb colour) {
  const double outer = radius + 0.5 * width;
  const double inner = std::max(0.0, radius - 0.5 * width);
  const int x_lo = std::max(0, int(std::floor(cx - outer)));
  const int x_hi = std::min(width_ - 1, int(std::ceil(cx + outer)));
  const int y_lo = std::max(0, int(std::floor(cy - outer)));
  const int y_hi = std::min(height_ - 1, int(std::ceil(cy + outer)));
  for (int py = y_lo; py <= y_hi; ++py) {
    for (int px = x_lo; px <= x_hi; ++px) {
      const double d = std::hypot(px + 0.5 - cx, py + 0.5 - cy);
      if (d >= inner && d <= outer) Set(px, py, colour);
    }
  }
}

void RasterImage::DrawLine(double x0, double y0, double x1, double y1, double width, Rgb colour) {
  if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1)) return;
  const double half = 0.5 * std::max(1.0, width);
  // The bounding box, clamped in floating point first so that far-away ends never overflow an int.
  const auto clamp_to = [](double v, int hi) {
    return int(std::clamp(std::floor(v), -1.0, double(hi)));
  };
  const int x_lo = std::max(0, clamp_to(std::min(x0, x1) - half, width_));
  const int x_hi = std::min(width_ - 1, clamp_to(std::max(x0, x1) + half, width_));
  const int y_lo = std::max(0, clamp_to(std::min(y0, y1) - half, height_));
  const int y_hi = std::min(height_ - 1, clamp_to(std::max(y0, y1) + half, height_));
  const double dx = x1 - x0;
  const double dy = y1 - y0;
  const double length2 = dx * dx + dy * dy;
  if (!std::isfinite(length2)) return;
  for (int py = y_lo; py <= y_hi; ++py) {
    for (int px = x_lo; px <= x_hi; ++px) {
      const double cx = px + 0.5 - x0;
      const double cy = py + 0.5 - y0;
      // Distance from the pixel centre to the nearest point of the segment.
      const double s = length2 > 0.0 ? std::clamp((cx * dx + cy * dy) / length2, 0.0, 1.0) : 0.0;
      if (std::hypot(cx - s * dx, cy - s * dy) <= half) Set(px, py, colour);
    }
  }
}

void RasterImage::DrawText(int x, int y, const std::string& text, int scale, Rgb colour) {
  for (std::size_t n = 0; n < text.size(); ++n) {
    const Glyph& glyph = GlyphFor(text[n]);
    const int left = x + int(n) * kGlyphAdvance * scale;
    for (int row = 0; row < kGlyphHeight; ++row) {
      for (int col = 0; col < kGlyphWidth; ++col) {
        if (glyph[std::size_t(row)] & (0x10 >> col)) {
          FillRect(left + col * scale, y + row * scale, scale, scale, colour);
        }
      }
    }
  }
}

}  // namespace dlmfd
