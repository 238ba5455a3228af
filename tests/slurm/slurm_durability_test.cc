// Durability of the slurm executor against a real Slurm (scripts/slurm-dev.sh start): the daemon
// killed with SIGKILL while 20 Slurm jobs run or wait adopts them all on restart (the Slurm ids
// of the store: none submitted again, none run twice) and records those that ended meanwhile
// with their results; slurmctld stopped and started again while jobs run, wait and are
// submitted: the daemon carries on (it keeps the last states while squeue fails and runs sbatch
// again once the controller answers) and every job completes. Skipped, naming scripts/slurm-dev.sh,
// when no Slurm answers sinfo; the controller restart also needs root (it stops and starts
// slurmctld).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "slurm_harness.h"

namespace dlmfd::testing {
namespace {
namespace fs = std::filesystem;

class SlurmDurability : public SlurmTest {};

const std::string kSlurmDev = std::string(DLMFD_SOURCE_DIR) + "/scripts/slurm-dev.sh";

// How many of the jobs have ended in Slurm (the jobcomp file).
int EndedInSlurm(const std::vector<std::string>& ids) {
  int ended = 0;
  for (const auto& id : ids) ended += SlurmEndsOfName("dlmfd-" + id) > 0 ? 1 : 0;
  return ended;
}

TEST_F(SlurmDurability, ADaemonKilledWithTwentyJobsInSlurmAdoptsThemAllOnRestart) {
  constexpr int kJobs = 20;
  std::vector<std::string> ids;
  std::map<std::string, std::string> slurm_ids;
  int ended_before = 0;
  {
    ASSERT_TRUE(StartDaemon()) << daemon().Log();
    auto* stub = this->stub();
    for (int k = 0; k < kJobs; ++k) ids.push_back(Submit(*stub, CavityScene(2.0)).id());
    // All in Slurm's hands (2 run on the node's 2 CPUs, the others wait), one has run.
    ASSERT_TRUE(WaitUntil([&] {
      for (const auto& id : ids) {
        if (GetJob(*stub, id).slurm_job_id().empty()) return false;
      }
      return true;
    })) << daemon().Log();
    WaitForProgress(*stub, ids.front());
    for (const auto& id : ids) slurm_ids[id] = GetJob(*stub, id).slurm_job_id();
    daemon().Kill(SIGKILL);
    daemon().Wait();
    ended_before = EndedInSlurm(ids);
  }
  ASSERT_LT(ended_before, kJobs - 2) << "the jobs ended before the daemon was killed";
  // Slurm goes on without the daemon: two more jobs end meanwhile.
  ASSERT_TRUE(WaitUntil([&] { return EndedInSlurm(ids) >= ended_before + 2; }));
  const size_t log_before = daemon().Log().size();  // the restarted daemon appends to the log
  ASSERT_TRUE(StartDaemon()) << daemon().Log();
  auto* stub = this->stub();
  for (const auto& id : ids) {
    const v1::Job done = WaitFinished(*stub, id);
    EXPECT_EQ(done.state(), v1::COMPLETED) << id << ": " << done.reason() << "\n" << daemon().Log();
    EXPECT_EQ(done.slurm_job_id(), slurm_ids[id]) << id;  // not submitted again
    EXPECT_EQ(done.step(), 200) << id;
    EXPECT_TRUE(fs::exists(done.results_dir() + "/summary.json")) << id;
  }
  // Each ran once in Slurm.
  EXPECT_TRUE(WaitUntil([&] { return EndedInSlurm(ids) == kJobs; }));
  for (const auto& id : ids) EXPECT_EQ(SlurmEndsOfName("dlmfd-" + id), 1) << id;
  // Every job unfinished at the kill was adopted; nothing was submitted. Which were unfinished is
  // what the next daemon found RUNNING: a job whose exit file the daemon read before the kill is
  // recorded finished though Slurm's jobcomp file may not list it yet (ended_before misses it).
  const std::string log = daemon().Log().substr(log_before);
  auto count = [&log](const std::string& text) {
    int n = 0;
    for (size_t at = log.find(text); at != std::string::npos; at = log.find(text, at + 1)) ++n;
    return n;
  };
  const int adopted = count(" adopted (it outlived");
  const int unfinished = count("was RUNNING when the daemon stopped");
  EXPECT_EQ(adopted, unfinished) << log;
  EXPECT_GT(unfinished, kJobs / 2) << log;  // most were in flight at the kill
  EXPECT_FALSE(std::regex_search(log, std::regex("Slurm job [0-9_]+ started"))) << log;
  EXPECT_EQ(log.find("job array"), std::string::npos) << log;
}

// Starts slurmctld again when the test ends, whatever happened.
struct ControllerBack {
  ~ControllerBack() { std::system((kSlurmDev + " start-slurmctld > /dev/null 2>&1").c_str()); }
};

// A long job is followed through the outage (its squeue fails: the daemon keeps the last
// states), jobs submitted during it wait for the controller (sbatch is run again); afterwards the
// long job is cancelled through Slurm and the jobs in Slurm before the outage end as usual.
TEST_F(SlurmDurability, TheDaemonCarriesOnThroughASlurmctldRestart) {
  if (geteuid() != 0) GTEST_SKIP() << "stopping slurmctld needs root (scripts/slurm-dev.sh)";
  ASSERT_TRUE(StartDaemon()) << daemon().Log();
  auto* stub = this->stub();
  const std::string long_job = Submit(*stub, CavityScene(1.0e4)).id();
  std::vector<std::string> ids;
  for (int k = 0; k < 2; ++k) ids.push_back(Submit(*stub, CavityScene(2.0)).id());
  WaitForProgress(*stub, long_job);
  {
    ControllerBack back;
    ASSERT_EQ(std::system((kSlurmDev + " stop-slurmctld > /dev/null").c_str()), 0);
    for (int k = 0; k < 2; ++k) ids.push_back(Submit(*stub, CavityScene(2.0)).id());
    // The daemon sees the controller gone: squeue fails, sbatch cannot reach it.
    EXPECT_TRUE(WaitUntil([&] {
      const std::string log = daemon().Log();
      return log.find("squeue --json failed") != std::string::npos &&
             log.find("trying again in") != std::string::npos;
    })) << daemon().Log();
    EXPECT_EQ(GetJob(*stub, long_job).state(), v1::RUNNING);
    ASSERT_EQ(std::system((kSlurmDev + " start-slurmctld > /dev/null").c_str()), 0);
  }
  // The long job ran through it all and is cancelled as ever (first: on a node of one CPU the
  // other jobs wait for its CPU).
  const v1::Job cancelled = CancelAndWait(*stub, long_job);
  EXPECT_EQ(cancelled.state(), v1::CANCELLED) << cancelled.reason() << "\n" << daemon().Log();
  EXPECT_EQ(cancelled.attempt(), 1);
  for (const auto& id : ids) {
    const v1::Job done = WaitFinished(*stub, id);
    EXPECT_EQ(done.state(), v1::COMPLETED) << id << ": " << done.reason() << "\n" << daemon().Log();
    EXPECT_EQ(done.step(), 200) << id;
    EXPECT_EQ(done.attempt(), 1) << id;
  }
  EXPECT_TRUE(WaitUntil([&] { return EndedInSlurm(ids) == 4; }));
  for (const auto& id : ids) EXPECT_EQ(SlurmEndsOfName("dlmfd-" + id), 1) << id;
}

}  // namespace
}  // namespace dlmfd::testing
