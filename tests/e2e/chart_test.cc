// `dlmfd chart` end to end: the real dlmfd-solve runs two tiny particle scenes (a pair and a single
// disk settling in a 16 x 32 box for 10 steps), then the real dlmfd binary charts them: velocities
// of several runs overlaid, a trajectory, the angle, the gap, a CSV work-precision chart; the PNGs
// read back with cairo at the asked size and carry the series colours; series of runs that differ
// in a parameter are named by it, the key in the legend's title; SVG and PDF by the extension; bad
// quantities, `gap` of one
// particle, unknown particles and CSV columns are usage errors (exit 2) that say what is allowed.
// No daemon is involved.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../support/build_paths.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/viz/canvas.h"
#include "dlmfd/viz/line_chart.h"
#include "support/run_process.h"

namespace dlmfd {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using testing::kClient;
using testing::kSolver;

// Disks of diameter 0.25 settling in a closed Newtonian box; `disks` holds the centres' lines.
std::string SettlingScene(const std::string& disks) {
  return "title = \"chart e2e\"\n"
         "[domain]\nsize = [1.0, 2.0]\nh = 0.0625\n"
         "[fluid]\ndensity = 1.0\nviscosity = 0.1\nrelaxation_time = 0.0\n"
         "gravity = [0.0, -981.0]\n"
         "[time]\ndt = 0.001\nend = 0.01\n"
         "[particle_mesh]\nh = 0.08571428571428572\n" +
         disks + "[output]\nfields_every = 0.0\nparticles_every = 0.002\ncheckpoint_every = 0.0\n";
}

std::string Disk(double x, double y) {
  std::ostringstream text;
  text << "[[particles]]\ncenter = [" << x << ", " << y << "]\ndiameter = 0.25\ndensity = 1.1\n";
  return text.str();
}

using test::Execute;
using test::Outcome;

struct Picture {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
  std::set<std::uint32_t> Colours() const {
    std::set<std::uint32_t> colours;
    for (std::size_t k = 0; k + 2 < rgb.size(); k += 3)
      colours.insert(rgb[k] << 16 | rgb[k + 1] << 8 | rgb[k + 2]);
    return colours;
  }
};

std::uint32_t Packed(Rgb c) { return std::uint32_t(c.r) << 16 | std::uint32_t(c.g) << 8 | c.b; }

// Decodes with cairo; width 0 when the file is not a readable PNG.
Picture ReadPicture(const fs::path& path) {
  Picture picture;
  try {
    const RgbImage image = ReadPng(path.string());
    picture.width = image.width;
    picture.height = image.height;
    picture.rgb = image.rgb;
  } catch (const Error&) {}
  return picture;
}

class ChartTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(fs::exists(kClient)) << kClient << " is not built";
    ASSERT_TRUE(fs::exists(kSolver)) << kSolver << " is not built";
    root_ = fs::path(::testing::TempDir()) / ("dlmfd_chart_e2e_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    std::ofstream(root_ / "pair.toml") << SettlingScene(Disk(0.5, 1.4) + Disk(0.5, 0.9));
    std::ofstream(root_ / "single.toml") << SettlingScene(Disk(0.5, 1.4));
    std::string heavy = SettlingScene(Disk(0.5, 1.4));
    heavy.replace(heavy.find("density = 1.1"), 13, "density = 1.3");
    std::ofstream(root_ / "heavy.toml") << heavy;
    for (const char* name : {"pair", "single", "heavy"}) {
      const Outcome solve = Execute({kSolver, (root_ / (std::string(name) + ".toml")).string(),
                                     "--out", (root_ / name).string(), "--quiet", "--threads", "1"},
                                    root_);
      ASSERT_EQ(solve.code, 0) << name << ": " << solve.err;
    }
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }

  static Outcome Chart(std::vector<std::string> args) {
    args.insert(args.begin(), {kClient, "chart"});
    return Execute(args, root_);
  }

  static fs::path root_;
};

fs::path ChartTest::root_;

std::string Slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST_F(ChartTest, OverlaysTheVelocityOfSeveralRuns) {
  // Each --label takes one value, so labels may stand before their directories.
  const Outcome run =
      Chart({"--label", "two disks", "pair", "--label", "one disk", "single", "--y", "v", "--title",
             "settling", "--out", "v.png", "--width", "640", "--height", "480"});
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(run.out, "v.png\n");
  const Picture picture = ReadPicture(root_ / "v.png");
  EXPECT_EQ(picture.width, 640);
  EXPECT_EQ(picture.height, 480);
  // Two particles of the pair and the single disk: three series in the first three colours (at
  // least in their legend entries; the pair's two lines may overlap).
  const std::set<std::uint32_t> colours = picture.Colours();
  for (std::size_t n = 0; n < 3; ++n) EXPECT_EQ(colours.count(Packed(SeriesColour(n))), 1u) << n;
  EXPECT_EQ(colours.count(Packed(SeriesColour(3))), 0u);
}

TEST_F(ChartTest, NamesTheSeriesByTheParameterInWhichTheRunsDiffer) {
  const Outcome run = Chart(
      {"single", "heavy", "--y", "v", "--out", "study.svg", "--width", "700", "--height", "500"});
  ASSERT_EQ(run.code, 0) << run.err;
  // The scenes as run differ only in the particle's density: it names the series.
  EXPECT_THAT(run.err, HasSubstr("legend (particles.0.density): 1.1; 1.3"));
  const std::string svg = Slurp(root_ / "study.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("width=\"700pt\" height=\"500pt\""), std::string::npos);
  // --label names them instead; a directory alone keeps its name.
  const Outcome labelled =
      Chart({"--label", "light", "single", "heavy", "--y", "v", "--out", "study.pdf"});
  ASSERT_EQ(labelled.code, 0) << labelled.err;
  EXPECT_THAT(labelled.err, HasSubstr(": light; 1.3"));
  EXPECT_EQ(Slurp(root_ / "study.pdf").rfind("%PDF-", 0), 0u);
  const Outcome alone = Chart({"single", "--y", "v", "--equal", "--x", "x", "--out", "alone.png"});
  ASSERT_EQ(alone.code, 0) << alone.err;
  EXPECT_THAT(alone.err, HasSubstr("legend: single"));
  const Outcome bad = Chart({"single", "--y", "v", "--out", "v.jpg"});
  EXPECT_EQ(bad.code, 2);
  EXPECT_THAT(bad.err, HasSubstr(".png, .svg or .pdf"));
}

TEST_F(ChartTest, DrawsATrajectoryAndTheGapWithDefaultNames) {
  const Outcome trajectory =
      Chart({"pair", "--x", "x", "--y", "y", "--particle", "1", "--markers"});
  ASSERT_EQ(trajectory.code, 0) << trajectory.err;
  EXPECT_EQ(trajectory.out, "chart_y_x.png\n");
  const Picture t = ReadPicture(root_ / "chart_y_x.png");
  EXPECT_EQ(t.width, 1000);
  EXPECT_EQ(t.height, 700);
  EXPECT_EQ(t.Colours().count(Packed(SeriesColour(0))), 1u);
  EXPECT_EQ(t.Colours().count(Packed(SeriesColour(1))), 0u);

  // The orientation theta of /angle (an ellipse's tilt; a disk's rotation since t = 0).
  const Outcome angle = Chart({"pair", "--y", "angle", "--out", "angle.png"});
  ASSERT_EQ(angle.code, 0) << angle.err;
  EXPECT_EQ(ReadPicture(root_ / "angle.png").Colours().count(Packed(SeriesColour(1))), 1u);

  const Outcome gap = Chart({"pair/", "--y", "gap", "--logy", "--out", "gap.png"});
  ASSERT_EQ(gap.code, 0) << gap.err;
  const Picture g = ReadPicture(root_ / "gap.png");
  EXPECT_EQ(g.width, 1000);
  EXPECT_EQ(g.Colours().count(Packed(SeriesColour(0))), 1u);
}

TEST_F(ChartTest, ChartsCsvColumnsGroupedIntoSeries) {
  std::ofstream(root_ / "wp.csv") << "advection,h,ms_per_step,error\n"
                                     "least_squares,0.0625,3.1,2.0e-2\n"
                                     "least_squares,0.03125,12.5,5.1e-3\n"
                                     "wave,0.0625,1.2,3.0e-2\n"
                                     "wave,0.03125,4.4,\n"
                                     "\"wave\",0.015625,17.0,2.1e-3\n";
  const Outcome run =
      Chart({"--csv", "wp.csv", "--xcol", "ms_per_step", "--ycol", "error", "--group", "advection",
             "--logx", "--logy", "--markers", "--out", "wp.png"});
  ASSERT_EQ(run.code, 0) << run.err;
  const Picture picture = ReadPicture(root_ / "wp.png");
  EXPECT_EQ(picture.width, 1000);
  EXPECT_EQ(picture.Colours().count(Packed(SeriesColour(1))), 1u);
  EXPECT_EQ(picture.Colours().count(Packed(SeriesColour(2))), 0u);

  const Outcome bad_column = Chart({"--csv", "wp.csv", "--xcol", "cost", "--ycol", "error"});
  EXPECT_EQ(bad_column.code, 2);
  EXPECT_THAT(bad_column.err, HasSubstr("advection, h, ms_per_step, error"));

  std::ofstream(root_ / "bad.csv") << "a,b\n1,2\n3,oops\n";
  const Outcome bad_cell = Chart({"--csv", "bad.csv", "--xcol", "a", "--ycol", "b"});
  EXPECT_EQ(bad_cell.code, 2);
  EXPECT_THAT(bad_cell.err, HasSubstr("bad.csv:3"));
}

TEST_F(ChartTest, UsageErrorsSayWhatIsAllowed) {
  const Outcome quantity = Chart({"pair", "--y", "velocity"});
  EXPECT_EQ(quantity.code, 2);
  EXPECT_THAT(quantity.err, HasSubstr("t, x, y, u, v, omega, angle, fx, fy, torque, speed, gap"));

  const Outcome gap = Chart({"single", "--y", "gap"});
  EXPECT_EQ(gap.code, 2);
  EXPECT_THAT(gap.err, HasSubstr("gap needs two or more particles"));

  const Outcome particle = Chart({"pair", "--y", "u", "--particle", "7"});
  EXPECT_EQ(particle.code, 2);
  EXPECT_THAT(particle.err, HasSubstr("its ids: 0, 1"));

  const Outcome missing = Chart({"no_such_run", "--y", "u"});
  EXPECT_EQ(missing.code, 2);
  EXPECT_THAT(missing.err, HasSubstr("no_such_run"));

  const Outcome both = Chart({"pair", "--y", "u", "--csv", "wp.csv", "--xcol", "a", "--ycol", "b"});
  EXPECT_EQ(both.code, 2);

  const Outcome unwritable = Chart({"pair", "--y", "u", "--out", "no_such_dir/u.png"});
  EXPECT_EQ(unwritable.code, 9);
  EXPECT_THAT(unwritable.err, HasSubstr("no_such_dir/u.png"));
}

}  // namespace
}  // namespace dlmfd
