// Signed quantities on the diverging map (colour_map.h, colour_scale.h, field_picture.h): the
// cool to warm map reproduces Moreland's published table, zero is its neutral middle, a signed
// field's automatic range is symmetric about zero so the zero line of the field is neutral grey
// with blue on its negative side and red on its positive side, the colour bar draws the same
// scale, a user's range is kept as given with zero still neutral and the sign still the hue,
// isolines stay visible (black) over the light middle, and only the vorticity, A12 and the
// pressure are signed.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/scratch_path.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/viz/canvas.h"
#include "dlmfd/viz/colour_map.h"
#include "dlmfd/viz/colour_scale.h"
#include "dlmfd/viz/field_picture.h"
#include "dlmfd/viz/node_quantities.h"

namespace dlmfd {
namespace {

// f(x, y) = a + b x on a 2 x 1 domain, 16 x 8 cells (P1 reproduces it exactly).
NodeField LinearField(double a, double b, const std::string& quantity) {
  NodeField f;
  f.quantity = quantity;
  f.grid = Grid{16, 8, 0.125, 0.0, 0.0};
  f.values.resize(f.grid.NodeCount());
  for (int j = 0; j <= f.grid.ny; ++j) {
    for (int i = 0; i <= f.grid.nx; ++i) f.values[f.grid.Index(i, j)] = a + b * f.grid.X(i);
  }
  return f;
}

PictureOptions Diverging(int width = 500, int height = 300) {
  PictureOptions options;
  options.max_width = width;
  options.max_height = height;
  options.diverging = true;
  return options;
}

// The picture through a PNG file and back, as a user's file holds it.
RgbImage WrittenPng(const FieldPicture& picture, const std::string& stem) {
  const std::string path = dlmfd::testing::ScratchPath(stem, ".png");
  picture.image.Write(path);
  RgbImage png = ReadPng(path);
  std::remove(path.c_str());
  return png;
}

// The x of the centre of panel column px on the 2-wide domain.
double ColumnX(const FieldPicture& p, int px) { return (px + 0.5) / p.panel_width * 2.0; }

bool Warm(Rgb c) { return c.r > c.b + 20; }
bool Cool(Rgb c) { return c.b > c.r + 20; }
bool Dark(Rgb c) { return c.r < 128 && c.g < 128 && c.b < 128; }

TEST(DivergingColoursTest, CoolWarmReproducesMorelandsTable) {
  // K. Moreland (2009), the cool to warm map at s = k/32 (his table of 33 entries, 8-bit sRGB).
  const int kTable[33][3] = {
      {59, 76, 192},   {68, 90, 204},   {77, 104, 215},  {87, 117, 225},  {98, 130, 234},
      {108, 142, 241}, {119, 154, 247}, {130, 165, 251}, {141, 176, 254}, {152, 185, 255},
      {163, 194, 255}, {174, 201, 253}, {184, 208, 249}, {194, 213, 244}, {204, 217, 238},
      {213, 219, 230}, {221, 221, 221}, {229, 216, 209}, {236, 211, 197}, {241, 204, 185},
      {245, 196, 173}, {247, 187, 160}, {247, 177, 148}, {247, 166, 135}, {244, 154, 123},
      {241, 141, 111}, {236, 127, 99},  {229, 112, 88},  {222, 96, 77},   {213, 80, 66},
      {203, 62, 56},   {192, 40, 47},   {180, 4, 38}};
  for (int k = 0; k <= 32; ++k) {
    const Rgb c = CoolWarm(k / 32.0);
    EXPECT_LE(std::abs(c.r - kTable[k][0]), 1) << "s = " << k << "/32";
    EXPECT_LE(std::abs(c.g - kTable[k][1]), 1) << "s = " << k << "/32";
    EXPECT_LE(std::abs(c.b - kTable[k][2]), 1) << "s = " << k << "/32";
  }
  // The ends and the neutral middle exactly; clamped outside [0, 1]; NaN is the NaN grey, which
  // the map never produces.
  EXPECT_EQ(CoolWarm(0.0), (Rgb{59, 76, 192}));
  EXPECT_EQ(CoolWarm(0.5), (Rgb{221, 221, 221}));
  EXPECT_EQ(CoolWarm(1.0), (Rgb{180, 4, 38}));
  EXPECT_EQ(CoolWarm(-3.0), CoolWarm(0.0));
  EXPECT_EQ(CoolWarm(7.0), CoolWarm(1.0));
  EXPECT_EQ(CoolWarm(std::numeric_limits<double>::quiet_NaN()), kNanColour);
  for (int k = 0; k <= 256; ++k) EXPECT_NE(CoolWarm(k / 256.0), kNanColour) << k;
}

TEST(DivergingColoursTest, ScaleIsSymmetricAboutZeroWhateverTheRange) {
  // The automatic range of a signed field [-m, m]: zero in the middle.
  const ColourScale symmetric(-2.0, 2.0, false, true);
  EXPECT_EQ(symmetric.Of(0.0), CoolWarm(0.5));
  EXPECT_EQ(symmetric.Of(2.0), CoolWarm(1.0));
  EXPECT_EQ(symmetric.Of(-2.0), CoolWarm(0.0));
  EXPECT_EQ(symmetric.Of(1.0), CoolWarm(0.75));
  EXPECT_EQ(symmetric.Of(-1.0), CoolWarm(0.25));
  EXPECT_EQ(symmetric.AtFraction(0.0), CoolWarm(0.0));
  EXPECT_EQ(symmetric.AtFraction(1.0), CoolWarm(1.0));
  // A lopsided user range [-1, 3]: the scale of m = 3, so zero stays neutral and -1 is as pale a
  // blue as 1 is a pale red; the bar's bottom is not the blue end.
  const ColourScale lopsided(-1.0, 3.0, false, true);
  EXPECT_EQ(lopsided.Of(0.0), CoolWarm(0.5));
  EXPECT_EQ(lopsided.Of(3.0), CoolWarm(1.0));
  EXPECT_EQ(lopsided.Of(-1.0), CoolWarm(0.5 - 1.0 / 6.0));
  EXPECT_EQ(lopsided.Of(1.0), CoolWarm(0.5 + 1.0 / 6.0));
  EXPECT_EQ(lopsided.Of(-5.0), lopsided.Of(-1.0));  // clamped into the range
  EXPECT_EQ(lopsided.AtFraction(0.0), CoolWarm(0.5 - 1.0 / 6.0));
  EXPECT_EQ(lopsided.AtFraction(0.25), CoolWarm(0.5));  // the bar's zero
  // A range without zero, [0.5, 2]: the part of the warm half it covers; no neutral, no blue.
  const ColourScale positive(0.5, 2.0, false, true);
  EXPECT_EQ(positive.Of(0.5), CoolWarm(0.625));
  EXPECT_EQ(positive.Of(2.0), CoolWarm(1.0));
  EXPECT_EQ(positive.Of(0.0), CoolWarm(0.625));
  EXPECT_TRUE(Warm(positive.AtFraction(0.0)));
  // Degenerate: all zero is neutral; a log scale is sequential only.
  EXPECT_EQ(ColourScale(0.0, 0.0, false, true).Of(0.0), CoolWarm(0.5));
  EXPECT_EQ(ColourScale(0.0, 0.0, false, true).AtFraction(0.9), CoolWarm(0.5));
  EXPECT_THROW(ColourScale(1.0, 2.0, true, true), InvalidParameter);
  EXPECT_THROW(ColourScale(2.0, 1.0, false, true), InvalidParameter);
  // The sequential scale is unchanged: viridis over [lo, hi].
  EXPECT_EQ(ColourScale(1.0, 3.0, false, false).Of(2.0), Viridis(0.5));
  EXPECT_EQ(ColourScale(1.0, 3.0, false, false).AtFraction(0.25), Viridis(0.25));
}

TEST(DivergingColoursTest, ZeroOfASignedFieldIsNeutralWithBlueAndRedOnEitherSide) {
  // f = 3 x - 1.5: -1.5 at x = 0, 0 at x = 0.5, 4.5 at x = 2; the range is [-4.5, 4.5].
  const NodeField field = LinearField(-1.5, 3.0, "vorticity");
  const FieldPicture picture = DrawFieldPicture(field, {}, Diverging());
  EXPECT_TRUE(picture.diverging);
  EXPECT_DOUBLE_EQ(picture.value_min, -4.5);
  EXPECT_DOUBLE_EQ(picture.value_max, 4.5);
  const RgbImage png = WrittenPng(picture, "diverging");
  const int row = picture.panel_top + picture.panel_height / 2;
  for (int px = 0; px < picture.panel_width; px += 5) {
    const double f = -1.5 + 3.0 * ColumnX(picture, px);
    const Rgb c = png.At(picture.panel_left + px, row);
    EXPECT_EQ(c, CoolWarm(0.5 + f / 9.0)) << "pixel " << px;
    if (f < -0.3) {
      EXPECT_TRUE(Cool(c)) << "pixel " << px << " f = " << f;
    }
    if (f > 0.3) {
      EXPECT_TRUE(Warm(c)) << "pixel " << px << " f = " << f;
    }
  }
  // The column on x = 0.5 (f = 0) is the neutral grey to within a step of the table.
  const int zero_column = int(picture.PixelX(0.5));
  const Rgb zero = png.At(zero_column, row);
  EXPECT_LE(std::abs(zero.r - 221), 4);
  EXPECT_LE(std::abs(zero.g - 221), 1);
  EXPECT_LE(std::abs(zero.b - 221), 4);
  // The bar: the red end at its top, the blue end at its bottom, neutral at the row of zero
  // (half way), and its ticks symmetric about zero.
  const int bar_x = picture.bar_left + picture.bar_width / 2;
  EXPECT_EQ(png.At(bar_x, picture.bar_top), CoolWarm(1.0 - 0.5 / picture.bar_height));
  EXPECT_EQ(png.At(bar_x, picture.bar_top + picture.bar_height - 1),
            CoolWarm(0.5 / picture.bar_height));
  EXPECT_NEAR(picture.BarY(0.0), picture.bar_top + 0.5 * picture.bar_height, 1e-9);
  const Rgb bar_zero = png.At(bar_x, int(picture.BarY(0.0)));
  EXPECT_LE(std::abs(bar_zero.r - 221), 4);
  EXPECT_LE(std::abs(bar_zero.b - 221), 4);
  const std::vector<double>& ticks = picture.bar_ticks.values;
  ASSERT_GE(ticks.size(), 3u);
  EXPECT_NE(std::find(ticks.begin(), ticks.end(), 0.0), ticks.end());
  EXPECT_DOUBLE_EQ(ticks.front(), -ticks.back());
}

TEST(DivergingColoursTest, AUsersRangeIsKeptAndZeroStaysNeutral) {
  const NodeField field = LinearField(-1.5, 3.0, "A12");  // -1.5 ... 4.5 along x
  PictureOptions options = Diverging();
  options.fixed_range = true;
  options.range_min = -1.0;
  options.range_max = 3.0;
  const FieldPicture picture = DrawFieldPicture(field, {}, options);
  EXPECT_DOUBLE_EQ(picture.value_min, -1.0);
  EXPECT_DOUBLE_EQ(picture.value_max, 3.0);
  const RgbImage png = WrittenPng(picture, "diverging_range");
  const int row = picture.panel_top + picture.panel_height / 2;
  for (int px = 0; px < picture.panel_width; px += 5) {
    const double f = std::clamp(-1.5 + 3.0 * ColumnX(picture, px), -1.0, 3.0);
    EXPECT_EQ(png.At(picture.panel_left + px, row), CoolWarm(0.5 + f / 6.0)) << "pixel " << px;
  }
  // The bar spans [-1, 3]: the red end at its top, a pale blue (not the blue end) at its bottom,
  // neutral a quarter of the way up.
  const int bar_x = picture.bar_left + picture.bar_width / 2;
  const int h = picture.bar_height;
  EXPECT_EQ(png.At(bar_x, picture.bar_top), CoolWarm(0.5 + (3.0 - 2.0 / h) / 6.0));
  const Rgb bottom = png.At(bar_x, picture.bar_top + h - 1);
  EXPECT_EQ(bottom, CoolWarm(0.5 + (-1.0 + 2.0 / h) / 6.0));
  EXPECT_TRUE(Cool(bottom));
  EXPECT_NE(bottom, CoolWarm(0.0));
  EXPECT_NEAR(picture.BarY(0.0), picture.bar_top + 0.75 * h, 1e-9);
}

TEST(DivergingColoursTest, IsolinesAreBlackOverTheLightMiddle) {
  // f = x - 1, range [-1, 1]: one isovalue, 0, on the line x = 1, where the map is light grey.
  const NodeField field = LinearField(-1.0, 1.0, "pressure");
  PictureOptions options = Diverging();
  options.isolines = 1;
  const FieldPicture picture = DrawFieldPicture(field, {}, options);
  ASSERT_EQ(picture.isovalues.size(), 1u);
  EXPECT_DOUBLE_EQ(picture.isovalues[0], 0.0);
  const RgbImage png = WrittenPng(picture, "diverging_isolines");
  const int x = int(picture.PixelX(1.0));
  for (const double y : {0.25, 0.5, 0.75}) {
    bool dark = false;
    for (int dx = -1; dx <= 1; ++dx) dark = dark || Dark(png.At(x + dx, int(picture.PixelY(y))));
    EXPECT_TRUE(dark) << "no black isoline at (1, " << y << ")";
  }
  // Away from it the field's own colours.
  const int px = picture.panel_width / 4;
  EXPECT_EQ(png.At(picture.panel_left + px, int(picture.PixelY(0.5))),
            CoolWarm(0.5 + (ColumnX(picture, px) - 1.0) / 2.0));
  // Marked on the bar in black too, at its middle.
  const int bar_x = picture.bar_left + picture.bar_width / 2;
  bool marked = false;
  for (int dy = -1; dy <= 1; ++dy)
    marked = marked || Dark(png.At(bar_x, int(picture.BarY(0.0)) + dy));
  EXPECT_TRUE(marked);
}

TEST(DivergingColoursTest, AConstantZeroFieldIsNeutralAndLogIsRefused) {
  const NodeField zero = LinearField(0.0, 0.0, "vorticity");
  const FieldPicture picture = DrawFieldPicture(zero, {}, Diverging(400, 300));
  EXPECT_EQ(picture.value_min, 0.0);
  EXPECT_EQ(picture.value_max, 0.0);
  const RgbImage png = WrittenPng(picture, "diverging_zero");
  EXPECT_EQ(png.At(picture.panel_left + 3, picture.panel_top + 3), CoolWarm(0.5));
  EXPECT_EQ(png.At(picture.bar_left + 2, picture.bar_top + 2), CoolWarm(0.5));
  PictureOptions log = Diverging();
  log.log_colours = true;
  EXPECT_THROW(DrawFieldPicture(LinearField(1.0, 1.0, "vorticity"), {}, log), InvalidParameter);
}

TEST(DivergingColoursTest, OnlyTheVorticityA12AndThePressureAreSigned) {
  std::vector<std::string> signed_quantities;
  for (const std::string& q : PictureQuantities()) {
    if (IsSignedQuantity(q)) signed_quantities.push_back(q);
  }
  EXPECT_EQ(signed_quantities, (std::vector<std::string>{"vorticity", "A12", "pressure"}));
}

}  // namespace
}  // namespace dlmfd
