// The slurm executor's follow loop (SlurmRun::ReadEvents, slurm_executor.h) on a job directory as
// a Slurm job leaves it, without a Slurm: the events a real dlmfd-solve wrote (events.bin) and the
// batch script's exit file (solver.exit). The race of the flaky durability test
// (tests/slurm/slurm_durability_test.cc, a job COMPLETED at step 0 under load): the solver
// finishes, and the batch script writes its exit file, while the daemon handles the first events
// it read (here: while it records that the job runs, the OnStateChange handler). Every event the
// solver wrote must still be delivered, its finished event last, before the end.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config.h"
#include "event_file_tail.h"
#include "job_store.h"
#include "slurm_commands.h"
#include "slurm_executor.h"
#include "support/daemon_process.h"

namespace dlmfd::server {
namespace {
namespace fs = std::filesystem;
using dlmfd::testing::CavityScene;
using dlmfd::testing::kSolverPath;
using dlmfd::testing::SolverAvailable;
using dlmfd::testing::TempDir;

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void WriteBytes(const fs::path& path, const std::string& bytes, std::ios::openmode mode) {
  std::ofstream out(path, std::ios::binary | mode);
  out << bytes;
}

// No Slurm is needed here: squeue, which the follow loop's first poll runs, is not found (PATH is
// an empty directory: it fails at once, where a Slurm without a controller takes seconds to say
// so). PATH is restored afterwards.
class NoSlurmCommands {
 public:
  explicit NoSlurmCommands(const std::string& empty_dir) {
    if (const char* old = std::getenv("PATH")) old_ = old;
    setenv("PATH", empty_dir.c_str(), 1);
  }
  ~NoSlurmCommands() {
    if (old_) {
      setenv("PATH", old_->c_str(), 1);
    } else {
      unsetenv("PATH");
    }
  }
  NoSlurmCommands(const NoSlurmCommands&) = delete;
  NoSlurmCommands& operator=(const NoSlurmCommands&) = delete;

 private:
  std::optional<std::string> old_;
};

TEST(SlurmFollow, AnExitThatComesWhileTheFirstEventsAreHandledEndsAfterAllEvents) {
  if (!SolverAvailable()) GTEST_SKIP() << "dlmfd-solve is not built: " << kSolverPath;
  TempDir tmp;
  const fs::path work = tmp.path();
  // A real solver's event stream: the 16x16 cavity for 200 steps.
  const fs::path scene = work / "scene.toml";
  WriteBytes(scene, CavityScene(2.0), std::ios::trunc);
  const fs::path full = work / "events.full";
  const std::string command = "exec 3> '" + full.string() + "'; '" + kSolverPath + "' '" +
                              scene.string() + "' --out '" + (work / "results").string() +
                              "' --events 3 > '" + (work / "solver.log").string() + "' 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << ReadBytes(work / "solver.log");
  std::vector<v1::SolverEvent> written;
  int64_t first_end = 0;  // the offset just past the first event
  {
    EventFileTail all(full.string());
    all.ReadNew([&](const v1::SolverEvent& event) {
      if (written.empty()) first_end = static_cast<int64_t>(all.offset());
      written.push_back(event);
    });
  }
  ASSERT_GT(written.size(), 3u);
  ASSERT_TRUE(written.front().has_started());
  ASSERT_TRUE(written.back().has_finished());
  ASSERT_EQ(written.back().finished().steps(), 200);
  const std::string bytes = ReadBytes(full);

  // The job directory when the daemon looks first: Slurm runs the job, the solver has written its
  // first event. The job was submitted by a daemon before (adopted: Slurm's last word PENDING).
  const fs::path dir = work / "job";
  fs::create_directories(dir);
  WriteBytes(dir / kSlurmEventsFile, bytes.substr(0, first_end), std::ios::trunc);
  Config config;
  config.executor = "slurm";
  SlurmRun run(config, std::make_shared<SlurmQueue>(config.slurm));
  JobRecord job;
  job.id = "j-follow";
  job.slurm_job_id = "4242";
  job.slurm_live = true;
  job.slurm_state = "PENDING";
  job.slurm_waiting = true;
  ASSERT_TRUE(run.Adopt(dir.string(), job, [](const std::string&) { return std::nullopt; }));
  // While the daemon records that the job runs, the solver writes the rest and exits 0, and the
  // batch script writes its exit file.
  int running_reports = 0;
  run.OnStateChange([&](const ExecutorState& state) {
    if (state.state != "RUNNING" || running_reports++ > 0) return;
    WriteBytes(dir / kSlurmEventsFile, bytes.substr(first_end), std::ios::app);
    WriteBytes(dir / kSlurmExitFile, "0 0\n", std::ios::trunc);
  });
  std::vector<v1::SolverEvent> delivered;
  std::vector<int64_t> offsets;
  {
    fs::create_directories(work / "no-commands");
    NoSlurmCommands no_slurm((work / "no-commands").string());
    run.ReadEvents([&](const v1::SolverEvent& event, const EventPosition& position) {
      delivered.push_back(event);
      offsets.push_back(position.offset);
      EXPECT_EQ(position.source, "slurm:4242");
    });
  }
  EXPECT_EQ(running_reports, 1);
  const SolverExit exit = run.Wait();
  EXPECT_FALSE(exit.signalled);
  EXPECT_EQ(exit.code, 0);
  EXPECT_FALSE(run.Outcome().has_value());
  // Every event once, in order, finished (step 200) last; the last offset is the file's end.
  ASSERT_EQ(delivered.size(), written.size());
  for (size_t k = 0; k < written.size(); ++k) {
    EXPECT_EQ(delivered[k].SerializeAsString(), written[k].SerializeAsString()) << "event " << k;
  }
  ASSERT_TRUE(delivered.back().has_finished());
  EXPECT_EQ(delivered.back().finished().steps(), 200);
  EXPECT_EQ(offsets.back(), static_cast<int64_t>(bytes.size()));
}

}  // namespace
}  // namespace dlmfd::server
