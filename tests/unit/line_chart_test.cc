// Line charts (viz/line_chart): 1-2-5 and decade ticks on known ranges, readable ticks over less
// than a decade, data landing on the expected pixels with the series colour (cairo draws
// antialiased lines of 2 px or more, so the pixels along a line's centre are fully covered), a NaN
// or a value <= 0 on a log axis breaking the line instead of crashing, clear errors for empty
// input, equal axis scales, styles that tell 28 and more series apart, and a legend title.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../support/scratch_path.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/viz/canvas.h"
#include "dlmfd/viz/line_chart.h"

namespace dlmfd {
namespace {

using ::testing::ElementsAre;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

void ExpectValues(const AxisTicks& ticks, const std::vector<double>& expected) {
  ASSERT_EQ(ticks.values.size(), expected.size());
  ASSERT_EQ(ticks.labels.size(), expected.size());
  // Tick values are k * step computed in double: equal to the decimal value to round-off.
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_NEAR(ticks.values[k], expected[k], 1e-12 * std::max(1.0, std::abs(expected[k]))) << k;
  }
}

TEST(LinearTicks, OneTwoFiveStepsInsideTheRange) {
  const AxisTicks a = LinearTicks(0.0, 0.37, 5);
  ExpectValues(a, {0.0, 0.1, 0.2, 0.3});
  EXPECT_THAT(a.labels, ElementsAre("0.0", "0.1", "0.2", "0.3"));

  // Span 17 over 5 wanted: raw step 3.4 -> 5.
  const AxisTicks b = LinearTicks(-3.0, 14.0, 5);
  ExpectValues(b, {0.0, 5.0, 10.0});
  EXPECT_THAT(b.labels, ElementsAre("0", "5", "10"));

  // Span 0.9 over 5: raw 0.18 -> 0.2; negative values keep their sign.
  const AxisTicks c = LinearTicks(-0.45, 0.45, 5);
  ExpectValues(c, {-0.4, -0.2, 0.0, 0.2, 0.4});
  EXPECT_THAT(c.labels, ElementsAre("-0.4", "-0.2", "0.0", "0.2", "0.4"));

  // A narrow range far from zero: labels carry the digits that tell ticks apart.
  const AxisTicks d = LinearTicks(7.2013, 7.2061, 5);
  ExpectValues(d, {7.202, 7.203, 7.204, 7.205, 7.206});
  EXPECT_THAT(d.labels, ElementsAre("7.202", "7.203", "7.204", "7.205", "7.206"));

  // A narrow range of moderate values keeps fixed decimals, as many as the step needs.
  const AxisTicks f = LinearTicks(0.24999995, 0.25000034, 4);
  ExpectValues(f, {0.2500000, 0.2500001, 0.2500002, 0.2500003});
  EXPECT_THAT(f.labels, ElementsAre("0.2500000", "0.2500001", "0.2500002", "0.2500003"));

  // Axes of only tiny values switch to scientific notation.
  const AxisTicks e = LinearTicks(1e-6, 4.5e-6, 4);
  ExpectValues(e, {1e-6, 2e-6, 3e-6, 4e-6});
  EXPECT_THAT(e.labels, ElementsAre("1e-06", "2e-06", "3e-06", "4e-06"));
}

TEST(LinearTicks, NeverMoreThanWantedPlusOne) {
  for (const double hi : {0.11, 0.37, 1.0, 2.9, 7.77, 123.0, 1e5}) {
    for (int wanted = 2; wanted <= 10; ++wanted) {
      const AxisTicks t = LinearTicks(0.0, hi, wanted);
      EXPECT_GE(t.values.size(), 2u) << hi << " " << wanted;
      EXPECT_LE(t.values.size(), std::size_t(wanted) + 1) << hi << " " << wanted;
    }
  }
}

TEST(LinearTicks, RejectsEmptyOrNonFiniteRanges) {
  EXPECT_THROW(LinearTicks(1.0, 1.0, 5), InvalidParameter);
  EXPECT_THROW(LinearTicks(0.0, kNan, 5), InvalidParameter);
}

TEST(LogTicks, DecadesInsideTheRange) {
  const AxisTicks a = LogTicks(3e-4, 2e-1, 6);
  ExpectValues(a, {1e-3, 1e-2, 1e-1});
  EXPECT_THAT(a.labels, ElementsAre("0.001", "0.01", "0.1"));

  // Twelve decades, at most 4 wanted: every third decade, on multiples of three.
  const AxisTicks b = LogTicks(2e-7, 3e5, 4);
  ExpectValues(b, {1e-6, 1e-3, 1.0, 1e3});
  // One notation on the whole axis: never "1e-6" beside "0.001".
  EXPECT_THAT(b.labels, ElementsAre("1e-6", "1e-3", "1e0", "1e3"));
  const AxisTicks b2 = LogTicks(20.0, 2e7, 6);
  ExpectValues(b2, {1e2, 1e3, 1e4, 1e5, 1e6, 1e7});
  EXPECT_THAT(b2.labels, ElementsAre("1e2", "1e3", "1e4", "1e5", "1e6", "1e7"));

  // Less than three decades: 1-2-5 multiples, unless they are more than wanted + 1.
  const AxisTicks c = LogTicks(1.5, 60.0, 6);
  ExpectValues(c, {2.0, 5.0, 10.0, 20.0, 50.0});
  const AxisTicks c2 = LogTicks(3e-4, 2e-2, 8);
  ExpectValues(c2, {5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 2e-2});
  EXPECT_THAT(c2.labels, ElementsAre("5e-4", "1e-3", "2e-3", "5e-3", "1e-2", "2e-2"));
  const AxisTicks c3 = LogTicks(3e-4, 2e-2, 4);
  ExpectValues(c3, {1e-3, 1e-2});

  // Less than two 1-2-5 multiples: linear ticks on positive values (raw step 0.7 -> 1).
  const AxisTicks d = LogTicks(2.1, 4.9, 4);
  ExpectValues(d, {3.0, 4.0});
}

TEST(LogTicks, LessThanADecadeGetsThreeOrMoreReadableTicks) {
  // [0.13, 0.9]: only 0.2 and 0.5 are 1-2-5 multiples; linear ticks read better.
  const AxisTicks a = LogTicks(0.13, 0.9, 4);
  ExpectValues(a, {0.2, 0.4, 0.6, 0.8});
  EXPECT_THAT(a.labels, ElementsAre("0.2", "0.4", "0.6", "0.8"));
  // [1.2, 1.9]: no 1-2-5 multiple at all.
  const AxisTicks b = LogTicks(1.2, 1.9, 4);
  ExpectValues(b, {1.2, 1.4, 1.6, 1.8});
  // [0.15, 2.5]: four multiples across a decade boundary stay.
  const AxisTicks c = LogTicks(0.15, 2.5, 6);
  ExpectValues(c, {0.2, 0.5, 1.0, 2.0});
}

TEST(LogTicks, RejectsNonPositiveRanges) {
  EXPECT_THROW(LogTicks(0.0, 1.0, 5), InvalidParameter);
  EXPECT_THROW(LogTicks(-1.0, 1.0, 5), InvalidParameter);
}

TEST(CanvasLine, CoversThePixelsAlongTheSegmentOnly) {
  Canvas canvas(40, 30);
  const Rgb red{255, 0, 0};
  canvas.Line(5.5, 11.0, 30.5, 11.0, 2.0, red);  // rows 10 and 11 exactly, butt ends rounded
  const RgbImage image = canvas.Rasterise();
  for (int x = 7; x <= 29; ++x) {
    EXPECT_EQ(image.At(x, 10), red) << x;
    EXPECT_EQ(image.At(x, 11), red) << x;
  }
  for (int x = 0; x < 40; ++x) {
    EXPECT_EQ(image.At(x, 8), kWhite) << x;
    EXPECT_EQ(image.At(x, 13), kWhite) << x;
  }
  EXPECT_EQ(image.At(1, 10), kWhite);
  EXPECT_EQ(image.At(35, 10), kWhite);
  // Far-away ends are clipped; non-finite ends are not drawn.
  Canvas clipped(10, 10);
  clipped.Line(-1e6, 5.0, 1e6, 5.0, 2.0, red);
  clipped.Line(kNan, 1.0, 5.0, 1.0, 2.0, red);
  const RgbImage c = clipped.Rasterise();
  for (int x = 0; x < 10; ++x) {
    EXPECT_EQ(c.At(x, 4), red) << x;
    EXPECT_EQ(c.At(x, 1), kWhite) << x;
  }
}

// Whether `colour` is at the pixel containing (px, py) or one of its 8 neighbours: a slanted line
// 2 px wide covers fully the pixels whose centres are within 1 - (|cos| + |sin|) / 2 >= 0.29 px of
// its axis, and one of the 3 x 3 pixels around a point on it is that near.
bool NearColour(const RgbImage& image, double px, double py, Rgb colour) {
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (image.At(int(px) + dx, int(py) + dy) == colour) return true;
    }
  }
  return false;
}

LineChartOptions Options(AxisScale x = AxisScale::kLinear, AxisScale y = AxisScale::kLinear) {
  LineChartOptions o;
  o.width = 600;
  o.height = 400;
  o.title = "particle 0";
  o.x_axis = {"t", x};
  o.y_axis = {"v", y};
  return o;
}

TEST(LineChart, PointsLandOnTheirPixelsInTheSeriesColour) {
  LineChart chart(Options());
  chart.AddSeries({"run a", {0.0, 1.0, 2.0}, {0.0, 2.0, 1.0}, true});
  chart.AddSeries({"run b", {0.0, 2.0}, {1.5, 1.5}, false});
  const ChartPicture p = chart.Draw();
  const RgbImage shown = p.image.Rasterise();
  EXPECT_EQ(shown.width, 600);
  EXPECT_EQ(p.image.Width(), 600);
  EXPECT_EQ(p.image.Height(), 400);
  // The data range [0, 2] widened by kPadding on each side.
  EXPECT_DOUBLE_EQ(p.x_lo, -2.0 * kPadding);
  EXPECT_DOUBLE_EQ(p.x_hi, 2.0 + 2.0 * kPadding);
  // The ends of the range sit on the centres of the first and last pixels of the panel.
  EXPECT_DOUBLE_EQ(p.PixelX(p.x_lo), p.panel_left + 0.5);
  EXPECT_DOUBLE_EQ(p.PixelX(p.x_hi), p.panel_left + p.panel_width - 0.5);
  EXPECT_DOUBLE_EQ(p.PixelY(p.y_lo), p.panel_top + p.panel_height - 0.5);
  EXPECT_DOUBLE_EQ(p.PixelY(p.y_hi), p.panel_top + 0.5);
  // Series a's marker at (1, 2); halfway along its first segment, the point (0.5, 1).
  const Rgb a = SeriesColour(0);
  EXPECT_EQ(shown.At(int(p.PixelX(1.0)), int(p.PixelY(2.0))), a);
  EXPECT_TRUE(NearColour(shown, p.PixelX(0.5), p.PixelY(1.0), a));
  // Series b, the horizontal line y = 1.5, away from series a (at y = 1.2 there).
  const Rgb b = SeriesColour(1);
  EXPECT_NE(a, b);
  EXPECT_EQ(shown.At(int(p.PixelX(1.8)), int(p.PixelY(1.5))), b);
  // Between a's descending segment and the top of the range, at (1.8, 1.7): background or grid
  // only.
  const Rgb empty = shown.At(int(p.PixelX(1.8)), int(p.PixelY(1.7)));
  EXPECT_TRUE(empty == kWhite || empty == (Rgb{225, 225, 225}));
  // Ticks on the widened ranges.
  EXPECT_GE(p.x_ticks.values.size(), 2u);
  EXPECT_GE(p.y_ticks.values.size(), 2u);
}

TEST(LineChart, NanBreaksTheLine) {
  LineChart chart(Options());
  chart.AddSeries({"broken", {0.0, 1.0, 2.0, 3.0}, {0.0, 0.0, kNan, 0.0}, false});
  chart.AddSeries({"ref", {0.0, 3.0}, {1.0, 1.0}, false});
  const ChartPicture p = chart.Draw();
  const RgbImage shown = p.image.Rasterise();
  const Rgb c = SeriesColour(0);
  const int row = int(p.PixelY(0.0));
  // Drawn from x = 0 to 1; nothing between 1 and 3 (the NaN at x = 2 removes both neighbours'
  // segments); the isolated point at x = 3 is a dot.
  EXPECT_EQ(shown.At(int(p.PixelX(0.5)), row), c);
  EXPECT_NE(shown.At(int(p.PixelX(1.5)), row), c);
  EXPECT_NE(shown.At(int(p.PixelX(2.5)), row), c);
  EXPECT_EQ(shown.At(int(p.PixelX(3.0)), row), c);
}

// A series without lines (dlmfd chart --points) is a scatter plot: a marker at every point and no
// segment between them.
TEST(LineChart, PointsOnlySeriesHasMarkersAndNoLines) {
  LineChart chart(Options());
  ChartSeries scatter{"scatter", {0.0, 1.0, 2.0}, {0.0, 0.0, 0.0}, true};
  scatter.lines = false;
  chart.AddSeries(scatter);
  chart.AddSeries({"ref", {0.0, 2.0}, {1.0, 1.0}, false});
  const ChartPicture p = chart.Draw();
  const RgbImage shown = p.image.Rasterise();
  const Rgb c = SeriesColour(0);
  const int row = int(p.PixelY(0.0));
  for (const double x : {0.0, 1.0, 2.0}) EXPECT_EQ(shown.At(int(p.PixelX(x)), row), c) << x;
  EXPECT_NE(shown.At(int(p.PixelX(0.5)), row), c);
  EXPECT_NE(shown.At(int(p.PixelX(1.5)), row), c);
}

TEST(LineChart, LogAxisSkipsNonPositiveValues) {
  LineChart chart(Options(AxisScale::kLog10, AxisScale::kLog10));
  // Work-precision style: error against cost; the 0 and the negative cost are skipped.
  chart.AddSeries({"wave", {1e1, 1e2, 0.0, 1e3, 1e4}, {1e-1, 1e-2, 1e-3, -1.0, 1e-4}, true});
  const ChartPicture p = chart.Draw();
  const RgbImage shown = p.image.Rasterise();
  EXPECT_GT(p.x_lo, 0.0);
  EXPECT_NEAR(std::log10(p.x_lo), 1.0 - 3.0 * kPadding, 1e-12);
  EXPECT_NEAR(std::log10(p.y_hi), -1.0 + 3.0 * kPadding, 1e-12);
  EXPECT_TRUE(std::isnan(p.PixelX(0.0)));
  EXPECT_TRUE(std::isnan(p.PixelY(-1.0)));
  ExpectValues(p.x_ticks, {1e1, 1e2, 1e3, 1e4});
  const Rgb c = SeriesColour(0);
  // Joined from 10 to 100; the gap spans (100, 1e4) where only the point 1e4 is drawn.
  EXPECT_TRUE(NearColour(shown, p.PixelX(std::sqrt(1e3)), p.PixelY(std::sqrt(1e-3)), c));
  EXPECT_FALSE(NearColour(shown, p.PixelX(1e3), p.PixelY(1e-3), c));
  EXPECT_EQ(shown.At(int(p.PixelX(1e4)), int(p.PixelY(1e-4))), c);
}

TEST(LineChart, ConstantSeriesGetsAFiniteRange) {
  LineChart chart(Options());
  chart.AddSeries({"still", {0.0, 1.0, 2.0}, {0.0, 0.0, 0.0}, false});
  const ChartPicture p = chart.Draw();
  const RgbImage shown = p.image.Rasterise();
  EXPECT_LT(p.y_lo, 0.0);
  EXPECT_GT(p.y_hi, 0.0);
  EXPECT_EQ(shown.At(int(p.PixelX(1.0)), int(p.PixelY(0.0))), SeriesColour(0));
}

TEST(LineChart, EmptyInputIsAClearError) {
  LineChart none(Options());
  EXPECT_THROW(none.Draw(), InvalidParameter);
  LineChart mismatched(Options());
  EXPECT_THROW(mismatched.AddSeries({"bad", {0.0, 1.0}, {0.0}, false}), InvalidParameter);
  LineChart unusable(Options(AxisScale::kLinear, AxisScale::kLog10));
  unusable.AddSeries({"nothing", {0.0, 1.0}, {0.0, -2.0}, false});
  unusable.AddSeries({"nan", {kNan}, {1.0}, false});
  try {
    unusable.Draw();
    FAIL() << "no usable point must throw";
  } catch (const InvalidParameter& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("no usable point"));
  }
  LineChart tiny([] {
    LineChartOptions o = Options();
    o.width = 40;
    return o;
  }());
  tiny.AddSeries({"a", {0.0, 1.0}, {0.0, 1.0}, false});
  EXPECT_THROW(tiny.Draw(), InvalidParameter);
}

TEST(LineChart, EqualScaleGivesTheSameUnitsPerPixelOnBothAxes) {
  LineChartOptions o = Options();
  o.equal_scale = true;
  LineChart chart(o);
  // A trajectory 0.2 wide and 2 high: without equal scales it would fill the panel's width.
  chart.AddSeries({"path", {0.9, 1.1, 1.0}, {0.0, 1.0, 2.0}, false});
  const ChartPicture p = chart.Draw();
  const double x_per_pixel = (p.x_hi - p.x_lo) / (p.panel_width - 1);
  const double y_per_pixel = (p.y_hi - p.y_lo) / (p.panel_height - 1);
  EXPECT_NEAR(x_per_pixel, y_per_pixel, 1e-12 * y_per_pixel);
  // The y range (the longer one) is the data's, padded; x is widened about its centre.
  EXPECT_DOUBLE_EQ(p.y_lo, -2.0 * kPadding);
  EXPECT_NEAR(0.5 * (p.x_lo + p.x_hi), 1.0, 1e-12);
  LineChartOptions log = Options(AxisScale::kLog10);
  log.equal_scale = true;
  LineChart bad(log);
  bad.AddSeries({"a", {1.0, 2.0}, {1.0, 2.0}, false});
  EXPECT_THROW(bad.Draw(), InvalidParameter);
}

TEST(LineChart, ThirtyTwoSeriesHaveDistinctStylesAndALegendTitle) {
  // 32 series (a sweep of 32 points): colour x dash x marker styles never repeat.
  std::set<std::tuple<int, int, int, int>> styles;
  for (std::size_t n = 0; n < 32; ++n) {
    const Rgb c = SeriesColour(n);
    const Dash dash = SeriesDash(n);
    styles.insert({c.r << 16 | c.g << 8 | c.b, int(dash.size()),
                   dash.empty() ? 0 : int(10 * dash[0]), SeriesMarker(n)});
  }
  EXPECT_EQ(styles.size(), 32u);
  EXPECT_TRUE(SeriesDash(0).empty());
  EXPECT_FALSE(SeriesDash(kPaletteSize).empty());
  EXPECT_EQ(SeriesMarker(0), 0);
  EXPECT_GT(SeriesMarker(kPaletteSize * kDashCount), 0);

  LineChartOptions o = Options();
  o.width = 900;
  o.legend_title = "fluid.relaxation_time";
  LineChart chart(o);
  for (int n = 0; n < 32; ++n) {
    chart.AddSeries({std::to_string(0.1 * n), {0.0, 1.0}, {double(n), double(n) + 1.0}, false});
  }
  const ChartPicture p = chart.Draw();
  const RgbImage shown = p.image.Rasterise();
  // Every legend entry is drawn inside the image: the 32nd series' colour (the 4th of the
  // palette) appears right of the panel, and dark legend text is there.
  int dark = 0;
  for (int y = 0; y < shown.height; ++y) {
    for (int x = p.panel_left + p.panel_width + 2; x < shown.width; ++x) {
      const Rgb c = shown.At(x, y);
      dark += c.r < 60 && c.g < 60 && c.b < 60;
    }
  }
  EXPECT_GT(dark, 200);
}

TEST(LineChart, SaveWritesTheFormatOfTheExtension) {
  LineChart chart(Options());
  chart.AddSeries({"a", {0.0, 1.0}, {0.0, 1.0}, false});
  const std::string stem = dlmfd::testing::ScratchPath("line_chart_save");
  const ChartPicture png = chart.Save(stem + ".png");
  const RgbImage back = ReadPng(stem + ".png");
  EXPECT_EQ(back.width, 600);
  EXPECT_EQ(back.height, 400);
  EXPECT_EQ(back.rgb, png.image.Rasterise().rgb);
  chart.Save(stem + ".svg");
  std::ifstream svg(stem + ".svg");
  std::stringstream text;
  text << svg.rdbuf();
  EXPECT_NE(text.str().find("width=\"600pt\" height=\"400pt\""), std::string::npos);
  EXPECT_THROW(chart.Save(stem + ".bmp"), InvalidParameter);
  std::remove((stem + ".png").c_str());
  std::remove((stem + ".svg").c_str());
}

TEST(LineChart, PaletteIsDistinctAndCycles) {
  for (std::size_t i = 0; i < kPaletteSize; ++i) {
    EXPECT_NE(SeriesColour(i), kWhite);
    for (std::size_t j = i + 1; j < kPaletteSize; ++j)
      EXPECT_NE(SeriesColour(i), SeriesColour(j)) << i << j;
  }
  EXPECT_EQ(SeriesColour(kPaletteSize + 2), SeriesColour(2));
}

}  // namespace
}  // namespace dlmfd
