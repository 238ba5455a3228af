// Pictures a paper can use, end to end (issue 35): the real dlmfd-solve runs a disk moved at a
// prescribed velocity (so its centre at any time is known exactly: y = 1.6 - 10 t) with field and
// particle output rates that do not line up (fields every 0.06, particles every 0.04), then
//  - the snapshot at t = 0.06 holds the disk at y = 1.0, the frame drawn from it shows the disk
//    there (white at the centre's pixel) and not at the particle records' 1.2 or 0.8, and
//    `dlmfd plot` draws it with no warning;
//  - `dlmfd plot --size 3,4 --dpi 200` is 600 x 800 pixels, its PDF a 3 x 4 inch page;
//    --no-caption and --caption "" draw no caption (the panel moves up);
//  - captions state the run's settings at sensible precision ("h = 1/16", not 0.0625000...);
//  - `dlmfd chart` of two runs that differ in many keys draws (the legend goes below), and the
//    entries stay distinct; reference data from a CSV go over the runs.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../support/build_paths.h"
#include "dlmfd/io/field_snapshot.h"
#include "dlmfd/viz/canvas.h"
#include "dlmfd/viz/field_picture.h"
#include "dlmfd/viz/results_frame.h"
#include "support/run_process.h"

namespace dlmfd {
namespace {

namespace fs = std::filesystem;
using test::Execute;
using test::Outcome;
using ::testing::HasSubstr;
using testing::kClient;
using testing::kSolver;

// The disk is held at velocity (0, -10): centre y = 1.6 - 10 t exactly (the corrector's
// trapezoidal rule is exact for a constant velocity).
std::string PrescribedScene(const std::string& extra) {
  return "title = \"prescribed disk, mesh 1/96\"\n"
         "[domain]\nsize = [1.0, 2.0]\nh = 0.0625\n"
         "[fluid]\ndensity = 1.0\nviscosity = 0.1\nrelaxation_time = 0.0\n"
         "gravity = [0.0, 0.0]\n"
         "[time]\ndt = 0.002\nend = 0.08\n"
         "[particle_mesh]\nh = 0.08571428571428572\n"
         "[[particles]]\ncenter = [0.5, 1.6]\ndiameter = 0.25\ndensity = 1.1\n"
         "velocity = [0.0, -10.0]\nmotion = \"prescribed\"\n"
         "[output]\nfields_every = 0.06\nparticles_every = 0.04\ncheckpoint_every = 0.0\n" +
         extra;
}

class PublicationTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fs::path(::testing::TempDir()) / ("dlmfd_publication_e2e_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    std::ofstream(root_ / "disk.toml") << PrescribedScene("");
    const Outcome solve = Execute({kSolver, (root_ / "disk.toml").string(), "--out",
                                   (root_ / "disk").string(), "--quiet", "--threads", "1"},
                                  root_);
    ASSERT_EQ(solve.code, 0) << solve.err;
    const Outcome other = Execute({kSolver,
                                   (root_ / "disk.toml").string(),
                                   "--out",
                                   (root_ / "other").string(),
                                   "--quiet",
                                   "--threads",
                                   "1",
                                   "--set",
                                   "fluid.viscosity=0.2",
                                   "--set",
                                   "fluid.density=1.5",
                                   "--set",
                                   "particles.0.density=1.2",
                                   "--set",
                                   "collisions.range=2",
                                   "--set",
                                   "collisions.wall_stiffness=2e-5",
                                   "--set",
                                   "collisions.particle_stiffness=3e-5",
                                   "--set",
                                   "particles.0.angular_velocity=1",
                                   "--set",
                                   "output.particles_every=0.02"},
                                  root_);
    ASSERT_EQ(other.code, 0) << other.err;
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  static fs::path root_;
};
fs::path PublicationTest::root_;

TEST_F(PublicationTest, TheDiskIsDrawnWhereItWasAtTheSnapshotsTime) {
  const std::string dir = (root_ / "disk").string();
  EXPECT_EQ(SnapshotSteps(dir), (std::vector<long>{0, 30}));
  const ResultsFrame frame = LoadResultsFrame(dir, 30, "speed");
  EXPECT_TRUE(frame.particles_note.empty()) << frame.particles_note;
  ASSERT_EQ(frame.disks.size(), 1u);
  EXPECT_NEAR(frame.disks[0].y, 1.6 - 10.0 * 0.06, 1e-9);
  EXPECT_DOUBLE_EQ(frame.particles_time, frame.time);
  PictureOptions options;
  options.max_width = 500;
  options.max_height = 900;
  const FieldPicture picture = DrawFieldPicture(frame.field, frame.disks, options);
  const RgbImage pixels = picture.image.Rasterise();
  // Left of the centre: the rotation mark (angle 0) points right.
  const int x = int(picture.PixelX(0.5) - 0.5 * 0.125 / picture.grid.Width() * picture.panel_width);
  EXPECT_EQ(pixels.At(x, int(picture.PixelY(1.0))), kWhite);  // the disk at t = 0.06
  EXPECT_NE(pixels.At(x, int(picture.PixelY(1.2))), kWhite);  // not the record at t = 0.04
  EXPECT_NE(pixels.At(x, int(picture.PixelY(0.8))), kWhite);  // nor the one at t = 0.08
  const Outcome plot = Execute({kClient, "plot", dir, "--snapshot", "30", "--quantity", "speed",
                                "--out", (root_ / "disk.png").string()},
                               root_);
  EXPECT_EQ(plot.code, 0) << plot.err;
  EXPECT_EQ(plot.err, "");
}

TEST_F(PublicationTest, SizeInInchesAtAResolutionAndNoCaption) {
  const std::string dir = (root_ / "disk").string();
  const std::string png = (root_ / "sized.png").string();
  Outcome plot =
      Execute({kClient, "plot", dir, "--size", "3,4", "--dpi", "200", "--out", png}, root_);
  ASSERT_EQ(plot.code, 0) << plot.err;
  const RgbImage sized = ReadPng(png);
  EXPECT_LE(sized.width, 600);
  EXPECT_LE(sized.height, 800);
  EXPECT_TRUE(sized.width == 600 || sized.height == 800) << sized.width << "x" << sized.height;
  const std::string pdf = (root_ / "sized.pdf").string();
  plot = Execute({kClient, "plot", dir, "--size", "3,4", "--dpi", "200", "--out", pdf}, root_);
  ASSERT_EQ(plot.code, 0) << plot.err;
  std::ifstream in(pdf, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The page is the picture's pixels at 200 dpi: at most 3 x 4 inches = 216 x 288 points.
  std::smatch box;
  ASSERT_TRUE(
      std::regex_search(bytes, box, std::regex(R"(/MediaBox \[ ?0 0 ([0-9.]+) ([0-9.]+) ?\])")));
  EXPECT_NEAR(std::stod(box[1]), sized.width * 72.0 / 200.0, 0.01);
  EXPECT_NEAR(std::stod(box[2]), sized.height * 72.0 / 200.0, 0.01);
  // No caption: the picture is shorter by the caption's lines (the panel keeps its aspect).
  const std::string with = (root_ / "with.png").string();
  const std::string without = (root_ / "without.png").string();
  const std::string empty = (root_ / "empty.png").string();
  ASSERT_EQ(
      Execute({kClient, "plot", dir, "--width", "500", "--height", "900", "--out", with}, root_)
          .code,
      0);
  ASSERT_EQ(Execute({kClient, "plot", dir, "--width", "500", "--height", "900", "--no-caption",
                     "--out", without},
                    root_)
                .code,
            0);
  ASSERT_EQ(Execute({kClient, "plot", dir, "--width", "500", "--height", "900", "--caption", "",
                     "--out", empty},
                    root_)
                .code,
            0);
  const RgbImage a = ReadPng(with), b = ReadPng(without), c = ReadPng(empty);
  EXPECT_EQ(b.width, c.width);
  EXPECT_EQ(b.height, c.height);
  // The top rows of a picture without caption are white down to the panel.
  for (int x = 0; x < b.width; ++x) EXPECT_EQ(b.At(x, 3), kWhite) << x;
  EXPECT_LT(b.height, a.height);  // no room taken by the caption's lines
}

TEST_F(PublicationTest, CaptionsStateTheRunsSettings) {
  // The PDF's text (cairo embeds it with its Unicode map), read by poppler's pdftotext
  // (poppler-utils, scripts/setup.sh): the run's real mesh, not the title's "1/96", at sensible
  // precision.
  ASSERT_TRUE(fs::exists("/usr/bin/pdftotext")) << "poppler-utils is not installed";
  const std::string pdf = (root_ / "caption.pdf").string();
  ASSERT_EQ(Execute({kClient, "plot", (root_ / "disk").string(), "--out", pdf}, root_).code, 0);
  const Outcome text = Execute({"/usr/bin/pdftotext", pdf, "-"}, root_);
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("h = 1/16"));
  EXPECT_THAT(text.out, HasSubstr("dt = 0.002"));
  EXPECT_THAT(text.out, HasSubstr("t = 0.06"));
  EXPECT_EQ(text.out.find("0.0625"), std::string::npos);
  const std::string none = (root_ / "none.pdf").string();
  ASSERT_EQ(
      Execute({kClient, "plot", (root_ / "disk").string(), "--no-caption", "--out", none}, root_)
          .code,
      0);
  EXPECT_EQ(Execute({"/usr/bin/pdftotext", none, "-"}, root_).out.find("step"), std::string::npos);
}

TEST_F(PublicationTest, ChartsOfRunsDifferingInManyKeysAndReferenceData) {
  const std::string png = (root_ / "chart.png").string();
  const Outcome chart = Execute({kClient, "chart", (root_ / "disk").string(),
                                 (root_ / "other").string(), "--y", "y", "--out", png},
                                root_);
  ASSERT_EQ(chart.code, 0) << chart.err;
  // The legend as text: two entries, different, with every differing key's value.
  std::smatch legend;
  ASSERT_TRUE(std::regex_search(chart.err, legend, std::regex(R"(legend \(([^)]*)\): (.*))")));
  const std::string entries = legend[2];
  const std::size_t split = entries.find("; ");
  ASSERT_NE(split, std::string::npos);
  EXPECT_NE(entries.substr(0, split), entries.substr(split + 2));
  EXPECT_EQ(ReadPng(png).width, 1000);
  const fs::path csv = root_ / "reference.csv";
  std::ofstream(csv) << "t,y\n0,1.6\n0.04,1.2\n0.08,0.8\n";
  const Outcome overlay =
      Execute({kClient, "chart", (root_ / "disk").string(), "--y", "y", "--csv", csv.string(),
               "--xcol", "t", "--ycol", "y", "--csv-label", "exact", "--xlim", "0,0.08", "--units",
               "cgs", "--out", (root_ / "overlay.svg").string()},
              root_);
  ASSERT_EQ(overlay.code, 0) << overlay.err;
  EXPECT_THAT(overlay.err, HasSubstr("; exact"));
}

}  // namespace
}  // namespace dlmfd
