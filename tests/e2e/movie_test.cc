// `dlmfd movie` and `dlmfd plot` end to end: the real dlmfd-solve runs tiny scenes (a disk settling
// in a 16 x 32 box, 10 steps; Oldroyd-B with a snapshot every 2 steps, without snapshots, and
// Newtonian), then the real dlmfd binary
// makes a movie of its snapshots with Debian's ffmpeg, which ffprobe reads back: one frame per
// snapshot, the frame size dlmfd reports (even sides), the duration frames / fps. The same run is
// plotted in the derived quantities with isolines and arrows, as PNG read back by cairo and as PDF,
// the signed ones (vorticity, A12, pressure) on the diverging map and the others on viridis;
// a quantity the snapshots lack and a movie without snapshots are usage errors naming the cause.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../support/build_paths.h"
#include "dlmfd/io/field_snapshot.h"
#include "dlmfd/viz/canvas.h"
#include "dlmfd/viz/colour_map.h"
#include "support/run_process.h"

namespace dlmfd {
namespace {

namespace fs = std::filesystem;
using test::Execute;
using test::Outcome;
using ::testing::HasSubstr;

using testing::kClient;
using testing::kSolver;
const std::string kFfprobe = "/usr/bin/ffprobe";

std::string Scene(double fields_every, double relaxation_time) {
  std::ostringstream text;
  text << "title = \"movie e2e\"\n"
       << "[domain]\nsize = [1.0, 2.0]\nh = 0.0625\n"
       << "[fluid]\ndensity = 1.0\nviscosity = 0.1\nrelaxation_time = " << relaxation_time
       << "\nsolvent_ratio = 0.5\n"
       << "gravity = [0.0, -981.0]\n"
       << "[time]\ndt = 0.001\nend = 0.01\n"
       << "[particle_mesh]\nh = 0.08571428571428572\n"
       << "[[particles]]\ncenter = [0.5, 1.4]\ndiameter = 0.25\ndensity = 1.1\n"
       << "[output]\nfields_every = " << fields_every
       << "\nparticles_every = 0.001\ncheckpoint_every = 0.0\n";
  return text.str();
}

// "key=value" lines of ffprobe's default writer.
std::string Probed(const std::string& text, const std::string& key) {
  std::smatch match;
  if (!std::regex_search(text, match, std::regex(key + "=([^\\n]*)"))) return "";
  return match[1];
}

class MovieTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(fs::exists(kClient)) << kClient << " is not built";
    ASSERT_TRUE(fs::exists(kSolver)) << kSolver << " is not built";
    root_ = fs::path(::testing::TempDir()) / ("dlmfd_movie_e2e_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    std::ofstream(root_ / "disk.toml") << Scene(0.002, 0.1);
    std::ofstream(root_ / "quiet.toml") << Scene(0.0, 0.1);
    std::ofstream(root_ / "newtonian.toml") << Scene(0.005, 0.0);
    for (const char* name : {"disk", "quiet", "newtonian"}) {
      const Outcome solve = Execute({kSolver, (root_ / (std::string(name) + ".toml")).string(),
                                     "--out", (root_ / name).string(), "--quiet", "--threads", "1"},
                                    root_);
      ASSERT_EQ(solve.code, 0) << name << ": " << solve.err;
    }
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }

  static Outcome Client(std::vector<std::string> args) {
    args.insert(args.begin(), kClient);
    return Execute(args, root_);
  }

  static fs::path root_;
};

fs::path MovieTest::root_;

TEST_F(MovieTest, OneFramePerSnapshotAtTheReportedSizeAndRate) {
  ASSERT_TRUE(fs::exists(kFfprobe)) << "ffprobe (Debian's ffmpeg, scripts/setup.sh) is missing";
  const std::size_t snapshots = SnapshotSteps((root_ / "disk").string()).size();
  ASSERT_GE(snapshots, 5u);
  const Outcome movie = Client({"movie", "disk", "--quantity", "trA", "--out", "disk.mp4", "--fps",
                                "4", "--width", "420", "--height", "500"});
  ASSERT_EQ(movie.code, 0) << movie.err;
  EXPECT_EQ(movie.out, "disk.mp4\n");
  std::smatch size;
  ASSERT_TRUE(std::regex_search(movie.err, size, std::regex("(\\d+) frames, (\\d+)x(\\d+)")))
      << movie.err;
  EXPECT_EQ(std::stoul(size[1]), snapshots);
  const int width = std::stoi(size[2]);
  const int height = std::stoi(size[3]);
  EXPECT_EQ(width % 2, 0);
  EXPECT_EQ(height % 2, 0);
  EXPECT_LE(width, 420);
  EXPECT_LE(height, 500);

  const Outcome probe =
      Execute({kFfprobe, "-v", "error", "-select_streams", "v:0", "-count_frames", "-show_entries",
               "stream=codec_name,width,height,nb_read_frames:format=duration", "-of",
               "default=noprint_wrappers=1", (root_ / "disk.mp4").string()},
              root_);
  ASSERT_EQ(probe.code, 0) << probe.err;
  EXPECT_EQ(Probed(probe.out, "codec_name"), "h264");
  EXPECT_EQ(std::stoi(Probed(probe.out, "width")), width);
  EXPECT_EQ(std::stoi(Probed(probe.out, "height")), height);
  EXPECT_EQ(std::stoul(Probed(probe.out, "nb_read_frames")), snapshots);
  // snapshots / 4 seconds, to the container's time base.
  EXPECT_NEAR(std::stod(Probed(probe.out, "duration")), snapshots / 4.0, 0.01);
  // Nothing is left under a temporary name.
  for (const auto& entry : fs::directory_iterator(root_))
    EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos);
}

TEST_F(MovieTest, ErrorsNameTheCause) {
  const Outcome none = Client({"movie", "quiet", "--out", "quiet.mp4"});
  EXPECT_EQ(none.code, 2);
  EXPECT_THAT(none.err, HasSubstr("no field snapshots"));
  const Outcome extension = Client({"movie", "disk", "--out", "disk.avi"});
  EXPECT_EQ(extension.code, 2);
  EXPECT_THAT(extension.err, HasSubstr(".mp4, .mkv, .mov, .webm or .gif"));
  const Outcome missing_ffmpeg =
      Client({"movie", "disk", "--out", "x.mp4", "--ffmpeg", "/nonexistent/ffmpeg"});
  EXPECT_NE(missing_ffmpeg.code, 0);
  EXPECT_THAT(missing_ffmpeg.err, HasSubstr("ffmpeg"));
  EXPECT_FALSE(fs::exists(root_ / "x.mp4"));
}

TEST_F(MovieTest, PlotDrawsTheDerivedQuantitiesWithIsolinesAndArrows) {
  for (const char* quantity : {"trA-2", "log10(trA/2)", "vorticity", "A12", "pressure"}) {
    const Outcome plot =
        Client({"plot", "disk", "--quantity", quantity, "--isolines", "4", "--arrows", "6", "--out",
                "q.png", "--width", "400", "--height", "600"});
    ASSERT_EQ(plot.code, 0) << quantity << ": " << plot.err;
    const RgbImage png = ReadPng((root_ / "q.png").string());
    EXPECT_LE(png.width, 400) << quantity;
    EXPECT_LE(png.height, 600) << quantity;
    EXPECT_GT(png.height, png.width) << quantity;  // the 1 x 2 domain stands upright
  }
  const Outcome pdf = Client({"plot", "disk", "--quantity", "trA-2", "--log", "--isolines", "5",
                              "--lines-only", "--window", "0.2,1.0,0.8,1.6", "--out", "trA.pdf"});
  ASSERT_EQ(pdf.code, 0) << pdf.err;
  std::ifstream in(root_ / "trA.pdf", std::ios::binary);
  std::string head(5, '\0');
  in.read(head.data(), 5);
  EXPECT_EQ(head, "%PDF-");
  const Outcome newtonian = Client({"plot", "newtonian", "--quantity", "A11"});
  EXPECT_EQ(newtonian.code, 2);
  EXPECT_THAT(newtonian.err, HasSubstr("/A11 is missing: a Newtonian run"));
  const Outcome lines = Client({"plot", "disk", "--lines-only"});
  EXPECT_EQ(lines.code, 2);
  EXPECT_THAT(lines.err, HasSubstr("--isolines"));
}

// Whether any pixel of the image is exactly `colour`.
bool Holds(const RgbImage& image, Rgb colour) {
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (image.At(x, y) == colour) return true;
    }
  }
  return false;
}

TEST_F(MovieTest, SignedQuantitiesAreDrawnOnTheDivergingMapCentredOnZero) {
  // The colour bar (over 256 rows here) runs from one end of its map to the other: a signed
  // quantity's range is symmetric about zero on cool to warm, so both of its ends show; the
  // others stay on viridis.
  auto picture = [&](const std::vector<std::string>& flags) {
    std::vector<std::string> args = {"plot", "disk", "--out", "s.png"};
    args.insert(args.end(), {"--width", "500", "--height", "800"});
    args.insert(args.end(), flags.begin(), flags.end());
    const Outcome plot = Client(args);
    EXPECT_EQ(plot.code, 0) << plot.err;
    return ReadPng((root_ / "s.png").string());
  };
  for (const char* quantity : {"vorticity", "A12", "pressure"}) {
    const RgbImage png = picture({"--quantity", quantity});
    EXPECT_TRUE(Holds(png, CoolWarm(0.0))) << quantity;
    EXPECT_TRUE(Holds(png, CoolWarm(1.0))) << quantity;
    EXPECT_FALSE(Holds(png, Viridis(1.0))) << quantity;
  }
  for (const char* quantity : {"trA", "trA-2", "speed", "A11", "A22"}) {
    const RgbImage png = picture({"--quantity", quantity});
    EXPECT_TRUE(Holds(png, Viridis(0.0))) << quantity;
    EXPECT_TRUE(Holds(png, Viridis(1.0))) << quantity;
    EXPECT_FALSE(Holds(png, CoolWarm(0.0))) << quantity;
    EXPECT_FALSE(Holds(png, CoolWarm(1.0))) << quantity;
  }
  // A lopsided --range keeps zero neutral: its positive end is the red end, its negative end
  // (-1 of 3) a pale blue, never the blue end. --log keeps viridis.
  const RgbImage lopsided = picture({"--quantity", "vorticity", "--range=-1,3"});
  EXPECT_TRUE(Holds(lopsided, CoolWarm(1.0)));
  EXPECT_FALSE(Holds(lopsided, CoolWarm(0.0)));
  EXPECT_TRUE(Holds(lopsided, CoolWarm(0.5 - 1.0 / 6.0)));
  const RgbImage log = picture({"--quantity", "vorticity", "--log"});
  EXPECT_TRUE(Holds(log, Viridis(1.0)));
  EXPECT_FALSE(Holds(log, CoolWarm(1.0)));
}

}  // namespace
}  // namespace dlmfd
