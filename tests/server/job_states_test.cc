// The job-state table (job_states.h) and the store that is built from it (real SQLite): the
// allowed transitions, written out once more by hand, and a store that refuses the others.
#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "job_states.h"
#include "job_store.h"
#include "support/daemon_process.h"
#include "support/store_fixtures.h"

namespace dlmfd::server {
namespace {

using dlmfd::testing::StoreJob;
using S = JobState;

TEST(JobStates, TheTableAllowsExactlyTheDocumentedTransitions) {
  const std::set<std::pair<S, S>> allowed = {
      {S::kQueued, S::kRunning},    {S::kQueued, S::kCompleted}, {S::kQueued, S::kFailed},
      {S::kQueued, S::kCancelled},  {S::kRunning, S::kQueued},   {S::kRunning, S::kRunning},
      {S::kRunning, S::kCompleted}, {S::kRunning, S::kFailed},   {S::kRunning, S::kCancelled},
      {S::kCompleted, S::kQueued},  {S::kFailed, S::kQueued},    {S::kCancelled, S::kQueued},
  };
  for (const auto& from : kJobStates) {
    for (const auto& to : kJobStates) {
      EXPECT_EQ(TransitionAllowed(from.state, to.state), allowed.count({from.state, to.state}) > 0)
          << from.name << " -> " << to.name;
    }
  }
  EXPECT_EQ(JobStatesBefore(JobTransition::kFinish), "(1, 2)");
  EXPECT_EQ(JobStatesBefore(JobTransition::kRetry), "(3, 4, 5)");
  EXPECT_TRUE(IsFinished(S::kCancelled));
  EXPECT_FALSE(IsFinished(S::kRunning));
  EXPECT_STREQ(JobStateName(S::kFailed), "FAILED");
  EXPECT_THROW(CheckTransition(JobTransition::kFinish, S::kQueued), std::logic_error);
}

TEST(JobStates, TheStoreRefusesWhatTheTableDoesNotAllow) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  store.InsertJobs({StoreJob("a"), StoreJob("b")}, "local", "");
  store.MarkRunning("a", 1);
  ASSERT_TRUE(store.MarkFinished("a", S::kCompleted, "", 1));
  // Finished: it neither starts, nor ends again, nor is cancelled as queued (a retry queues it).
  EXPECT_THROW(store.MarkRunning("a", 2), StoreError);
  EXPECT_FALSE(store.MarkFinished("a", S::kFailed, "again", 2));
  EXPECT_FALSE(store.CancelQueued("a", "cancelled", 2));
  EXPECT_THROW(store.EndAttempt("a", AttemptEnd{}), StoreError);
  EXPECT_EQ(store.Get("a")->state, S::kCompleted);
  // Queued: no attempt of it can end; it starts once, and then is no longer cancelled as queued.
  EXPECT_THROW(store.EndAttempt("b", AttemptEnd{}), StoreError);
  store.MarkRunning("b", 3);
  EXPECT_THROW(store.MarkRunning("b", 3), StoreError);
  EXPECT_FALSE(store.CancelQueued("b", "cancelled", 3));
  EXPECT_EQ(store.Get("b")->state, S::kRunning);
  EXPECT_THROW(store.MarkFinished("b", S::kRunning, "", 4), std::logic_error);
}

}  // namespace
}  // namespace dlmfd::server
