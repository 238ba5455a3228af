// Pictures of node fields (viz/, drawn with cairo): PNG, SVG and PDF files of the laid-out size,
// the PNG read back with cairo has the pixels carrying the P1 value of the field through viridis
// exactly, a colour bar with its ends and ticks (at their logarithms on a log scale), axis tick
// labels, isolines at the exact level sets, arrows, particles drawn where they are with their
// rotation mark, real fonts with descenders, the derived quantities of a snapshot, and degenerate
// fields (constant, NaN) giving finite scales instead of dividing by zero.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../support/scratch_path.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/io/atomic_file.h"
#include "dlmfd/io/field_snapshot.h"
#include "dlmfd/io/particle_history.h"
#include "dlmfd/viz/canvas.h"
#include "dlmfd/viz/caption_lines.h"
#include "dlmfd/viz/colour_map.h"
#include "dlmfd/viz/field_picture.h"
#include "dlmfd/viz/isolines.h"
#include "dlmfd/viz/node_quantities.h"
#include "dlmfd/viz/results_frame.h"

namespace dlmfd {
namespace {

std::string TempFile(const std::string& stem, const std::string& extension) {
  return dlmfd::testing::ScratchPath(stem, extension);
}

// The picture written as a PNG file and read back (cairo's PNG reader).
RgbImage WrittenPng(const FieldPicture& picture, const std::string& stem) {
  const std::string path = TempFile(stem, ".png");
  picture.image.Write(path);
  RgbImage png = ReadPng(path);
  std::remove(path.c_str());
  return png;
}

PictureOptions Sized(int width, int height, const std::string& caption = "") {
  PictureOptions options;
  options.max_width = width;
  options.max_height = height;
  options.caption = caption;
  return options;
}

// Darker than mid grey: text, rims, ticks, and antialiased lines of 1.25 px or more (one of the
// pixels they cross is covered to 5/8 at least).
bool Dark(Rgb c) { return c.r < 128 && c.g < 128 && c.b < 128; }

// Dark pixels in the rectangle [x0, x1) x [y0, y1).
int DarkPixels(const RgbImage& image, int x0, int y0, int x1, int y1) {
  int count = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) count += Dark(image.At(x, y));
  }
  return count;
}

// f(x, y) = a + b x + c y on a 2 x 1 domain, 16 x 8 cells.
NodeField LinearField(double a, double b, double c) {
  NodeField f;
  f.grid = Grid{16, 8, 0.125, 0.0, 0.0};
  f.values.resize(f.grid.NodeCount());
  for (int j = 0; j <= f.grid.ny; ++j) {
    for (int i = 0; i <= f.grid.nx; ++i)
      f.values[f.grid.Index(i, j)] = a + b * f.grid.X(i) + c * f.grid.Y(j);
  }
  return f;
}

TEST(RenderTest, PngSvgAndPdfHaveTheLaidOutSizeAndKeepTheAspectRatio) {
  const FieldPicture picture =
      DrawFieldPicture(LinearField(1.0, 1.0, 0.0), {}, Sized(600, 400, "trA t = 1"));
  EXPECT_LE(picture.image.Width(), 600);
  EXPECT_LE(picture.image.Height(), 400);
  // The panel is floor(2 s) x floor(1 s) for one scale s: the 2:1 aspect to within a pixel.
  EXPECT_NEAR(double(picture.panel_width) / picture.panel_height, 2.0, 2.0 / picture.panel_height);
  // The panel fills the width left by the axes and the colour bar (the binding side here).
  EXPECT_GE(picture.panel_width, 600 / 2);
  const RgbImage png = WrittenPng(picture, "size");
  EXPECT_EQ(png.width, picture.image.Width());
  EXPECT_EQ(png.height, picture.image.Height());
  EXPECT_EQ(png.rgb, picture.image.Rasterise().rgb);

  // SVG and PDF by the extension, 1 pixel = 1 pt.
  const std::string w = std::to_string(picture.image.Width());
  const std::string h = std::to_string(picture.image.Height());
  const std::string svg = TempFile("size", ".svg");
  const std::string pdf = TempFile("size", ".PDF");
  picture.image.Write(svg);
  picture.image.Write(pdf);
  const std::string svg_text = ReadTextFile(svg);
  const std::string pdf_text = ReadTextFile(pdf);
  std::remove(svg.c_str());
  std::remove(pdf.c_str());
  EXPECT_NE(svg_text.find("<svg"), std::string::npos);
  EXPECT_NE(svg_text.find("width=\"" + w + "pt\" height=\"" + h + "pt\""), std::string::npos)
      << svg_text.substr(0, 300);
  EXPECT_EQ(pdf_text.rfind("%PDF-", 0), 0u);
  EXPECT_NE(pdf_text.find("/MediaBox [ 0 0 " + w + " " + h + " ]"), std::string::npos);
  EXPECT_THROW(picture.image.Write(TempFile("size", ".jpg")), InvalidParameter);
  EXPECT_EQ(FormatOfPath("a/b.Svg"), FileFormat::kSvg);
}

TEST(RenderTest, PixelsCarryTheLinearFieldThroughViridis) {
  // P1 reproduces a linear field exactly, so each pixel is Viridis((f(centre) - min) / (max -
  // min)).
  const NodeField field = LinearField(2.0, 3.0, -1.0);
  const FieldPicture picture = DrawFieldPicture(field, {}, Sized(500, 300));
  EXPECT_DOUBLE_EQ(picture.value_min, 2.0 - 1.0);
  EXPECT_DOUBLE_EQ(picture.value_max, 2.0 + 6.0);
  const RgbImage png = WrittenPng(picture, "linear");
  const int probes[][2] = {{0, 0},
                           {picture.panel_width - 1, 0},
                           {0, picture.panel_height - 1},
                           {picture.panel_width / 2, picture.panel_height / 3},
                           {picture.panel_width - 1, picture.panel_height - 1}};
  for (const auto& p : probes) {
    const double x = (p[0] + 0.5) / picture.panel_width * 2.0;
    const double y = (1.0 - (p[1] + 0.5) / picture.panel_height) * 1.0;
    const double t =
        (2.0 + 3.0 * x - y - picture.value_min) / (picture.value_max - picture.value_min);
    EXPECT_EQ(png.At(picture.panel_left + p[0], picture.panel_top + p[1]), Viridis(t))
        << "pixel " << p[0] << "," << p[1];
  }
  // Colour bar: the top row is the maximum, the bottom row the minimum; its frame just outside.
  const int bar_x = picture.bar_left + picture.bar_width / 2;
  EXPECT_EQ(png.At(bar_x, picture.bar_top), Viridis(1.0 - 0.5 / picture.bar_height));
  EXPECT_EQ(png.At(bar_x, picture.bar_top + picture.bar_height - 1),
            Viridis(0.5 / picture.bar_height));
  EXPECT_EQ(png.At(picture.bar_left - 1, picture.bar_top + picture.bar_height / 2), kBlack);
  // Bar ticks: 1-2-5 values inside [1, 8] at their rows, each with its label right of the bar.
  ASSERT_GE(picture.bar_ticks.values.size(), 3u);
  for (std::size_t k = 0; k < picture.bar_ticks.values.size(); ++k) {
    const double v = picture.bar_ticks.values[k];
    EXPECT_NEAR(picture.BarY(v), picture.bar_top + (8.0 - v) / 7.0 * picture.bar_height, 1e-9);
    const int y = int(picture.BarY(v));
    const int right = picture.bar_left + picture.bar_width;
    EXPECT_GT(DarkPixels(png, right + 1, y - 6, png.width, y + 6), 5)
        << picture.bar_ticks.labels[k];
  }
  // Axis ticks in the domain's coordinates, x from 0 to 2, y from 0 to 1, labels below and left.
  EXPECT_DOUBLE_EQ(picture.x_ticks.values.front(), 0.0);
  EXPECT_DOUBLE_EQ(picture.x_ticks.values.back(), 2.0);
  EXPECT_DOUBLE_EQ(picture.y_ticks.values.back(), 1.0);
  const int bottom = picture.panel_top + picture.panel_height;
  for (const double x : picture.x_ticks.values) {
    const int px = int(picture.PixelX(x));
    EXPECT_GT(DarkPixels(png, px - 8, bottom + 3, px + 9, bottom + 24), 5) << "x tick " << x;
  }
  // Nothing is drawn below the panel half way between two x ticks (the labels are centred).
  const double gap_x = 0.5 * (picture.x_ticks.values[0] + picture.x_ticks.values[1]);
  EXPECT_EQ(DarkPixels(png, int(picture.PixelX(gap_x)) - 1, bottom + 1,
                       int(picture.PixelX(gap_x)) + 2, bottom + 12),
            0);
  for (const double y : picture.y_ticks.values) {
    const int py = int(picture.PixelY(y));
    EXPECT_GT(DarkPixels(png, 0, py - 6, picture.panel_left - 2, py + 7), 5) << "y tick " << y;
  }
}

TEST(RenderTest, LogColoursMapLog10OfTheValueAndTheBottomColourToNonPositiveValues) {
  // f = 1 + 49.5 x on the 2 x 1 domain (1 at x = 0, 100 at x = 2) is reproduced exactly by P1, so
  // each pixel is Viridis(log10 f(centre) / 2): log10 of the value, not the value, sets the colour.
  NodeField field = LinearField(1.0, 49.5, 0.0);
  PictureOptions options = Sized(500, 300);
  options.log_colours = true;
  const FieldPicture picture = DrawFieldPicture(field, {}, options);
  EXPECT_DOUBLE_EQ(picture.value_min, 1.0);
  EXPECT_DOUBLE_EQ(picture.value_max, 100.0);
  const RgbImage png = WrittenPng(picture, "log");
  for (int px : {0, picture.panel_width / 4, picture.panel_width / 2, picture.panel_width - 1}) {
    const double x = (px + 0.5) / picture.panel_width * 2.0;
    const double t = std::log10(1.0 + 49.5 * x) / 2.0;
    EXPECT_EQ(png.At(picture.panel_left + px, picture.panel_top + 3), Viridis(t)) << "pixel " << px;
  }
  // The bar is logarithmic: 10 sits half way up it, and its ticks are 1-2-5 multiples or decades.
  EXPECT_NEAR(picture.BarY(10.0), picture.bar_top + 0.5 * picture.bar_height, 1e-9);
  EXPECT_NEAR(picture.BarY(2.0),
              picture.bar_top + (1.0 - std::log10(2.0) / 2.0) * picture.bar_height, 1e-9);
  for (const double v : picture.bar_ticks.values) {
    const double mantissa = v / std::pow(10.0, std::floor(std::log10(v) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1.0) < 1e-9 || std::abs(mantissa - 2.0) < 1e-9 ||
                std::abs(mantissa - 5.0) < 1e-9)
        << v;
  }
  // A field with zero and negative nodes: the scale is set by the positive ones, and the others
  // take the bottom colour instead of a NaN from log10.
  field = LinearField(-1.0, 1.0, 0.0);  // -1 ... 1 along x
  const FieldPicture clipped = DrawFieldPicture(field, {}, options);
  EXPECT_DOUBLE_EQ(clipped.value_min, 0.125);
  EXPECT_DOUBLE_EQ(clipped.value_max, 1.0);
  EXPECT_EQ(clipped.image.Rasterise().At(clipped.panel_left, clipped.panel_top + 3), Viridis(0.0));
}

TEST(RenderTest, CropFieldKeepsTheWindowsNodesAndRejectsEmptyWindows) {
  const NodeField field = LinearField(0.0, 1.0, 10.0);  // f = x + 10 y, h = 1/8 on [0, 2] x [0, 1]
  // [0.3, 0.6] x [0.2, 0.9] widens to whole cells: x from 0.25 to 0.625, y from 0.125 to 1.
  const NodeField crop = CropField(field, 0.3, 0.2, 0.6, 0.9);
  EXPECT_EQ(crop.grid.nx, 3);
  EXPECT_EQ(crop.grid.ny, 7);
  EXPECT_DOUBLE_EQ(crop.grid.x0, 0.25);
  EXPECT_DOUBLE_EQ(crop.grid.y0, 0.125);
  EXPECT_DOUBLE_EQ(crop.grid.h, 0.125);
  ASSERT_EQ(crop.values.size(), crop.grid.NodeCount());
  for (int j = 0; j <= crop.grid.ny; ++j) {
    for (int i = 0; i <= crop.grid.nx; ++i) {
      EXPECT_DOUBLE_EQ(crop.values[crop.grid.Index(i, j)], crop.grid.X(i) + 10.0 * crop.grid.Y(j));
    }
  }
  // A window reaching past the domain is clipped to it.
  const NodeField clipped = CropField(field, -1.0, -1.0, 0.5, 5.0);
  EXPECT_EQ(clipped.grid.nx, 4);
  EXPECT_EQ(clipped.grid.ny, 8);
  EXPECT_THROW(CropField(field, 0.6, 0.2, 0.3, 0.9), InvalidParameter);  // inverted
  EXPECT_THROW(CropField(field, 3.0, 0.0, 4.0, 1.0), InvalidParameter);  // outside
  EXPECT_THROW(CropField(field, 0.0, 0.0, std::nan(""), 1.0), InvalidParameter);
}

TEST(RenderTest, InterpolationFollowsTheSouthWestNorthEastDiagonal) {
  // A hat at the SE node of cell (0, 0): zero on the diagonal SW-NE, 1/2 half way towards it.
  NodeField hat;
  hat.grid = Grid{2, 2, 1.0, 0.0, 0.0};
  hat.values.assign(hat.grid.NodeCount(), 0.0);
  hat.values[hat.grid.Index(1, 0)] = 1.0;
  EXPECT_DOUBLE_EQ(InterpolateP1(hat, 0.5, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(InterpolateP1(hat, 0.75, 0.25), 0.5);
  EXPECT_DOUBLE_EQ(InterpolateP1(hat, 0.25, 0.75), 0.0);  // NW triangle does not see the SE node
  EXPECT_DOUBLE_EQ(InterpolateP1(hat, 1.0, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(InterpolateP1(hat, 5.0, -3.0), 0.0);  // clamped to the corner (2, 0)
}

TEST(RenderTest, ParticleIsAWhiteDiskWithABlackRimAndItsRotationMark) {
  const NodeField field = LinearField(0.0, 1.0, 0.0);
  // Two disks: one turned by 0 (mark pointing in +x), one by pi/2 (mark pointing in +y).
  const DiskOutline disk{1.25, 0.5, 0.2, 0.0, true};
  const DiskOutline turned{0.5, 0.5, 0.2, 0.5 * kPi, true};
  const FieldPicture picture = DrawFieldPicture(field, {disk, turned}, Sized(800, 500));
  const RgbImage png = WrittenPng(picture, "disk");
  const double cx = picture.PixelX(disk.x);
  const double cy = picture.PixelY(disk.y);
  // The same scale on both axes: the circle's radius in pixels.
  const double r = disk.radius / 2.0 * picture.panel_width;
  ASSERT_GT(r, 20.0);
  EXPECT_NEAR(r, disk.radius * picture.panel_height, 1.0);
  EXPECT_EQ(png.At(int(cx), int(cy - 0.5 * r)), kWhite);
  EXPECT_EQ(png.At(int(cx - 0.5 * r), int(cy)), kWhite);
  // The rim: dark pixels within a pixel of radius r on each axis, none just inside.
  const auto rim_at = [&](double dx, double dy) {
    bool dark = false;
    for (double s = r - 1.5; s <= r + 1.5; s += 0.5)
      dark = dark || Dark(png.At(int(std::floor(cx + s * dx)), int(std::floor(cy + s * dy))));
    return dark;
  };
  EXPECT_TRUE(rim_at(1, 0));
  EXPECT_TRUE(rim_at(-1, 0));
  EXPECT_TRUE(rim_at(0, 1));
  EXPECT_TRUE(rim_at(0, -1));
  // The mark of the first disk runs from the centre towards +x; the turned one's towards +y (up).
  EXPECT_TRUE(Dark(png.At(int(cx + 0.5 * r), int(cy))));
  const double tx = picture.PixelX(turned.x);
  EXPECT_TRUE(Dark(png.At(int(tx), int(cy - 0.5 * r))));
  EXPECT_EQ(png.At(int(tx + 0.5 * r), int(cy)), kWhite);
  // Outside the rim the field shows again.
  const int outside = int(std::floor(cx + r + 4));
  const double x = (outside - picture.panel_left + 0.5) / picture.panel_width * 2.0;
  EXPECT_EQ(png.At(outside, int(cy)), Viridis(x / 2.0));
}

TEST(RenderTest, IsolinesAreTheExactLevelSetsOfTheP1Field) {
  // f = x + y on the 2 x 1 domain: P1 reproduces it, so {f = c} is the straight segment of the
  // line x + y = c inside the domain, and the marched segments must add up to its length.
  const NodeField field = LinearField(0.0, 1.0, 1.0);
  for (const double c : {0.7, 1.0, 1.55, 2.5}) {
    const std::vector<double> segments = IsolineSegments(field, c);
    double length = 0.0;
    for (std::size_t k = 0; k < segments.size(); k += 4) {
      EXPECT_NEAR(segments[k] + segments[k + 1], c, 1e-12);
      EXPECT_NEAR(segments[k + 2] + segments[k + 3], c, 1e-12);
      length += std::hypot(segments[k + 2] - segments[k], segments[k + 3] - segments[k + 1]);
    }
    // x from max(0, c - 1) to min(2, c), a chord of slope -1.
    const double expected = std::sqrt(2.0) * (std::min(2.0, c) - std::max(0.0, c - 1.0));
    EXPECT_NEAR(length, expected, 1e-12) << c;
  }
  EXPECT_TRUE(IsolineSegments(field, 5.0).empty());
  const std::vector<double> levels = Isovalues(1.0, 100.0, 3, true);
  ASSERT_EQ(levels.size(), 3u);
  EXPECT_NEAR(levels[0], std::pow(10.0, 0.5), 1e-12);
  EXPECT_NEAR(levels[1], 10.0, 1e-12);

  // Lines only (the paper's figures): f = x has isovalues 0.5, 1, 1.5 on [0, 2]: black vertical
  // lines at those x on white, marked on the colour bar too.
  PictureOptions options = Sized(600, 400);
  options.isolines = 3;
  options.fill = false;
  const FieldPicture picture = DrawFieldPicture(LinearField(0.0, 1.0, 0.0), {}, options);
  ASSERT_EQ(picture.isovalues.size(), 3u);
  EXPECT_DOUBLE_EQ(picture.isovalues[1], 1.0);
  const RgbImage png = WrittenPng(picture, "isolines");
  const int mid = picture.panel_top + picture.panel_height / 2;
  for (const double x : {0.5, 1.0, 1.5}) {
    const int px = int(picture.PixelX(x));
    EXPECT_GT(DarkPixels(png, px - 1, mid, px + 2, mid + 1), 0) << x;
  }
  EXPECT_EQ(png.At(int(picture.PixelX(0.75)), mid), kWhite);
  EXPECT_EQ(png.At(int(picture.PixelX(1.25)), mid), kWhite);
}

TEST(RenderTest, ArrowsShowTheVelocityWithTheSpeedOfOneSpacing) {
  const NodeField field = LinearField(1.0, 0.0, 0.0);  // constant: Viridis(0.5) everywhere
  NodeVelocity velocity{LinearField(0.0, 0.5, 0.0), LinearField(0.0, 0.0, 0.0)};  // u = x / 2
  PictureOptions options = Sized(800, 500);
  options.arrows = 4;
  EXPECT_THROW(DrawFieldPicture(field, {}, options), InvalidParameter);  // no velocity given
  const FieldPicture picture = DrawFieldPicture(field, {}, options, &velocity);
  // Lattice of spacing 0.5: centres at x = 0.25 ... 1.75; the fastest one has u = 0.875.
  EXPECT_DOUBLE_EQ(picture.arrow_speed, 0.875);
  const RgbImage png = WrittenPng(picture, "arrows");
  // The fastest arrow starts at (1.75, 0.25) and points in +x; its shaft covers the field colour.
  const int y = int(picture.PixelY(0.25));
  const int shaft = int(picture.PixelX(1.75 + 0.2));
  bool covered = false;
  for (int dy = -1; dy <= 1; ++dy) covered = covered || png.At(shaft, y + dy) != Viridis(0.5);
  EXPECT_TRUE(covered);
  // Left of the arrow's tail, between lattice columns, the field shows.
  EXPECT_EQ(png.At(int(picture.PixelX(1.75 - 0.1)), y), Viridis(0.5));
}

TEST(RenderTest, TextUsesARealFontWithDescendersThatScales) {
  Canvas canvas(200, 60);
  // p, g and y descend below the baseline; P and a do not; lower case is shorter than capitals.
  for (const char* descending : {"p", "g", "y"})
    EXPECT_GT(canvas.MeasureText(descending, 20).ink_bottom, 2.0) << descending;
  for (const char* sitting : {"P", "a", "steP"})
    EXPECT_LT(canvas.MeasureText(sitting, 20).ink_bottom, 0.6) << sitting;
  EXPECT_GT(canvas.MeasureText("s", 20).ink_top, canvas.MeasureText("P", 20).ink_top + 2.0);
  // Outlines scale: twice the size, twice the advance.
  EXPECT_NEAR(canvas.MeasureText("against", 24).advance,
              2.0 * canvas.MeasureText("against", 12).advance, 1.0);
  // Drawn: "gyp" with its baseline at y = 30 leaves ink below row 31; "PAE" leaves none there.
  canvas.Text(10, 30, "gyp", 20, kBlack, Align::kStart, Align::kCentre);
  const TextMetrics m = canvas.MeasureText("gyp", 20);
  const double baseline = 30 + 0.5 * (m.ascent - m.descent);
  canvas.Text(110, 30, "PAE", 20, kBlack, Align::kStart, Align::kCentre);
  const RgbImage image = canvas.Rasterise();
  const int below = int(std::ceil(baseline)) + 1;
  EXPECT_GT(DarkPixels(image, 0, below, 100, 60), 10);
  EXPECT_EQ(DarkPixels(image, 100, below, 200, 60), 0);
  EXPECT_GT(DarkPixels(image, 100, 0, 200, below), 50);
  EXPECT_EQ(FormatLabel(0.000123456), "0.0001235");
}

TEST(RenderTest, ConstantFieldTakesTheMiddleColourWithoutDividingByZero) {
  NodeField field = LinearField(2.0, 0.0, 0.0);
  const FieldPicture picture = DrawFieldPicture(field, {}, Sized(400, 300, "constant"));
  EXPECT_EQ(picture.value_min, 2.0);
  EXPECT_EQ(picture.value_max, 2.0);
  const RgbImage png = WrittenPng(picture, "constant");
  for (int py = 0; py < picture.panel_height; py += 7) {
    for (int px = 0; px < picture.panel_width; px += 7) {
      ASSERT_EQ(png.At(picture.panel_left + px, picture.panel_top + py), Viridis(0.5));
    }
  }
}

TEST(RenderTest, NanNodesAreGreyAndLeaveTheScaleFinite) {
  NodeField field = LinearField(0.0, 1.0, 0.0);
  field.values[field.grid.Index(8, 4)] = std::numeric_limits<double>::quiet_NaN();
  field.values[field.grid.Index(0, 0)] = std::numeric_limits<double>::infinity();
  const FieldPicture picture = DrawFieldPicture(field, {}, Sized(400, 300));
  EXPECT_TRUE(std::isfinite(picture.value_min));
  EXPECT_TRUE(std::isfinite(picture.value_max));
  EXPECT_DOUBLE_EQ(picture.value_max, 2.0);
  const RgbImage png = WrittenPng(picture, "nan");
  EXPECT_EQ(png.At(int(picture.PixelX(1.0)), int(picture.PixelY(0.5))), kNanColour);
  // Far from the bad nodes the field is drawn as usual.
  const int px = picture.panel_width * 7 / 8;
  const double x = (px + 0.5) / picture.panel_width * 2.0;
  EXPECT_EQ(png.At(picture.panel_left + px, picture.panel_top + picture.panel_height / 2),
            Viridis(x / 2.0));

  NodeField all_nan = field;
  all_nan.values.assign(all_nan.values.size(), std::numeric_limits<double>::quiet_NaN());
  const FieldPicture grey = DrawFieldPicture(all_nan, {}, Sized(400, 300));
  EXPECT_EQ(grey.value_min, 0.0);
  EXPECT_EQ(grey.value_max, 0.0);
}

TEST(RenderTest, LongCaptionsAreFittedInsideTheImage) {
  std::string caption = "Two disks in an Oldroyd-B liquid";
  for (int k = 0; k < 12; ++k) caption += ", fluid.relaxation_time=1.4";
  const FieldPicture picture =
      DrawFieldPicture(LinearField(1.0, 1.0, 0.0), {}, Sized(400, 300, caption + "\nsecond line"));
  const RgbImage png = WrittenPng(picture, "caption");
  // Text in the caption rows, none in the right margin (0.8 font sizes, 7 px here).
  EXPECT_GT(DarkPixels(png, 0, 0, png.width, picture.panel_top), 100);
  EXPECT_EQ(DarkPixels(png, png.width - 5, 0, png.width, picture.panel_top - 2), 0);
}

// A caption wraps at spaces in the room it has: every line fits, no word is lost or cut, the title
// paragraph alone is bold, and a paragraph longer than its lines ends cut with "...".
TEST(CaptionLines, WrapsAtSpacesWithinTheRoomAndCutsOnlyPastTheLastLine) {
  const Canvas measure(1, 1);
  const double fs = 12.0;
  std::string title = "5.2_oldroyd_b, short coarse run:";
  for (int k = 0; k < 4; ++k) title += " h = 1/32, h_p = 1/23.3, dt = 0.001,";
  const std::string caption = title + "\ntrA at t = 2.5";
  const double room = 300.0;
  const std::vector<CaptionLine> lines = CaptionLines(measure, caption, room, fs, 8);
  ASSERT_GT(lines.size(), 3u);
  std::string joined;
  for (std::size_t k = 0; k + 1 < lines.size(); ++k) {
    EXPECT_TRUE(lines[k].bold) << k;
    EXPECT_EQ(lines[k].size, fs) << k;  // wrapped, not shrunk
    EXPECT_LE(measure.MeasureText(lines[k].text, lines[k].size, true).advance, room) << k;
    joined += (k == 0 ? "" : " ") + lines[k].text;
  }
  EXPECT_EQ(joined, title);
  for (const CaptionLine& line : lines) {  // no line starts or ends at the "=" of a setting
    EXPECT_THAT(line.text, ::testing::Not(::testing::EndsWith("="))) << line.text;
    EXPECT_THAT(line.text, ::testing::Not(::testing::StartsWith("="))) << line.text;
  }
  EXPECT_FALSE(lines.back().bold);
  EXPECT_EQ(lines.back().text, "trA at t = 2.5");

  const std::vector<CaptionLine> two = CaptionLines(measure, caption, room, fs, 2);
  ASSERT_EQ(two.size(), 3u);
  EXPECT_EQ(two[0].text, lines[0].text);
  EXPECT_THAT(two[1].text, ::testing::EndsWith("..."));
  EXPECT_LE(measure.MeasureText(two[1].text, two[1].size, true).advance, room);
  EXPECT_GE(two[1].size, 0.75 * fs);
}

// On a narrow picture of a tall domain the caption takes more lines, and the panel moves down
// under them: the caption is not cut.
TEST(RenderTest, ALongCaptionWrapsOnANarrowPictureAndThePanelMovesBelowIt) {
  NodeField tall;
  tall.grid = Grid{4, 16, 0.125, 0.0, 0.0};
  tall.values.assign(tall.grid.NodeCount(), 1.0);
  const std::string words = "5.2_oldroyd_b, short coarse run: h = 1/32, h_p = 1/23.3, dt = 0.001";
  const FieldPicture one_line = DrawFieldPicture(tall, {}, Sized(400, 900, "title"));
  const FieldPicture wrapped = DrawFieldPicture(tall, {}, Sized(400, 900, words));
  const Canvas measure(1, 1);
  const double fs = std::clamp(400 / 55.0, 9.0, 24.0);
  const std::vector<CaptionLine> lines =
      CaptionLines(measure, words, wrapped.image.Width() - 1.6 * fs, fs);
  ASSERT_GE(lines.size(), 2u);
  for (const CaptionLine& line : lines)
    EXPECT_THAT(line.text, ::testing::Not(::testing::EndsWith("...")));
  EXPECT_NEAR(wrapped.panel_top - one_line.panel_top, (lines.size() - 1) * 1.3 * fs, 1.0);
  const RgbImage png = WrittenPng(wrapped, "wrapped_caption");
  EXPECT_EQ(DarkPixels(png, png.width - 5, 0, png.width, wrapped.panel_top - 2), 0);
}

TEST(RenderTest, RejectsMismatchedValuesAndSizesWithoutRoom) {
  NodeField field = LinearField(0.0, 1.0, 0.0);
  EXPECT_THROW(DrawFieldPicture(field, {}, Sized(40, 25)), InvalidParameter);
  field.values.pop_back();
  EXPECT_THROW(DrawFieldPicture(field, {}, Sized(400, 300)), InvalidParameter);
}

// A results directory written by the io writers: two snapshots (Oldroyd-B: trA present) and a
// particle history whose records include the later snapshot's step.
class ResultsFrameTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = dlmfd::testing::ScratchPath("render_results");
    std::filesystem::create_directories(dir_ + "/fields");
    grid_ = Grid{8, 4, 0.25, 0.0, 0.0};
    FlowState state;
    state.u.assign(grid_.NodeCount(), 3.0);
    state.v.assign(grid_.NodeCount(), 4.0);
    state.p.assign(grid_.Coarse().NodeCount(), 0.0);
    state.a11.assign(grid_.NodeCount(), 1.0);
    state.a12.assign(grid_.NodeCount(), 0.0);
    state.a22.assign(grid_.NodeCount(), 1.5);
    ParticleState disk;
    disk.id = 0;
    disk.radius = 0.125;
    disk.position = Vec2(0.5, 0.5);
    state.particles = {disk};
    auto history = ParticleHistoryWriter::Create(dir_ + "/particles.h5", state);
    for (long step : {0L, 5L, 10L}) {
      state.step = step;
      state.time = 0.01 * step;
      state.particles[0].position = Vec2(0.5 + 0.1 * step, 0.5);
      state.particles[0].angular_velocity = 2.0 + 10.0 * state.time;  // linear in t
      history->Append(state, {2.0 * state.time + 5.0 * state.time * state.time});
      if (step != 5) WriteFieldSnapshot(dir_ + "/fields/" + SnapshotFileName(step), grid_, state);
    }
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string dir_;
  Grid grid_;
};

TEST_F(ResultsFrameTest, LatestSnapshotWithItsParticles) {
  EXPECT_EQ(SnapshotSteps(dir_), (std::vector<long>{0, 10}));
  const ResultsFrame frame = LoadResultsFrame(dir_);
  EXPECT_EQ(frame.step, 10);
  EXPECT_EQ(frame.field.quantity, "trA");
  EXPECT_EQ(frame.field.grid.nx, 8);
  EXPECT_EQ(frame.field.grid.ny, 4);
  ASSERT_EQ(frame.field.values.size(), grid_.NodeCount());
  EXPECT_DOUBLE_EQ(frame.field.values[7], 2.5);
  ASSERT_EQ(frame.disks.size(), 1u);
  EXPECT_DOUBLE_EQ(frame.disks[0].x, 1.5);
  EXPECT_DOUBLE_EQ(frame.disks[0].radius, 0.125);
  EXPECT_DOUBLE_EQ(frame.particles_time, frame.time);
  // The rotation angle integrates omega = 2 + 10 t from 0 to 0.1 (the trapezoidal rule is exact
  // for a linear omega): 0.2 + 0.05.
  EXPECT_TRUE(frame.disks[0].has_angle);
  EXPECT_NEAR(frame.disks[0].angle, 0.25, 1e-12);
}

TEST_F(ResultsFrameTest, DerivedQuantitiesOfTheSnapshot) {
  // trA = 1 + 1.5 = 2.5 at every node.
  EXPECT_DOUBLE_EQ(LoadResultsFrame(dir_, 10, "trA-2").field.values[4], 0.5);
  EXPECT_DOUBLE_EQ(LoadResultsFrame(dir_, 10, "log10(trA/2)").field.values[4], std::log10(1.25));
  EXPECT_DOUBLE_EQ(LoadResultsFrame(dir_, 10, "A22").field.values[4], 1.5);
  EXPECT_DOUBLE_EQ(LoadResultsFrame(dir_, 10, "A12").field.values[4], 0.0);
  EXPECT_DOUBLE_EQ(LoadResultsFrame(dir_, 10, "vorticity").field.values[4], 0.0);  // uniform flow
  const ResultsFrame pressure = LoadResultsFrame(dir_, 10, "pressure");
  EXPECT_EQ(pressure.field.grid.nx, grid_.nx / 2);  // the 2h mesh
  EXPECT_DOUBLE_EQ(pressure.field.grid.h, 2.0 * grid_.h);
  EXPECT_EQ(pressure.field.values.size(), grid_.Coarse().NodeCount());
  EXPECT_TRUE(LoadResultsFrame(dir_, 10, "speed").has_velocity);
  try {
    LoadResultsFrame(dir_, 10, "stream");
    FAIL() << "an unknown quantity must throw";
  } catch (const InvalidParameter& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr(PictureQuantityList()));
  }
}

TEST(NodeQuantities, VorticityIsExactForQuadraticVelocities) {
  // Second-order differences (centred inside, one-sided three-point on the sides) are exact for
  // quadratics: u = -y + y^2, v = x + 3 x^2 gives omega = 1 + 6x + 1 - 2y.
  const Grid g{6, 4, 0.25, -0.5, 0.25};
  std::vector<double> u(g.NodeCount()), v(g.NodeCount());
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      u[g.Index(i, j)] = -g.Y(j) + g.Y(j) * g.Y(j);
      v[g.Index(i, j)] = g.X(i) + 3.0 * g.X(i) * g.X(i);
    }
  }
  const std::vector<double> omega = NodeVorticity(g, u, v);
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i)
      EXPECT_NEAR(omega[g.Index(i, j)], 2.0 + 6.0 * g.X(i) - 2.0 * g.Y(j), 1e-12) << i << "," << j;
  }
}

TEST_F(ResultsFrameTest, ChosenSnapshotSpeedAndErrors) {
  const ResultsFrame frame = LoadResultsFrame(dir_, 0, "speed");
  EXPECT_EQ(frame.step, 0);
  EXPECT_EQ(frame.field.quantity, "speed");
  EXPECT_DOUBLE_EQ(frame.field.values[3], 5.0);
  EXPECT_DOUBLE_EQ(frame.disks[0].x, 0.5);
  EXPECT_THROW(LoadResultsFrame(dir_, 5),
               InvalidParameter);  // particles at step 5, no field snapshot
  EXPECT_THROW(LoadResultsFrame(dir_, -1, "no such quantity"), InvalidParameter);
  EXPECT_THROW(LoadResultsFrame(dir_ + "/nothing"), InvalidParameter);
  // And the frame draws: the disk at x = 1.5 is white at its centre.
  const FieldPicture picture =
      DrawFieldPicture(LoadResultsFrame(dir_).field, LoadResultsFrame(dir_).disks, Sized(400, 300));
  // (Left of the centre: the rotation mark, at 0.25 rad, points right.)
  const double r = 0.125 / picture.grid.Width() * picture.panel_width;
  EXPECT_EQ(
      WrittenPng(picture, "frame").At(int(picture.PixelX(1.5) - 0.5 * r), int(picture.PixelY(0.5))),
      kWhite);
}

}  // namespace
}  // namespace dlmfd
