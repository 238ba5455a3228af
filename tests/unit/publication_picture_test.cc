// The publication controls of the pictures (issue 35): colour ranges from percentiles with the
// colour bar's end triangles, the round arrow key, streamlines (against exact lines of uniform
// flow and of a solid-body rotation), text sized by the caller, and the chart's legend below the
// panel when it is too wide for its right, with entries never cut.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "dlmfd/core/errors.h"
#include "dlmfd/viz/field_picture.h"
#include "dlmfd/viz/line_chart.h"
#include "dlmfd/viz/streamlines.h"

namespace dlmfd {
namespace {

NodeField Field(const Grid& g, double (*value)(double, double), const std::string& quantity) {
  NodeField f{g, std::vector<double>(g.NodeCount()), quantity};
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) f.values[g.Index(i, j)] = value(g.X(i), g.Y(j));
  }
  return f;
}

TEST(PercentileRange, ASpikeNoLongerSetsTheScaleOfASignedField) {
  const Grid g{40, 40, 0.025, 0.0, 0.0};
  // Values spread evenly over [-1, 1] (a smooth saddle) and one spike of 100.
  NodeField f = Field(
      g, [](double x, double y) { return (2 * x - 1) * (2 * y - 1); }, "vorticity");
  f.values[g.Index(20, 20)] = 100.0;
  PictureOptions options;
  options.max_width = 400;
  options.max_height = 400;
  options.diverging = true;
  const FieldPicture all = DrawFieldPicture(f, {}, options);
  EXPECT_DOUBLE_EQ(all.value_max, 100.0);
  EXPECT_FALSE(all.clipped_high);
  options.percentile = 99.0;
  const FieldPicture robust = DrawFieldPicture(f, {}, options);
  EXPECT_LE(robust.value_max, 1.0);  // the 99th percentile of |value| of values in [-1, 1]
  EXPECT_GT(robust.value_max, 0.8);
  EXPECT_DOUBLE_EQ(robust.value_min, -robust.value_max);
  EXPECT_TRUE(robust.clipped_high);  // the spike (and the 1 % largest |values|): the top triangle
  EXPECT_TRUE(robust.clipped_low);   // the saddle's corners at -1 lie beyond -m too
  // The extremes of a sequential field are not "clipped".
  options.diverging = false;
  options.percentile = 100.0;
  const FieldPicture plain = DrawFieldPicture(f, {}, options);
  EXPECT_FALSE(plain.clipped_low);
  EXPECT_FALSE(plain.clipped_high);
}

TEST(ArrowKey, ShowsTheLargestRoundSpeedNotAboveTheLongestArrow) {
  const Grid g{8, 8, 0.125, 0.0, 0.0};
  const NodeField u = Field(
      g, [](double, double) { return 0.37; }, "u");
  const NodeField v = Field(
      g, [](double, double) { return 0.0; }, "v");
  PictureOptions options;
  options.max_width = 400;
  options.max_height = 400;
  options.arrows = 6;
  const NodeVelocity velocity{u, v};
  const FieldPicture p = DrawFieldPicture(u, {}, options, &velocity);
  EXPECT_DOUBLE_EQ(p.arrow_speed, 0.37);
  EXPECT_DOUBLE_EQ(p.key_speed, 0.2);
}

TEST(FontSize, TheCallersSizeGrowsTheTextAndTheMargins) {
  const Grid g{8, 8, 0.125, 0.0, 0.0};
  const NodeField f = Field(
      g, [](double x, double) { return x; }, "trA");
  PictureOptions options;
  options.max_width = 3000;
  options.max_height = 3000;
  const FieldPicture large = DrawFieldPicture(f, {}, options);
  options.font_size = 12.0;
  const FieldPicture small_text = DrawFieldPicture(f, {}, options);
  // 3000 / 55 = 54.5 px text: the axis labels take more room left of the panel.
  EXPECT_GT(large.panel_left, 2 * small_text.panel_left);
}

TEST(Streamlines, UniformFlowGivesStraightEvenlySpacedLines) {
  const Grid g{20, 10, 0.1, 0.0, 0.0};
  const NodeVelocity velocity{Field(
                                  g, [](double, double) { return 2.0; }, "u"),
                              Field(
                                  g, [](double, double) { return 0.0; }, "v")};
  const std::vector<std::vector<double>> lines = Streamlines(velocity, 10);
  ASSERT_FALSE(lines.empty());
  std::vector<double> heights;
  for (const std::vector<double>& line : lines) {
    for (std::size_t k = 1; k < line.size(); k += 2) EXPECT_NEAR(line[k], line[1], 1e-12);
    for (std::size_t k = 2; k < line.size(); k += 2) EXPECT_GT(line[k], line[k - 2]);  // downstream
    heights.push_back(line[1]);
  }
  // One line per row of seeds (spacing d = 0.2 over a height of 1): 5 lines, d apart.
  EXPECT_EQ(lines.size(), 5u);
  for (std::size_t k = 1; k < heights.size(); ++k)
    EXPECT_NEAR(heights[k] - heights[k - 1], 0.2, 1e-12);
}

TEST(Streamlines, ASolidBodyRotationGivesCircles) {
  // u = -y, v = x about (0, 0) is P1-exact; the midpoint rule with steps ds = d / 10 moves a
  // point on a circle of radius R outwards by R theta^4 / 8 a step (theta = ds / R), so over one
  // turn (2 pi / theta steps) by R pi theta^3 / 4: at most 8e-4 R for R >= d (theta <= 0.1).
  const Grid g{40, 40, 0.05, -1.0, -1.0};
  const NodeVelocity velocity{Field(
                                  g, [](double, double y) { return -y; }, "u"),
                              Field(
                                  g, [](double x, double) { return x; }, "v")};
  const double d = g.Width() / 8;
  const std::vector<std::vector<double>> lines = Streamlines(velocity, 8);
  ASSERT_FALSE(lines.empty());
  int checked = 0;
  for (const std::vector<double>& line : lines) {
    const double r0 = std::hypot(line[0], line[1]);
    if (r0 < d) continue;
    bool inside = true;
    double worst = 0.0;
    for (std::size_t k = 0; k + 1 < line.size(); k += 2) {
      const double r = std::hypot(line[k], line[k + 1]);
      inside = inside && r < 0.99;
      worst = std::max(worst, std::abs(r - r0));
    }
    if (!inside) continue;  // a line that reaches the square's sides is cut there
    EXPECT_LE(worst, 8e-4 * r0) << "line from radius " << r0;
    ++checked;
  }
  EXPECT_GE(checked, 1);
}

TEST(ChartLegend, GoesBelowWhenTooWideAndKeepsEveryEntryWhole) {
  LineChartOptions options;
  options.width = 1000;
  options.height = 700;
  options.legend_title =
      "collisions.particle_stiffness, collisions.range, collisions.wall_stiffness, "
      "fluid.density, fluid.viscosity, output.particles_every, particles.0.angular_velocity";
  LineChart chart(options);
  for (const char* name :
       {"2e-05, 1.5, 1e-05, 1, 0.1, 0.04, 0, 1.1", "3e-05, 2, 2e-05, 1.5, 0.2, 0.02, 1, 1.2"}) {
    chart.AddSeries({name, {0.0, 1.0}, {0.0, 1.0}});
  }
  const ChartPicture picture = chart.Draw();
  EXPECT_TRUE(picture.legend_below);
  EXPECT_GT(picture.panel_width, 700);  // the panel keeps the width
  EXPECT_EQ(chart.LegendText(),
            "2e-05, 1.5, 1e-05, 1, 0.1, 0.04, 0, 1.1; 3e-05, 2, 2e-05, 1.5, 0.2, 0.02, 1, 1.2");
}

TEST(ChartAxes, FixedLimitsAreKeptAsGiven) {
  LineChartOptions options;
  options.x_axis.fixed = true;
  options.x_axis.lo = -1.0;
  options.x_axis.hi = 3.0;
  LineChart chart(options);
  chart.AddSeries({"a", {0.0, 1.0}, {0.0, 1.0}});
  const ChartPicture picture = chart.Draw();
  EXPECT_DOUBLE_EQ(picture.x_lo, -1.0);
  EXPECT_DOUBLE_EQ(picture.x_hi, 3.0);
  options.x_axis.lo = 4.0;  // LO > HI
  LineChart inverted(options);
  inverted.AddSeries({"a", {0.0, 1.0}, {0.0, 1.0}});
  EXPECT_THROW(inverted.Draw(), InvalidParameter);
}

}  // namespace
}  // namespace dlmfd
