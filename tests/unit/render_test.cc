// Pictures of node fields (viz/): the PNG read back with libpng has the laid-out size, the
// pixels carry the P1 value of the field through viridis exactly, particles are drawn where they
// are, and degenerate fields (constant, NaN) give finite scales instead of dividing by zero.
#include <png.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dlmfd/core/errors.h"
#include "dlmfd/io/field_snapshot.h"
#include "dlmfd/io/particle_history.h"
#include "dlmfd/viz/bitmap_font.h"
#include "dlmfd/viz/colour_map.h"
#include "dlmfd/viz/field_picture.h"
#include "dlmfd/viz/png_file.h"
#include "dlmfd/viz/results_frame.h"

namespace dlmfd {
namespace {

struct DecodedPng {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
  Rgb At(int x, int y) const {
    const std::size_t k = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
    return Rgb{rgb[k], rgb[k + 1], rgb[k + 2]};
  }
};

// Decodes with libpng's simplified API, independent of the writer under test.
DecodedPng ReadPng(const std::string& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  EXPECT_NE(png_image_begin_read_from_file(&image, path.c_str()), 0) << image.message;
  image.format = PNG_FORMAT_RGB;
  DecodedPng out;
  out.width = int(image.width);
  out.height = int(image.height);
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  EXPECT_NE(png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr), 0) << image.message;
  return out;
}

std::string TempPng(const std::string& stem) {
  return ::testing::TempDir() + "/" + stem + "_" + std::to_string(::getpid()) + ".png";
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

TEST(RenderTest, PngHasTheLaidOutSizeAndKeepsTheAspectRatio) {
  const FieldPicture picture =
      DrawFieldPicture(LinearField(1.0, 1.0, 0.0), {}, {600, 400, "trA t = 1"});
  EXPECT_LE(picture.image.Width(), 600);
  EXPECT_LE(picture.image.Height(), 400);
  // The panel is floor(2 s) x floor(1 s) for one scale s: the 2:1 aspect to within a pixel.
  EXPECT_NEAR(double(picture.panel_width) / picture.panel_height, 2.0, 2.0 / picture.panel_height);
  // The panel fills the width left by the colour bar (the binding side for a 2:1 domain here).
  EXPECT_GE(picture.panel_width, 600 / 2);
  const std::string path = TempPng("size");
  WritePng(picture.image, path);
  const DecodedPng png = ReadPng(path);
  EXPECT_EQ(png.width, picture.image.Width());
  EXPECT_EQ(png.height, picture.image.Height());
  ASSERT_EQ(png.rgb, picture.image.Bytes());
  std::remove(path.c_str());
}

TEST(RenderTest, PixelsCarryTheLinearFieldThroughViridis) {
  // P1 reproduces a linear field exactly, so each pixel is Viridis((f(centre) - min) / (max -
  // min)).
  const NodeField field = LinearField(2.0, 3.0, -1.0);
  const FieldPicture picture = DrawFieldPicture(field, {}, {500, 300, ""});
  EXPECT_DOUBLE_EQ(picture.value_min, 2.0 - 1.0);
  EXPECT_DOUBLE_EQ(picture.value_max, 2.0 + 6.0);
  const std::string path = TempPng("linear");
  WritePng(picture.image, path);
  const DecodedPng png = ReadPng(path);
  std::remove(path.c_str());
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
  // Colour bar: the top row is the maximum, the bottom row the minimum (inside the frame).
  const int bar_x = picture.bar_left + picture.bar_width / 2;
  EXPECT_EQ(png.At(bar_x, picture.bar_top + 1), Viridis(1.0 - 1.5 / picture.bar_height));
  EXPECT_EQ(png.At(bar_x, picture.bar_top + picture.bar_height - 2),
            Viridis(1.5 / picture.bar_height));
  EXPECT_EQ(png.At(picture.bar_left, picture.bar_top + picture.bar_height / 2), kBlack);
}

TEST(RenderTest, LogColoursMapLog10OfTheValueAndTheBottomColourToNonPositiveValues) {
  // f = 1 + 49.5 x on the 2 x 1 domain (1 at x = 0, 100 at x = 2) is reproduced exactly by P1, so
  // each pixel is Viridis(log10 f(centre) / 2): log10 of the value, not the value, sets the colour.
  NodeField field = LinearField(1.0, 49.5, 0.0);
  PictureOptions options{500, 300, ""};
  options.log_colours = true;
  const FieldPicture picture = DrawFieldPicture(field, {}, options);
  EXPECT_DOUBLE_EQ(picture.value_min, 1.0);
  EXPECT_DOUBLE_EQ(picture.value_max, 100.0);
  for (int px : {0, picture.panel_width / 4, picture.panel_width / 2, picture.panel_width - 1}) {
    const double x = (px + 0.5) / picture.panel_width * 2.0;
    const double t = std::log10(1.0 + 49.5 * x) / 2.0;
    EXPECT_EQ(picture.image.At(picture.panel_left + px, picture.panel_top + 3), Viridis(t))
        << "pixel " << px;
  }
  // A field with zero and negative nodes: the scale is set by the positive ones, and the others
  // take the bottom colour instead of a NaN from log10.
  field = LinearField(-1.0, 1.0, 0.0);  // -1 ... 1 along x
  const FieldPicture clipped = DrawFieldPicture(field, {}, options);
  EXPECT_DOUBLE_EQ(clipped.value_min, 0.125);
  EXPECT_DOUBLE_EQ(clipped.value_max, 1.0);
  EXPECT_EQ(clipped.image.At(clipped.panel_left, clipped.panel_top + 3), Viridis(0.0));
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

TEST(RenderTest, ParticleIsAWhiteDiskWithABlackRimWhereItIs) {
  const NodeField field = LinearField(0.0, 1.0, 0.0);
  const DiskOutline disk{1.25, 0.5, 0.2};
  const FieldPicture picture = DrawFieldPicture(field, {disk}, {800, 500, ""});
  const std::string path = TempPng("disk");
  WritePng(picture.image, path);
  const DecodedPng png = ReadPng(path);
  std::remove(path.c_str());
  const double cx = picture.PixelX(disk.x);
  const double cy = picture.PixelY(disk.y);
  const double r = disk.radius / 2.0 * picture.panel_width;
  ASSERT_GT(r, 20.0);
  EXPECT_EQ(png.At(int(cx), int(cy)), kWhite);
  EXPECT_EQ(png.At(int(cx + 0.5 * r), int(cy)), kWhite);
  // The rim: the pixel whose centre is nearest to radius r on each axis.
  EXPECT_EQ(png.At(int(std::floor(cx + r)), int(cy)), kBlack);
  EXPECT_EQ(png.At(int(std::floor(cx - r)), int(cy)), kBlack);
  EXPECT_EQ(png.At(int(cx), int(std::floor(cy - r))), kBlack);
  EXPECT_EQ(png.At(int(cx), int(std::floor(cy + r))), kBlack);
  // Outside the rim the field shows again.
  const int outside = int(std::floor(cx + r + 4));
  const double x = (outside - picture.panel_left + 0.5) / picture.panel_width * 2.0;
  EXPECT_EQ(png.At(outside, int(cy)), Viridis(x / 2.0));
}

TEST(RenderTest, ConstantFieldTakesTheMiddleColourWithoutDividingByZero) {
  NodeField field = LinearField(2.0, 0.0, 0.0);
  const FieldPicture picture = DrawFieldPicture(field, {}, {400, 300, "constant"});
  EXPECT_EQ(picture.value_min, 2.0);
  EXPECT_EQ(picture.value_max, 2.0);
  for (int py = 0; py < picture.panel_height; py += 7) {
    for (int px = 0; px < picture.panel_width; px += 7) {
      ASSERT_EQ(picture.image.At(picture.panel_left + px, picture.panel_top + py), Viridis(0.5));
    }
  }
}

TEST(RenderTest, NanNodesAreGreyAndLeaveTheScaleFinite) {
  NodeField field = LinearField(0.0, 1.0, 0.0);
  field.values[field.grid.Index(8, 4)] = std::numeric_limits<double>::quiet_NaN();
  field.values[field.grid.Index(0, 0)] = std::numeric_limits<double>::infinity();
  const FieldPicture picture = DrawFieldPicture(field, {}, {400, 300, ""});
  EXPECT_TRUE(std::isfinite(picture.value_min));
  EXPECT_TRUE(std::isfinite(picture.value_max));
  EXPECT_DOUBLE_EQ(picture.value_max, 2.0);
  EXPECT_EQ(picture.image.At(int(picture.PixelX(1.0)), int(picture.PixelY(0.5))), kNanColour);
  // Far from the bad nodes the field is drawn as usual.
  const int px = picture.panel_width * 7 / 8;
  const double x = (px + 0.5) / picture.panel_width * 2.0;
  EXPECT_EQ(picture.image.At(picture.panel_left + px, picture.panel_top + picture.panel_height / 2),
            Viridis(x / 2.0));

  NodeField all_nan = field;
  all_nan.values.assign(all_nan.values.size(), std::numeric_limits<double>::quiet_NaN());
  const FieldPicture grey = DrawFieldPicture(all_nan, {}, {400, 300, ""});
  EXPECT_EQ(grey.value_min, 0.0);
  EXPECT_EQ(grey.value_max, 0.0);
}

TEST(RenderTest, RejectsMismatchedValuesAndSizesWithoutRoom) {
  NodeField field = LinearField(0.0, 1.0, 0.0);
  EXPECT_THROW(DrawFieldPicture(field, {}, {40, 25, ""}), InvalidParameter);
  field.values.pop_back();
  EXPECT_THROW(DrawFieldPicture(field, {}, {400, 300, ""}), InvalidParameter);
}

TEST(RenderTest, FontHasEveryLabelCharacterAndMarksMissingOnes) {
  const Glyph& missing = GlyphFor('\x01');
  for (char c : std::string("0123456789.-+e trAspedtimx=:")) EXPECT_NE(GlyphFor(c), missing) << c;
  EXPECT_EQ(GlyphFor('~'), missing);
  EXPECT_EQ(TextWidth("1.5e-03"), 7 * kGlyphAdvance - 1);
  EXPECT_EQ(TextWidth(""), 0);
  EXPECT_EQ(FormatLabel(0.000123456), "0.0001235");
}

// A results directory written by the io writers: two snapshots (Oldroyd-B: trA present) and a
// particle history whose records include the later snapshot's step.
class ResultsFrameTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "/render_results_" + std::to_string(::getpid());
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
      history->Append(state);
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
}

TEST_F(ResultsFrameTest, ChosenSnapshotSpeedAndErrors) {
  const ResultsFrame frame = LoadResultsFrame(dir_, 0, "speed");
  EXPECT_EQ(frame.step, 0);
  EXPECT_EQ(frame.field.quantity, "speed");
  EXPECT_DOUBLE_EQ(frame.field.values[3], 5.0);
  EXPECT_DOUBLE_EQ(frame.disks[0].x, 0.5);
  EXPECT_THROW(LoadResultsFrame(dir_, 5),
               InvalidParameter);  // particles at step 5, no field snapshot
  EXPECT_THROW(LoadResultsFrame(dir_, -1, "pressure"), InvalidParameter);
  EXPECT_THROW(LoadResultsFrame(dir_ + "/nothing"), InvalidParameter);
  // And the frame draws: the disk at x = 1.5 is white at its centre.
  const FieldPicture picture =
      DrawFieldPicture(LoadResultsFrame(dir_).field, LoadResultsFrame(dir_).disks, {400, 300, ""});
  EXPECT_EQ(picture.image.At(int(picture.PixelX(1.5)), int(picture.PixelY(0.5))), kWhite);
}

}  // namespace
}  // namespace dlmfd
