// The daemon's slurm executor against a real Slurm (scripts/slurm-dev.sh start): one job end to
// end with its events streamed through the shared job directory (progress, particle states and
// trA snapshots, as for a local job), `dlmfd show`'s Slurm id, a job that waits in Slurm (held)
// shown QUEUED with Slurm's reason until Slurm starts it, the job's own time limit as its --time,
// cancel as scancel, a daemon killed with SIGKILL that adopts its Slurm job on restart, and one
// killed before it stored the Slurm id that follows the job it submitted.
// Skipped, naming scripts/slurm-dev.sh, when no Slurm answers sinfo.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>

#include "../server/support/store_fixtures.h"
#include "slurm_harness.h"

namespace dlmfd::testing {
namespace {
namespace fs = std::filesystem;

class SlurmExecutor : public SlurmTest {};

TEST_F(SlurmExecutor, OneJobEndToEndStreamsLikeALocalJob) {
  ASSERT_TRUE(StartDaemon()) << daemon().Log();
  auto* stub = this->stub();
  const v1::Job job = Submit(*stub, DiskInCavity(0.2));
  auto context = Context();
  v1::WatchRequest watch;
  watch.set_job_id(job.id());
  watch.set_include_snapshots(true);
  auto reader = stub->Watch(context.get(), watch);
  std::vector<v1::WatchEvent> events;
  for (v1::WatchEvent event; reader->Read(&event);) events.push_back(event);
  ASSERT_TRUE(reader->Finish().ok());
  ASSERT_FALSE(events.empty());
  ASSERT_TRUE(events.back().has_state()) << daemon().Log();
  EXPECT_EQ(events.back().state().state(), v1::COMPLETED) << events.back().state().reason() << "\n"
                                                          << daemon().Log();
  int progress = 0, particles = 0, snapshots = 0;
  v1::Snapshot last_snapshot;
  for (const auto& event : events) {
    if (event.has_progress()) ++progress;
    if (event.has_particles()) {
      ++particles;
      EXPECT_EQ(event.particles().particles_size(), 1);
    }
    if (event.has_snapshot()) {
      ++snapshots;
      last_snapshot = event.snapshot();
      EXPECT_EQ(event.snapshot().values_size(),
                (event.snapshot().nx() + 1) * (event.snapshot().ny() + 1));
    }
  }
  EXPECT_GT(progress, 0);
  // particles_every = 0.02 over t = 0.2: 10 outputs (the initial state may add one). Snapshots
  // are kept as for a local job: the hub holds the newest, a watcher's queue replaces a queued one
  // by a newer one, so a watcher sees at least the last (t = 0.2), of trA.
  EXPECT_GE(particles, 10);
  EXPECT_GE(snapshots, 1);
  EXPECT_EQ(last_snapshot.quantity(), "trA") << last_snapshot.DebugString().substr(0, 300);
  EXPECT_NEAR(last_snapshot.time(), 0.2, 1e-9);
  const v1::Job done = GetJob(*stub, job.id());
  EXPECT_FALSE(done.slurm_job_id().empty());
  EXPECT_EQ(done.step(), 20);
  EXPECT_TRUE(fs::exists(done.results_dir() + "/summary.json"));
  // The job really went through Slurm: the jobcomp file has its end (Slurm writes it after the
  // batch script, which wrote the exit status the daemon went by, has ended).
  EXPECT_TRUE(WaitUntil([&] {
    return Shell("grep -c '^JobId=" + done.slurm_job_id() + " ' " + JobCompFile()) == "1\n";
  }));
  // dlmfd show names the Slurm id.
  const std::string out = dir() + "/show.txt";
  const std::string command = std::string(DLMFD_BINARY_DIR) + "/client/dlmfd --server " +
                              daemon().address() + " show " + job.id() + " > " + out;
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream show(out);
  std::string shown((std::istreambuf_iterator<char>(show)), std::istreambuf_iterator<char>());
  EXPECT_NE(shown.find("slurm job:   " + done.slurm_job_id()), std::string::npos) << shown;
}

// Issue 38 under Slurm: a job after another is held by the daemon until that one COMPLETED (it
// never reaches Slurm before), and a Slurm run's accounting comes from the solver's own getrusage
// in its last event (this cluster has no accounting storage for sacct).
TEST_F(SlurmExecutor, ADependantReachesSlurmAfterItsDependencyAndRunsAreAccounted) {
  ASSERT_TRUE(StartDaemon()) << daemon().Log();
  auto* stub = this->stub();
  const v1::Job first = Submit(*stub, DiskInCavity(0.2));
  v1::SubmitRequest request;
  request.set_scene(DiskInCavity(0.05));
  request.add_after(first.id());
  v1::Job second;
  {
    auto context = Context();
    ASSERT_TRUE(stub->Submit(context.get(), request, &second).ok());
  }
  // Held by the daemon, not by Slurm: no Slurm job while the first has not completed.
  const v1::Job waiting = GetJob(*stub, second.id());
  if (GetJob(*stub, first.id()).state() != v1::COMPLETED) {
    EXPECT_EQ(waiting.state(), v1::QUEUED);
    EXPECT_TRUE(waiting.slurm_job_id().empty()) << waiting.slurm_job_id();
    EXPECT_EQ(waiting.reason(), "dependency: waiting for job " + first.id() + " to complete");
  }
  const v1::Job first_done = WaitFinished(*stub, first.id());
  const v1::Job second_done = WaitFinished(*stub, second.id());
  ASSERT_EQ(first_done.state(), v1::COMPLETED) << first_done.reason() << "\n" << daemon().Log();
  ASSERT_EQ(second_done.state(), v1::COMPLETED) << second_done.reason();
  EXPECT_GE(second_done.started_time(), first_done.finished_time());
  for (const v1::Job& job : {first_done, second_done}) {
    ASSERT_TRUE(job.has_exit_code()) << job.id();
    EXPECT_EQ(job.exit_code(), 0);
    EXPECT_GT(job.cpu_seconds(), 0) << job.id();
    EXPECT_GT(job.peak_memory_bytes(), 4 << 20) << job.id();
    EXPECT_GT(job.elapsed_seconds(), 0) << job.id();
  }
}

// Every job of this daemon is submitted held (sbatch --hold): Slurm keeps it PENDING, reason
// JobHeldUser, until `scontrol release`.
TEST_F(SlurmExecutor, AJobWaitingInSlurmIsQueuedWithSlurmsReasonUntilSlurmStartsIt) {
  ASSERT_TRUE(StartDaemon({"--slurm-sbatch-options=--hold"})) << daemon().Log();
  auto* stub = this->stub();
  v1::SubmitRequest request;
  request.set_scene(CavityScene(1.0e4));  // runs until cancelled
  request.set_name("held");
  request.set_time_limit_seconds(7 * 60);
  v1::Job job;
  ASSERT_TRUE(stub->Submit(Context().get(), request, &job).ok());
  EXPECT_EQ(job.time_limit_seconds(), 420);
  ASSERT_TRUE(WaitUntil([&] { return GetJob(*stub, job.id()).slurm_reason() == "JobHeldUser"; }))
      << GetJob(*stub, job.id()).ShortDebugString() << "\n"
      << daemon().Log();
  const v1::Job held = GetJob(*stub, job.id());
  EXPECT_EQ(held.state(), v1::QUEUED);
  EXPECT_EQ(held.slurm_state(), "PENDING");
  EXPECT_NE(held.reason().find("Slurm: PENDING"), std::string::npos) << held.reason();
  EXPECT_NE(held.reason().find("JobHeldUser"), std::string::npos) << held.reason();
  EXPECT_EQ(held.started_time(), 0.0);
  const std::string slurm_id = held.slurm_job_id();
  ASSERT_FALSE(slurm_id.empty());
  // The job's time limit is its Slurm job's, in minutes.
  EXPECT_EQ(Shell("scontrol show job " + slurm_id + " | grep -o 'TimeLimit=[0-9:-]*'"),
            "TimeLimit=00:07:00\n");
  // `dlmfd show` says why it waits.
  const std::string command = std::string(DLMFD_BINARY_DIR) + "/client/dlmfd --server " +
                              daemon().address() + " show " + job.id();
  const std::string shown = Shell(command);
  EXPECT_NE(shown.find("state:       queued"), std::string::npos) << shown;
  EXPECT_NE(shown.find("JobHeldUser"), std::string::npos) << shown;
  EXPECT_NE(shown.find("slurm job:   " + slurm_id + " (PENDING, JobHeldUser)"), std::string::npos)
      << shown;
  EXPECT_NE(shown.find("time limit:  7m00s"), std::string::npos) << shown;
  // Another held job is deleted without force, as a queued one: it leaves Slurm's queue.
  v1::Job other;
  ASSERT_TRUE(stub->Submit(Context().get(), request, &other).ok());
  ASSERT_TRUE(WaitUntil([&] { return !GetJob(*stub, other.id()).slurm_job_id().empty(); }));
  const std::string other_slurm_id = GetJob(*stub, other.id()).slurm_job_id();
  v1::DeleteRequest remove;
  remove.add_job_ids(other.id());
  v1::DeleteResponse removed;
  const grpc::Status deleted = stub->Delete(Context().get(), remove, &removed);
  EXPECT_TRUE(deleted.ok()) << deleted.error_message();
  EXPECT_EQ(Shell("squeue -h -j " + other_slurm_id + " -t PD,R -o %T 2>/dev/null"), "");
  // Released, Slurm starts it: RUNNING, from its start in Slurm.
  ASSERT_EQ(std::system(("scontrol release " + slurm_id).c_str()), 0);
  ASSERT_TRUE(WaitUntil([&] { return GetJob(*stub, job.id()).state() == v1::RUNNING; }))
      << daemon().Log();
  const v1::Job running = GetJob(*stub, job.id());
  EXPECT_EQ(running.slurm_state(), "RUNNING");
  EXPECT_EQ(running.reason(), "");
  EXPECT_GT(running.started_time(), held.created_time());
  WaitForProgress(*stub, job.id());
  const v1::Job done = CancelAndWait(*stub, job.id());
  EXPECT_EQ(done.state(), v1::CANCELLED) << done.reason() << "\n" << daemon().Log();
  EXPECT_EQ(done.slurm_state(), "");
}

TEST_F(SlurmExecutor, CancelIsScancelAndTheSolverCheckpoints) {
  ASSERT_TRUE(StartDaemon()) << daemon().Log();
  auto* stub = this->stub();
  const v1::Job job = Submit(*stub, CavityScene(1.0e4));
  WaitForProgress(*stub, job.id());
  const v1::Job done = CancelAndWait(*stub, job.id());
  EXPECT_EQ(done.state(), v1::CANCELLED) << done.reason() << "\n" << daemon().Log();
  EXPECT_GT(done.step(), 0);
  EXPECT_TRUE(fs::exists(done.results_dir() + "/checkpoint.h5"));
  ASSERT_FALSE(done.slurm_job_id().empty());
  // Slurm no longer runs it.
  const std::string state = dir() + "/state.txt";
  const std::string command = "squeue -h -j " + done.slurm_job_id() + " -t R,PD -o %T > " + state;
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(state);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "");
}

TEST_F(SlurmExecutor, ADaemonKilledWithSigkillAdoptsItsSlurmJobOnRestart) {
  ASSERT_TRUE(StartDaemon()) << daemon().Log();
  // 20000 steps, about 7 s: still running when the daemon is killed (2000 steps had sometimes
  // ended by then, and an ended job is not adopted).
  const std::string id = Submit(*stub(), CavityScene(200.0)).id();
  WaitForProgress(*stub(), id);
  const std::string slurm_id = GetJob(*stub(), id).slurm_job_id();
  daemon().Kill(SIGKILL);
  daemon().Wait();
  ASSERT_FALSE(slurm_id.empty());
  ASSERT_TRUE(StartDaemon()) << daemon().Log();
  auto* stub = this->stub();
  const v1::Job done = WaitFinished(*stub, id);
  EXPECT_EQ(done.state(), v1::COMPLETED) << done.reason() << "\n" << daemon().Log();
  EXPECT_EQ(done.slurm_job_id(), slurm_id);  // the same Slurm job: not submitted again
  EXPECT_EQ(done.step(), 20000);
  EXPECT_NE(daemon().Log().find("Slurm job " + slurm_id + " adopted"), std::string::npos)
      << daemon().Log();
  // Slurm ran one job of that name.
  EXPECT_EQ(SlurmEndsOfName("dlmfd-" + id), 1);
}

// The window between sbatch's answer and the store's commit of the id: the daemon is killed, and
// its store (and the job directory) are left as if it had died inside that window. The next
// daemon finds the Slurm job by its name and directory and follows it: no second run.
TEST_F(SlurmExecutor, ADaemonKilledBeforeItStoredTheSlurmIdFollowsTheJobInsteadOfASecondOne) {
  ASSERT_TRUE(StartDaemon()) << daemon().Log();
  // 20000 steps, about 7 s: still running when the next daemon looks for it.
  const v1::Job job = Submit(*stub(), CavityScene(200.0));
  const std::string id = job.id();
  WaitForProgress(*stub(), id);
  const v1::Job running = GetJob(*stub(), id);
  const std::string slurm_id = running.slurm_job_id();
  ASSERT_FALSE(slurm_id.empty());
  daemon().Kill(SIGKILL);
  daemon().Wait();
  ExecuteOnStore(dir() + "/data/jobs.db",
                 "UPDATE slurm_jobs SET slurm_job_id = '', live = 0, attempts = 0 "
                 "WHERE job_id = '" +
                     id + "';",
                 "forgetting the Slurm id");
  fs::remove(fs::path(running.results_dir()).parent_path() / "slurm.id");
  ASSERT_TRUE(StartDaemon()) << daemon().Log();
  auto* stub = this->stub();
  const v1::Job done = WaitFinished(*stub, id);
  EXPECT_EQ(done.state(), v1::COMPLETED) << done.reason() << "\n" << daemon().Log();
  EXPECT_EQ(done.slurm_job_id(), slurm_id);  // the same Slurm job: not submitted again
  EXPECT_EQ(done.step(), 20000);
  EXPECT_NE(daemon().Log().find("Slurm job " + slurm_id + " of this job runs or waits, unrecorded"),
            std::string::npos)
      << daemon().Log();
  EXPECT_EQ(SlurmEndsOfName("dlmfd-" + id), 1);
}

}  // namespace
}  // namespace dlmfd::testing
