// Issue 38, "streams exactly once": watchers of a study reconnect with the last number they saw
// while the daemon is killed with SIGKILL again and again (its solvers die with it and resume from
// their checkpoints); each must receive every later event once, in order, equal to what a reader
// of the finished job gets, and no particle state or progress of a step already sent.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "support/daemon_process.h"
#include "support/watch_recorder.h"

namespace dlmfd::testing {
namespace {

// A disk settling in a closed box: 32 x 64 cells, 1000 steps, particle states every 4 steps, a
// checkpoint every 20 (so that each restart resumes and runs some steps again).
std::string SettlingDisk() {
  return "title = \"a disk settling in a closed box\"\n"
         "[domain]\nsize = [1.0, 2.0]\nh = 0.03125\n"
         "[fluid]\ndensity = 1.0\nviscosity = 0.1\ngravity = [0.0, -10.0]\n"
         "[time]\ndt = 0.005\nend = 5.0\n"
         "[[particles]]\ncenter = [0.5, 1.5]\ndiameter = 0.25\ndensity = 1.5\n"
         "[output]\nfields_every = 0.25\nparticles_every = 0.02\ncheckpoint_every = 0.1\n";
}

TEST(WatchExactlyOnce, EveryWatcherGetsEveryEventOnceThroughDaemonKills) {
  REQUIRE_SOLVER();
  TempDir dir;
  const std::string data = dir.path() + "/data";
  // A small buffer per watcher: a watcher that falls behind reads the rest from the log.
  const std::vector<std::string> flags = {"--max-concurrent", "2", "--watcher-buffer", "16"};
  auto daemon = std::make_unique<DaemonProcess>(data, flags);
  ASSERT_TRUE(daemon->Start()) << daemon->Log();
  const std::string address = daemon->address();
  std::vector<std::string> jobs;
  {
    auto stub = daemon->Stub();
    v1::SubmitStudyRequest request;
    request.set_scene(SettlingDisk());
    request.set_name("settling");
    auto* axis = request.add_axes();
    axis->set_key("particles.0.density");
    axis->add_values("1.5");
    axis->add_values("1.8");
    v1::SubmitStudyResponse response;
    auto context = Context();
    ASSERT_TRUE(stub->SubmitStudy(context.get(), request, &response).ok());
    for (const auto& job : response.jobs()) jobs.push_back(job.id());
  }
  Watchers watchers = WatchersOf(address, jobs);
  auto seen = [&] { return EventsSeen(watchers); };
  // Three kills, each once the watchers have seen some more events (or after 20 s).
  int kills = 0;
  for (int k = 0; k < 3; ++k) {
    const size_t before = seen();
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (seen() < before + 40 && std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    daemon->Kill(SIGKILL);
    daemon->Wait();
    ++kills;
    daemon = std::make_unique<DaemonProcess>(data, flags, address);
    ASSERT_TRUE(daemon->Start()) << daemon->Log();
    // A late watcher from the start joins after the first kill.
    if (k == 0) watchers.push_back(std::make_unique<ReconnectingWatcher>(address, jobs[0], false));
  }
  for (auto& w : watchers) w->Join();
  auto stub = daemon->Stub();
  int resumed = 0;
  for (const std::string& id : jobs) {
    const v1::Job job = WaitFinished(*stub, id);
    EXPECT_EQ(job.state(), v1::COMPLETED) << job.reason();
    EXPECT_GT(job.attempts(), 1) << id << ": no kill came while it ran";
    const std::vector<v1::WatchEvent> reference = ReferenceEvents(*stub, id);
    ASSERT_FALSE(reference.empty());
    EXPECT_EQ(job.last_seq(), reference.back().seq());
    EXPECT_TRUE(reference.back().has_state());
    for (const auto& e : reference) {
      resumed += e.has_log() && e.log().text() == "solver resumed from results/checkpoint.h5";
    }
    ExpectExactlyOnce(reference, watchers, id);
    // A watch of the finished job from a number in the middle: the rest of the events, once.
    const int64_t middle = job.last_seq() / 2;
    ReconnectingWatcher late(address, id, false, middle);
    late.Join();
    ExpectExactlyOnce(reference, late);
    EXPECT_EQ(late.Connections(), 1);
  }
  EXPECT_EQ(kills, 3);
  EXPECT_GT(resumed, 0) << "no solver resumed from a checkpoint";
  EXPECT_GT(Reconnected(watchers), 0u) << "no watcher saw a kill";
}

}  // namespace
}  // namespace dlmfd::testing
