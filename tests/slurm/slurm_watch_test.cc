// Issue 38 under the slurm executor (scripts/slurm-dev.sh start): watchers of a study that goes to
// Slurm as one throttled array reconnect with the last number they saw while the daemon is killed
// with SIGKILL twice (the next daemon adopts the Slurm jobs and reads their event files on from
// where the log says it stopped): each gets every event once, in order. A point that Slurm's
// throttle holds back is shown QUEUED until Slurm runs it, never RUNNING first, and adoptions are
// no solver starts.
#include <gtest/gtest.h>
#include <signal.h>

#include <memory>
#include <string>
#include <vector>

#include "../server/support/watch_recorder.h"
#include "slurm_harness.h"

namespace dlmfd::testing {
namespace {

class SlurmWatch : public SlurmTest {};

// About 3 s of one core a run (h = 1/64, 1600 steps), so the third point waits several of the
// daemon's 1 s polls of squeue; at h = 1/32 a run took 0.8 s and a poll could miss the wait.
std::string SettlingDisk() {
  return "title = \"a disk settling in a closed box\"\n"
         "[domain]\nsize = [1.0, 2.0]\nh = 0.015625\n"
         "[fluid]\ndensity = 1.0\nviscosity = 0.1\ngravity = [0.0, -10.0]\n"
         "[time]\ndt = 0.0025\nend = 4.0\n"
         "[[particles]]\ncenter = [0.5, 1.5]\ndiameter = 0.25\ndensity = 1.5\n"
         "[output]\nfields_every = 0.5\nparticles_every = 0.02\ncheckpoint_every = 0.5\n";
}

TEST_F(SlurmWatch, EveryWatcherGetsEveryEventOnceThroughDaemonKills) {
  ASSERT_TRUE(StartDaemon({"--watcher-buffer", "16"})) << daemon().Log();
  const std::string address = daemon().address();
  std::vector<std::string> jobs;
  {
    v1::SubmitStudyRequest request;
    request.set_scene(SettlingDisk());
    request.set_name("settling");
    request.set_max_running(2);  // the array's throttle holds the third point back
    auto* axis = request.add_axes();
    axis->set_key("particles.0.density");
    for (const char* value : {"1.5", "1.8", "2.1"}) axis->add_values(value);
    v1::SubmitStudyResponse response;
    ASSERT_TRUE(stub()->SubmitStudy(Context().get(), request, &response).ok());
    for (const auto& job : response.jobs()) jobs.push_back(job.id());
  }
  Watchers watchers = WatchersOf(address, jobs);
  auto seen = [&] { return EventsSeen(watchers); };
  for (int k = 0; k < 2; ++k) {
    const size_t before = seen();
    WaitUntil([&] { return seen() >= before + 20; }, std::chrono::seconds(60));
    daemon().Kill(SIGKILL);
    daemon().Wait();
    ASSERT_TRUE(StartDaemon({"--watcher-buffer", "16"}, address)) << daemon().Log();
  }
  for (auto& w : watchers) w->Join();
  int adopted = 0, throttled = 0;
  for (const std::string& id : jobs) {
    const v1::Job job = WaitFinished(*stub(), id);
    EXPECT_EQ(job.state(), v1::COMPLETED) << job.reason() << "\n" << daemon().Log();
    EXPECT_EQ(job.attempts(), 1) << id << ": an adoption counted as a solver start";
    const std::vector<v1::WatchEvent> reference = ReferenceEvents(*stub(), id);
    ASSERT_FALSE(reference.empty());
    EXPECT_EQ(job.last_seq(), reference.back().seq());
    int progress = 0, particles = 0;
    bool running = false;
    for (const auto& e : reference) {
      progress += e.has_progress();
      particles += e.has_particles();
      adopted += e.has_log() && e.log().text().find(" adopted") != std::string::npos;
      // Held back by Slurm while the others ran: the array's throttle, or the node's two CPUs
      // (squeue gives one reason; which one depends on Slurm's scheduling pass).
      throttled += e.has_state() && e.state().state() == v1::QUEUED &&
                   (e.state().reason().find("JobArrayTaskLimit") != std::string::npos ||
                    e.state().reason().find("(Resources") != std::string::npos);
      if (!e.has_state()) continue;
      // Shown QUEUED while Slurm holds it, RUNNING once it runs, and not QUEUED again.
      if (e.state().state() == v1::RUNNING) running = true;
      if (running) {
        EXPECT_NE(e.state().state(), v1::QUEUED) << id << ": " << e.DebugString();
      }
    }
    EXPECT_TRUE(running) << id;
    EXPECT_GT(progress, 0) << id;
    EXPECT_GT(particles, 100) << id;  // 200 samples, and the initial state
    ExpectExactlyOnce(reference, watchers, id);
  }
  EXPECT_GT(adopted, 0) << "no kill came while a Slurm job ran";
  EXPECT_GT(throttled, 0) << "no point was shown waiting for the array's throttle or the node";
  EXPECT_GT(Reconnected(watchers), 0u);
}

}  // namespace
}  // namespace dlmfd::testing
