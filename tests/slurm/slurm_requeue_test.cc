// Attempts under the slurm executor against a real Slurm (scripts/slurm-dev.sh start):
// `scontrol requeue` of a running job is a new attempt of the same Slurm job (Slurm's restart
// count) that resumes from the checkpoint and completes, not a failure; a job that Slurm ends
// with TIMEOUT is queued again by the daemon (slurm_max_attempts), resumes from the checkpoint
// the solver wrote at Slurm's SIGTERM and ends COMPLETED with the result of an uninterrupted
// run; a node that fails under a job (NODE_FAIL) is another attempt that completes. Skipped, naming
// scripts/slurm-dev.sh, when no Slurm answers sinfo.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "dlmfd/solver/run_summary.h"
#include "slurm_harness.h"

namespace dlmfd::testing {
namespace {
namespace fs = std::filesystem;

class SlurmRequeue : public SlurmTest {};

// A disk settling in an Oldroyd-B liquid in a closed box, 16 x 32 cells: a free particle and a
// polymer stress whose values a resumed run must reproduce to the last bit.
std::string SettlingDisk(double end_time) {
  std::ostringstream scene;
  scene << "title = \"a disk settling in an Oldroyd-B liquid\"\n"
           "gravity = [0.0, -981.0]\n"
           "[domain]\nsize = [1.0, 2.0]\nh = 0.0625\n"
           "[domain.boundary]\nleft = { type = \"wall\" }\nright = { type = \"wall\" }\n"
           "bottom = { type = \"wall\" }\ntop = { type = \"wall\" }\n"
           "[fluid]\ndensity = 1.0\nviscosity = 0.1\nrelaxation_time = 0.1\n"
           "solvent_ratio = 0.5\n"
           "[time]\ndt = 0.001\nend = "
        << end_time
        << "\n"
           "[[particles]]\ncenter = [0.5, 1.5]\ndiameter = 0.25\ndensity = 1.5\n"
           "[particle_mesh]\nh = 0.0625\n"
           "[output]\nfields_every = 0\nparticles_every = 0.01\ncheckpoint_every = 0\n";
  return scene.str();
}

// The daemon queued the job again once, as a new Slurm submission, after Slurm ended its first
// attempt (Slurm job slurm_id) in slurm_state (the jobcomp file says so).
void ExpectQueuedAgainAfter(const v1::Job& done, const std::string& slurm_id,
                            const std::string& slurm_state) {
  ASSERT_EQ(done.previous_attempts_size(), 1);
  const std::string reason = done.previous_attempts(0).reason();
  EXPECT_NE(reason.find("queued again to resume from the checkpoint: Slurm attempt 2 of "
                        "slurm_max_attempts = 2"),
            std::string::npos)
      << reason;
  EXPECT_NE(done.slurm_job_id(), slurm_id);  // a new submission
  EXPECT_TRUE(WaitUntil([&] {
    return Shell("grep '^JobId=" + slurm_id + " ' " + JobCompFile())
               .find("JobState=" + slurm_state) != std::string::npos;
  }));
}

solver::RunSummary Summary(const std::string& results) {
  return solver::ReadRunSummary(results + "/" + solver::kRunSummaryFile);
}

TEST_F(SlurmRequeue, ScontrolRequeueIsANewAttemptThatResumesAndCompletes) {
  ASSERT_TRUE(StartDaemon()) << daemon().Log();
  auto* stub = this->stub();
  // 30000 steps, about 10 s: still running when the test acts on it (3000 steps took 1 s).
  const v1::Job job = Submit(*stub, CavityScene(300.0));
  WaitForProgress(*stub, job.id());
  const std::string slurm_id = GetJob(*stub, job.id()).slurm_job_id();
  ASSERT_FALSE(slurm_id.empty());
  ASSERT_EQ(std::system(("scontrol requeue " + slurm_id).c_str()), 0);
  const std::time_t requeued_at = std::time(nullptr);
  // Slurm holds a requeued batch job back for a while (its begin time, 2 min here); an
  // administrator's `scontrol update StartTime=now` lets it go, as the test does not wait.
  ASSERT_TRUE(
      WaitUntil([&] { return Shell("squeue -h -j " + slurm_id + " -o %T") == "PENDING\n"; }));
  // The requeue revoked the job's credential at a time in whole seconds, and slurmd refuses any
  // credential issued in that second ("Killing non-startable batch JobId=N: Job credential
  // revoked", and the job ends FAILED): Slurm's own begin time keeps the restart out of that
  // second, so the early release must too.
  ASSERT_TRUE(WaitUntil([&] { return std::time(nullptr) >= requeued_at + 2; }));
  ASSERT_EQ(std::system(("scontrol update JobId=" + slurm_id + " StartTime=now").c_str()), 0);
  const v1::Job done = WaitFinished(*stub, job.id());
  EXPECT_EQ(done.state(), v1::COMPLETED) << done.reason() << "\n" << daemon().Log();
  EXPECT_EQ(done.slurm_job_id(), slurm_id);  // the same Slurm job, run again
  EXPECT_EQ(done.step(), 30000);
  EXPECT_EQ(done.attempt(), 2);
  ASSERT_EQ(done.previous_attempts_size(), 1);
  EXPECT_NE(
      done.previous_attempts(0).reason().find("Slurm requeued job " + slurm_id + " (restart 1)"),
      std::string::npos)
      << done.previous_attempts(0).reason();
  EXPECT_GT(done.previous_attempts(0).step(), 0);
  // The second run resumed from the checkpoint the first wrote at Slurm's SIGTERM.
  EXPECT_GT(Summary(done.results_dir()).resumed_from_step, 0);
  EXPECT_EQ(daemon().Log().find("FAILED"), std::string::npos) << daemon().Log();
}

// Slurm enforces time limits in whole minutes, checked every 30 s; the test makes the job's
// limit come at once without a minute of solver time: the solver is stopped (SIGSTOP, as a very
// slow step would hold it) and the job's end time brought forward (scontrol update EndTime=now+1).
// Slurm then times the job out: it continues the solver and sends it SIGTERM (the solver
// checkpoints and exits 130), and ends the job TIMEOUT. The daemon queues it again; the next
// attempt resumes from the checkpoint.
TEST_F(SlurmRequeue, ATimeoutResumesFromTheCheckpointAndEndsAsAnUninterruptedRun) {
  ASSERT_TRUE(StartDaemon({"--slurm-time-limit-minutes", "1", "--slurm-signal-seconds", "10",
                           "--slurm-max-attempts", "2"}))
      << daemon().Log();
  auto* stub = this->stub();
  // 20000 steps, about 6 s: the solver must still run when the test stops it (the first
  // progress reaches the test about half a second after the solver wrote it; 2500 steps were
  // over by then on an idle machine).
  const std::string scene = SettlingDisk(20.0);
  const v1::Job job = Submit(*stub, scene);
  WaitForProgress(*stub, job.id());
  const std::string slurm_id = GetJob(*stub, job.id()).slurm_job_id();
  ASSERT_FALSE(slurm_id.empty());
  // "--ou[t]": the shell that runs pgrep does not match its own pattern.
  const std::string pid = Shell("pgrep -f -- '--ou[t] " + job.results_dir() + "'");
  ASSERT_FALSE(pid.empty()) << "no solver of " << job.results_dir();
  ASSERT_EQ(std::system(("kill -STOP " + pid).c_str()), 0);
  ASSERT_EQ(std::system(("scontrol update JobId=" + slurm_id + " EndTime=now+1").c_str()), 0);
  const v1::Job done = WaitFinished(*stub, job.id());
  EXPECT_EQ(done.state(), v1::COMPLETED) << done.reason() << "\n" << daemon().Log();
  EXPECT_EQ(done.step(), 20000);
  EXPECT_EQ(done.attempt(), 2);
  ASSERT_EQ(done.previous_attempts_size(), 1);
  const std::string reason = done.previous_attempts(0).reason();
  EXPECT_TRUE(reason.find("TIMEOUT") != std::string::npos ||
              reason.find("time limit") != std::string::npos)
      << reason;
  ExpectQueuedAgainAfter(done, slurm_id, "TIMEOUT");
  // The same result as a run that was never interrupted, to the last bit, with the same one
  // OpenMP thread as the Slurm job's (--cpus-per-task=1: sums in another order differ).
  const solver::RunSummary resumed = Summary(done.results_dir());
  EXPECT_GT(resumed.resumed_from_step, 0);
  const std::string scene_file = dir() + "/scene.toml";
  std::ofstream(scene_file) << scene;
  ASSERT_EQ(std::system(("OMP_NUM_THREADS=1 " + kSolverPath + " " + scene_file + " --out " + dir() +
                         "/uninterrupted > /dev/null 2>&1")
                            .c_str()),
            0);
  const solver::RunSummary reference = Summary(dir() + "/uninterrupted");
  EXPECT_EQ(reference.resumed_from_step, -1);
  EXPECT_EQ(resumed.steps, reference.steps);
  ASSERT_EQ(resumed.particles.size(), 1u);
  ASSERT_EQ(reference.particles.size(), 1u);
  EXPECT_EQ(resumed.particles[0].position, reference.particles[0].position);
  EXPECT_EQ(resumed.particles[0].velocity, reference.particles[0].velocity);
  EXPECT_EQ(resumed.particles[0].angular_velocity, reference.particles[0].angular_velocity);
  EXPECT_EQ(resumed.particles[0].force, reference.particles[0].force);
}

// Brings the node back when the test ends, whatever happened.
struct NodeBack {
  std::string node;
  ~NodeBack() {
    std::system(("scontrol update NodeName=" + node + " State=RESUME > /dev/null 2>&1").c_str());
  }
};

// A node failure: the node is set DOWN under a running job (as slurmctld does when a node stops
// answering). With --no-requeue (a site's JobRequeue=0) Slurm ends the job NODE_FAIL; the daemon
// queues it again (slurm_max_attempts) and the next attempt, on the node back in service,
// completes. With Slurm's default requeue the same failure is a Slurm restart, as the requeue
// test above.
TEST_F(SlurmRequeue, ANodeFailureIsQueuedAgainAndCompletes) {
  if (geteuid() != 0) GTEST_SKIP() << "setting the node DOWN needs Slurm's root (scontrol)";
  ASSERT_TRUE(StartDaemon({"--slurm-sbatch-options=--no-requeue", "--slurm-max-attempts", "2"}))
      << daemon().Log();
  auto* stub = this->stub();
  // 30000 steps, about 10 s: still running when the test acts on it (3000 steps took 1 s).
  const v1::Job job = Submit(*stub, CavityScene(300.0));
  WaitForProgress(*stub, job.id());
  const std::string slurm_id = GetJob(*stub, job.id()).slurm_job_id();
  ASSERT_FALSE(slurm_id.empty());
  NodeBack back{Shell("squeue -h -j " + slurm_id + " -o %N | tr -d '\\n'")};
  ASSERT_FALSE(back.node.empty());
  ASSERT_EQ(std::system(("scontrol update NodeName=" + back.node +
                         " State=DOWN Reason=dlmfd-node-failure-test")
                            .c_str()),
            0);
  ASSERT_TRUE(WaitUntil([&] { return GetJob(*stub, job.id()).attempt() == 2; })) << daemon().Log();
  // Back in service (slurmd may have registered it already: ReturnToService=2).
  std::system(("scontrol update NodeName=" + back.node + " State=RESUME 2>/dev/null").c_str());
  const v1::Job done = WaitFinished(*stub, job.id());
  EXPECT_EQ(done.state(), v1::COMPLETED) << done.reason() << "\n" << daemon().Log();
  EXPECT_EQ(done.step(), 30000);
  EXPECT_EQ(done.attempt(), 2);
  ASSERT_EQ(done.previous_attempts_size(), 1);
  const std::string reason = done.previous_attempts(0).reason();
  EXPECT_NE(reason.find("NODE_FAIL"), std::string::npos) << reason;
  ExpectQueuedAgainAfter(done, slurm_id, "NODE_FAIL");
}

}  // namespace
}  // namespace dlmfd::testing
