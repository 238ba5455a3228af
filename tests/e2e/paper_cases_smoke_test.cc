// Smoke runs of the paper's cases through the real dlmfd-solve binary: the scene files of
// cases/paper as shipped, on a coarse mesh (h = 1/24, particle mesh h = 1/17.5, the paper's ratio)
// for the first few dozen steps. They check the whole chain (scene file, Simulation with every
// substep, results directory) and physics that must hold from the first step on, whatever the mesh:
// a heavy disk released from rest falls and speeds up, disks stay apart and inside the channel, the
// liquid is stretched (trA > 2) around a moving disk and nowhere below trA = 2 beyond the
// divergence error of the mesh (see kTrASlack), and the run completes.
#include <sys/wait.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "../support/build_paths.h"
#include "../support/scratch_path.h"
#include "dlmfd/io/atomic_file.h"
#include "dlmfd/io/field_snapshot.h"
#include "dlmfd/io/particle_history.h"

namespace dlmfd {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kCases = DLMFD_SOURCE_DIR "/cases/paper/";
constexpr double kCoarseH = 1.0 / 24;
constexpr double kCoarseParticleH = kCoarseH * 96.0 / 70.0;  // the paper's ratio h_p / h
constexpr double kRecordEvery = 0.002;

std::string Number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

struct CaseRun {
  int exit_code = -1;
  std::string out;
  std::string summary;
  ParticleHistory history;
  FieldSnapshot last;  // the snapshot at the end time
};

// Runs cases/paper/<name>.toml coarse until `end`, particles every kRecordEvery, one snapshot at
// end.
CaseRun RunCase(const std::string& name, double end) {
  CaseRun run;
  run.out = dlmfd::testing::ScratchPath("paper_smoke_" + name);
  fs::remove_all(run.out);
  const std::vector<std::string> args = {kCases + name + ".toml",
                                         "--out",
                                         run.out,
                                         "--quiet",
                                         "--threads",
                                         "1",
                                         "--set",
                                         "domain.h=" + Number(kCoarseH),
                                         "--set",
                                         "particle_mesh.h=" + Number(kCoarseParticleH),
                                         "--set",
                                         "time.end=" + Number(end),
                                         "--set",
                                         "output.particles_every=" + Number(kRecordEvery),
                                         "--set",
                                         "output.fields_every=" + Number(end),
                                         "--set",
                                         "output.checkpoint_every=0"};
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv{const_cast<char*>(testing::kSolver.c_str())};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(testing::kSolver.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
  if (run.exit_code != 0) return run;
  run.summary = ReadTextFile(run.out + "/summary.json");
  run.history = ReadParticleHistory(run.out + "/particles.h5");
  std::string last;
  for (const auto& e : fs::directory_iterator(run.out + "/fields")) {
    const std::string file = e.path().filename().string();
    if (file.rfind("snap_", 0) == 0 && file > last) last = file;
  }
  run.last = ReadFieldSnapshot(run.out + "/fields/" + last);
  return run;
}

Vec2 Position(const ParticleHistory& h, std::size_t record, std::size_t p) {
  const std::size_t k = 2 * (record * h.particles + p);
  return Vec2(h.position[k], h.position[k + 1]);
}

double VerticalVelocity(const ParticleHistory& h, std::size_t record, std::size_t p) {
  return h.velocity[2 * (record * h.particles + p) + 1];
}

void ExpectCompleted(const CaseRun& run, double end) {
  ASSERT_EQ(run.exit_code, 0) << "see " << run.out;
  EXPECT_THAT(run.summary, HasSubstr("\"status\": \"completed\""));
  const std::size_t expected =
      static_cast<std::size_t>(std::llround(end / kRecordEvery)) + 1;  // t = 0 too
  EXPECT_EQ(run.history.records, expected);
  EXPECT_NEAR(run.last.time, end, 1e-12);
}

// Every pair of disks farther apart than the sum of radii, every disk inside the channel (width W,
// walls at x = 0, W and y = 0, H), at every record.
void ExpectApartAndInside(const ParticleHistory& h, double width, double height) {
  for (std::size_t r = 0; r < h.records; ++r) {
    for (std::size_t i = 0; i < h.particles; ++i) {
      const Vec2 xi = Position(h, r, i);
      const double ri = h.radius[i];
      EXPECT_GT(std::min({xi.x() - ri, width - xi.x() - ri, xi.y() - ri, height - xi.y() - ri}),
                0.0)
          << "particle " << i << " at record " << r;
      for (std::size_t j = i + 1; j < h.particles; ++j) {
        EXPECT_GT((Position(h, r, j) - xi).norm(), ri + h.radius[j])
            << "particles " << i << ", " << j << " at record " << r;
      }
    }
  }
}

// From A = I, the exact Oldroyd-B A keeps det A >= 1 in an incompressible flow (stretching with
// det F = 1 and relaxation towards I both keep it, det^(1/2) being concave on SPD tensors), hence
// trA >= 2. The discrete velocity is divergence-free only weakly (P1-iso-P2 against the P1 pressure
// of the 2h mesh), so the nodal trace of L is not zero where the velocity varies on the scale of a
// few cells, next to a disk; a compressive tr L = -2a relaxes A towards I / (1 + 2 lambda a), below
// trA = 2. Measured minimum of trA at t = 0.02 in 5.1a (the fastest, most stretched case) with the
// ring mesh: 1.847 at h = 1/24 and 1.844 at h = 1/48 (found 1.2-2.2 R from the disk, in its wake),
// i.e. a ~ 4/s against |L| ~ 100/s; 5.1b and 5.3c: 1.993 and 1.986 at h = 1/24. With the
// collocation points (the default since issue 32) the least is at the disk's surface, where the
// point forces squeeze the liquid between boundary points 2h apart: 1.747 / 1.673 at h = 1/24 /
// 1/48 under the case file's coupling and advection, 1.730 / 1.710 with wave advection on both
// diagonals under the incremental coupling, 1.744 / 1.796 under the paper's (2026-12-04). The
// slack 0.4 covers those with a margin and still fails on a sign or scale error of the coupling,
// which moves trA by O(1).
constexpr double kTrASlack = 0.4;

// max trA over the nodes within `distance` of centre, and over all nodes; min trA over all nodes.
struct TrAStats {
  double near_max = 0.0, max = 0.0, min = 0.0;
};
TrAStats TrA(const FieldSnapshot& s, const std::vector<Vec2>& centres, double distance) {
  const FieldArray& tr = s.fields.at("trA");
  const std::size_t rows = tr.shape[0], columns = tr.shape[1];
  TrAStats stats{-1e300, -1e300, 1e300};
  for (std::size_t j = 0; j < rows; ++j) {
    for (std::size_t i = 0; i < columns; ++i) {
      const double value = tr.values[j * columns + i];
      const Vec2 x(s.x0 + i * s.h, s.y0 + j * s.h);
      stats.max = std::max(stats.max, value);
      stats.min = std::min(stats.min, value);
      for (const Vec2& c : centres) {
        if ((x - c).norm() <= distance) stats.near_max = std::max(stats.near_max, value);
      }
    }
  }
  return stats;
}

// 5.1a: rho_p = 1.5, lambda = 0.01, dt = 1e-3, channel 1.5 x 6; 20 steps.
TEST(PaperCasesSmoke, HeavyDiskInOldroydBLiquidFallsFasterAndStretchesTheLiquidAroundIt) {
  const double end = 0.02;
  const CaseRun run = RunCase("5.1a_disk_rho1.5_h96_dt1e-3", end);
  ExpectCompleted(run, end);
  const ParticleHistory& h = run.history;
  ASSERT_EQ(h.particles, 1u);
  for (std::size_t r = 1; r < h.records; ++r) {
    EXPECT_LT(VerticalVelocity(h, r, 0), VerticalVelocity(h, r - 1, 0)) << "record " << r;
  }
  EXPECT_LT(Position(h, h.records - 1, 0).y(), 5.2);
  ExpectApartAndInside(h, 1.5, 6.0);
  const Vec2 centre = Position(h, h.records - 1, 0);
  const TrAStats tr = TrA(run.last, {centre}, 2.0 * 0.1);
  EXPECT_GT(tr.near_max, 2.1) << "no stretching near the moving disk (measured 2.22)";
  EXPECT_EQ(tr.near_max, tr.max) << "the liquid is most stretched next to the only moving body";
  EXPECT_GE(tr.min, 2.0 - kTrASlack);
}

// 5.1b: rho_p = 1.02, lambda = 0.3 (a slow, strongly elastic fall); 30 steps of 4e-4.
TEST(PaperCasesSmoke, LightDiskInElasticLiquidFalls) {
  const double end = 0.012;
  const CaseRun run = RunCase("5.1b_disk_rho1.02_lambda0.3", end);
  ExpectCompleted(run, end);
  const ParticleHistory& h = run.history;
  ASSERT_EQ(h.particles, 1u);
  for (std::size_t r = 1; r < h.records; ++r) {
    EXPECT_LT(VerticalVelocity(h, r, 0), VerticalVelocity(h, r - 1, 0)) << "record " << r;
  }
  ExpectApartAndInside(h, 1.5, 6.0);
  const TrAStats tr = TrA(run.last, {Position(h, h.records - 1, 0)}, 2.0 * 0.1);
  EXPECT_GT(tr.near_max, 2.0);
  EXPECT_EQ(tr.near_max, tr.max);
  EXPECT_GE(tr.min, 2.0 - kTrASlack);
}

// 5.3c: eleven disks in a channel 1 wide, closer to each other and to the walls (gaps 0.05) than
// the collision range 1.5 h = 0.0625 of this mesh: the collision forces act from the first step.
TEST(PaperCasesSmoke, ElevenDisksInNarrowChannelFallAndStayApart) {
  const double end = 0.012;
  const CaseRun run = RunCase("5.3c_eleven_disks_narrow", end);
  ExpectCompleted(run, end);
  const ParticleHistory& h = run.history;
  ASSERT_EQ(h.particles, 11u);
  ExpectApartAndInside(h, 1.0, 8.0);
  double mean_start = 0.0, mean_end = 0.0;
  std::vector<Vec2> centres;
  for (std::size_t p = 0; p < h.particles; ++p) {
    mean_start += Position(h, 0, p).y() / h.particles;
    mean_end += Position(h, h.records - 1, p).y() / h.particles;
    centres.push_back(Position(h, h.records - 1, p));
  }
  EXPECT_LT(mean_end, mean_start) << "the cloud must sink";
  double mean_velocity = 0.0;
  for (std::size_t p = 0; p < h.particles; ++p)
    mean_velocity += VerticalVelocity(h, h.records - 1, p);
  EXPECT_LT(mean_velocity, 0.0);
  const TrAStats tr = TrA(run.last, centres, 2.0 * 0.1);
  EXPECT_GT(tr.near_max, 2.0);
  EXPECT_EQ(tr.near_max, tr.max);
  EXPECT_GE(tr.min, 2.0 - kTrASlack);
}

}  // namespace
}  // namespace dlmfd
