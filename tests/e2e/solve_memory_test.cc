// The memory estimate against the real solver's peak (scene/scene_footprint.h): the daemon admits a
// job and Slurm reserves its --mem by the estimate, so it must hold what dlmfd-solve takes. Each
// run's peak resident set (wait4's ru_maxrss) less that of a run on a 16 x 16 cavity (the process
// itself: libraries, HDF5, spdlog) must lie within the estimate, and the estimate within twice it
// (docs/evidence/cut_cell_boundary.md, "The memory of a cut-cell run": the estimate was 1.09-1.5
// times the measured peak over the cases below; before it counted cut cells, 0.16 times a free
// disk's). Skipped under the sanitizers, whose shadow memory doubles the resident set.
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../support/build_paths.h"
#include "../support/scratch_path.h"
#include "dlmfd/scene/scene_file.h"
#include "dlmfd/scene/scene_footprint.h"

namespace dlmfd {
namespace {

namespace fs = std::filesystem;

const std::string kCaseDir = DLMFD_SOURCE_DIR "/cases/verification/";

struct Peak {
  int status = -1;
  double bytes = 0.0;
};

// Runs dlmfd-solve on one thread with `args` (output to a fresh folder); its exit status and peak
// resident set.
Peak PeakOfRun(const std::string& name, const std::vector<std::string>& args) {
  const std::string out = dlmfd::testing::ScratchPath("solve_memory_test_" + name);
  fs::remove_all(out);
  std::vector<std::string> all = args;
  for (const char* a : {"--threads", "1", "--quiet", "--out"}) all.emplace_back(a);
  all.push_back(out);
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, 1);
      dup2(null, 2);
    }
    std::vector<char*> argv{const_cast<char*>(testing::kSolver.c_str())};
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(testing::kSolver.c_str(), argv.data());
    _exit(127);
  }
  Peak peak;
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  peak.status = WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
  peak.bytes = static_cast<double>(usage.ru_maxrss) * 1024.0;  // ru_maxrss: KiB
  return peak;
}

// The scene file with the same overrides as the run (the "key=value" after each --set).
SceneFootprint EstimateOf(const std::string& scene, const std::vector<std::string>& args) {
  std::vector<SceneOverride> overrides;
  for (std::size_t i = 0; i + 1 < args.size(); ++i) {
    if (args[i] == "--set") overrides.push_back(ParseOverride(args[i + 1]));
  }
  return EstimateFootprint(LoadSceneFile(scene, overrides));
}

double ProcessAlone() {
  const std::string scene = dlmfd::testing::ScratchPath("solve_memory_test_cavity", ".toml");
  std::ofstream(scene) << "[domain]\nsize = [1.0, 1.0]\nh = 0.0625\n"
                          "[domain.boundary]\ntop = { type = \"velocity\", value = [1.0, 0.0] }\n"
                          "[time]\ndt = 0.001\nend = 0.002\n"
                          "[output]\nfields_every = 0\nparticles_every = 0\ncheckpoint_every = 0\n";
  const Peak p = PeakOfRun("cavity", {scene});
  EXPECT_EQ(p.status, 0);
  return p.bytes;
}

void ExpectEstimateHoldsThePeak(const std::string& name, const std::string& scene,
                                const std::vector<std::string>& sets, double process) {
  std::vector<std::string> args{scene};
  args.insert(args.end(), sets.begin(), sets.end());
  const Peak p = PeakOfRun(name, args);
  ASSERT_EQ(p.status, 0) << name;
  const double run = p.bytes - process;
  const double estimate = EstimateOf(scene, sets).bytes;
  EXPECT_GE(estimate, run) << name << ": peak " << p.bytes / 1e6 << " MB, the process alone "
                           << process / 1e6 << " MB";
  EXPECT_LE(estimate, 2.0 * run) << name;
}

TEST(SolveMemory, TheEstimateHoldsACutCellRunsPeak) {
#if defined(DLMFD_ASAN_BUILD) || defined(DLMFD_TSAN_BUILD)  // cmake/Sanitizers.cmake
  GTEST_SKIP() << "the sanitizers' shadow memory is not the solver's";
#endif
  const double process = ProcessAlone();
  const std::vector<std::string> common{"--set", "output.fields_every=0",
                                        "--set", "output.checkpoint_every=0",
                                        "--set", "particle_mesh.kind=\"cut_cell\""};
  auto with = [&](std::vector<std::string> sets) {
    sets.insert(sets.end(), common.begin(), common.end());
    return sets;
  };
  // A fixed disk (Schaefer-Turek as shipped, D/h = 20), a towed one (D/h = 40) and a free one
  // (Faxen's, D/h = 9.6), a few steps each: the peak comes with the set-up and the first steps.
  ExpectEstimateHoldsThePeak("fixed", kCaseDir + "schaefer_turek_2d1.toml",
                             with({"--set", "time.end=0.015"}), process);
  ExpectEstimateHoldsThePeak("towed", kCaseDir + "towed_disk_cut_cell.toml",
                             with({"--set", "domain.h=0.025", "--set", "time.end=0.02"}), process);
  ExpectEstimateHoldsThePeak(
      "free", kCaseDir + "faxen_disk_w1.toml",
      with({"--set", "domain.h=0.020833333333333332", "--set", "time.end=0.002"}), process);
}

}  // namespace
}  // namespace dlmfd
