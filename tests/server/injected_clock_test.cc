// The service's time is injected (server/src/clock.h; issue 39 point 3): with a ManualClock a test
// sets the time instead of waiting for it. A job's wall-time limit of an hour is reached at an
// hour of the clock and not a moment before, in no real time; the events and the summary a
// watcher gets are stamped with the hub's clock, and a running job's elapsed time counts to it.
#include <gtest/gtest.h>

#include <future>
#include <memory>
#include <string>

#include "event_hub.h"
#include "job_proto.h"
#include "job_store.h"
#include "support/daemon_process.h"
#include "support/manual_clock.h"
#include "support/store_fixtures.h"
#include "wall_time_limit.h"
#include "watcher_queue.h"

namespace dlmfd::server {
namespace {

using dlmfd::testing::ManualClock;

TEST(InjectedClock, AnHoursWallTimeLimitIsReachedAtAnHourOfTheClockAndNotBefore) {
  ManualClock clock;
  {
    WallTimeLimit limit(
        3600, [] { ADD_FAILURE() << "over the limit before an hour"; }, clock);
    clock.Advance(3599.5);
    EXPECT_FALSE(limit.End());
  }
  std::promise<void> over;
  std::future<void> reached = over.get_future();
  WallTimeLimit limit(
      3600, [&] { over.set_value(); }, clock);
  clock.Advance(3600.0);
  reached.wait();  // the limit's thread saw the clock: no real hour passes
  EXPECT_TRUE(limit.End());
}

TEST(InjectedClock, WatchEventsAndElapsedTimesFollowTheHubsClock) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  ManualClock clock(2.0e9);
  store.InsertJobs({dlmfd::testing::StoreJob("a")}, "local", "");
  store.MarkRunning("a", clock.Now());
  EventHub hub(
      store, [&](const std::string& id) { return dir.path() + "/jobs/" + id; }, clock);
  auto queue = std::make_shared<WatcherQueue>(WatchOptions{}, hub.LogDirectory("a"));
  queue->SetWake([] {});
  hub.Attach(*store.Get("a"), 0, queue);
  clock.Advance(90.0);
  hub.PublishState(*store.Get("a"));
  v1::WatchEvent progress;
  progress.mutable_progress()->set_step(1);
  clock.Advance(10.0);
  ASSERT_TRUE(hub.Publish("a", progress));
  v1::WatchEvent out;
  ASSERT_EQ(queue->Pop(&out), WatcherQueue::Next::kEvent);  // the summary on attach
  EXPECT_EQ(out.wall_time(), 2.0e9);
  ASSERT_EQ(queue->Pop(&out), WatcherQueue::Next::kEvent);
  ASSERT_TRUE(out.has_state()) << out.DebugString();
  EXPECT_EQ(out.wall_time(), 2.0e9 + 90.0);
  EXPECT_EQ(out.state().job().elapsed_seconds(), 90.0);
  ASSERT_EQ(queue->Pop(&out), WatcherQueue::Next::kEvent);
  EXPECT_TRUE(out.has_progress());
  EXPECT_EQ(out.wall_time(), 2.0e9 + 100.0);
  // A finished job's elapsed time is its run's, whatever the clock says.
  ASSERT_TRUE(store.MarkFinished("a", JobState::kCompleted, "", clock.Now()));
  clock.Advance(1000.0);
  EXPECT_EQ(ToProto(*store.Get("a"), clock.Now()).elapsed_seconds(), 100.0);
}

}  // namespace
}  // namespace dlmfd::server
