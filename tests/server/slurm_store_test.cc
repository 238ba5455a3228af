// The store's schemas 5 and 6, the slurm executor's record of a job (real SQLite): a store of
// schema 4 gains the columns; the Slurm id is stored at submission and read back; a job whose
// Slurm job outlived the daemon (slurm_live) comes first out of the queue, past its study's limit,
// and is neither cancelled while queued nor held; EndAttempt records a Slurm restart (the job
// stays RUNNING) and a requeue after a retryable end (QUEUED again); an end or a retry clears the
// mark. A job that Slurm holds waiting is QUEUED for the API (Get, List's states, a study's
// counts) with Slurm's reason, and RUNNING from its start in Slurm; its own time limit is kept.
// Schema 10 moves the Slurm record to a table of its own: a store written under schema 9 keeps
// every value, and the jobs table has no Slurm column left.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <string>
#include <vector>

#include "job_proto.h"
#include "job_store.h"
#include "support/daemon_process.h"
#include "support/store_fixtures.h"

namespace dlmfd::server {
namespace {

using dlmfd::testing::StoreJob;

TEST(SlurmStore, ASchemaFourStoreGainsTheSlurmColumns) {
  dlmfd::testing::TempDir dir;
  const std::string path = dir.path() + "/jobs.db";
  {
    JobStore store(path);
    store.InsertJobs({StoreJob("old")}, "local", "");
  }
  dlmfd::testing::RollBackSchema(path, 4);
  JobStore store(path);
  EXPECT_EQ(JobStore::SchemaVersion(), 11);
  const auto old = store.Get("old");
  ASSERT_TRUE(old);
  EXPECT_EQ(old->slurm_job_id, "");
  EXPECT_FALSE(old->slurm_live);
  EXPECT_EQ(old->slurm_attempts, 0);
  EXPECT_EQ(old->slurm_state, "");
  EXPECT_FALSE(old->slurm_waiting);
  EXPECT_EQ(old->time_limit_seconds, 0);
  EXPECT_TRUE(old->numerics.empty());  // schema 7's column, empty for a job admitted before it
  store.SetSlurmSubmitted("old", "77");
  EXPECT_EQ(store.Get("old")->slurm_job_id, "77");
}

TEST(SlurmStore, ALiveSlurmJobIsAdoptedFirstAndNeitherCancelledNorHeldWhileQueued) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  const StudyRecord study = dlmfd::testing::StoreStudy("s-1", 1);
  store.InsertJobs({StoreJob("a", "s-1"), StoreJob("b", "s-1"), StoreJob("c", "", 9)}, "local", "",
                   &study);
  // a and b were both in Slurm (an array with throttle 1 holds b back in Slurm, not here).
  for (const char* id : {"a", "b"}) {
    store.MarkRunning(id, 1.0);
  }
  store.SetSlurmSubmitted("a", "40_0");
  store.SetSlurmSubmitted("b", "40_1");
  // The daemon died; its next start queues its RUNNING jobs again.
  EXPECT_EQ(store.RequeueRunning(2.0).size(), 2u);
  const auto b = store.Get("b");
  EXPECT_EQ(b->state, JobState::kQueued);
  EXPECT_TRUE(b->slurm_live);
  EXPECT_EQ(b->slurm_job_id, "40_1");
  EXPECT_FALSE(store.CancelQueued("b", "cancelled", 3.0));  // Slurm still runs it
  EXPECT_FALSE(store.SetHeld("b", true));
  // Both live jobs come before c (priority 9), and the study's max_running = 1 holds neither.
  auto next = store.NextQueued();
  ASSERT_TRUE(next);
  EXPECT_EQ(next->id, "a");
  store.MarkRunning("a", 3.0);
  next = store.NextQueued();
  ASSERT_TRUE(next);
  EXPECT_EQ(next->id, "b");
  store.MarkRunning("b", 3.0);
  EXPECT_EQ(store.NextQueued()->id, "c");
  // Only jobs not in Slurm's hands form a study's next array.
  EXPECT_TRUE(store.QueuedOfStudy("s-1", 10).empty());
  EXPECT_EQ(store.CountRunningOfStudy("s-1"), 2);
  // An end clears the mark.
  ASSERT_TRUE(store.MarkFinished("a", JobState::kCompleted, "", 4.0));
  EXPECT_FALSE(store.Get("a")->slurm_live);
  EXPECT_EQ(store.Get("a")->slurm_job_id, "40_0");  // kept for `dlmfd show`
}

TEST(SlurmStore, AttemptsEndWithoutEndingTheJob) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  store.InsertJobs({StoreJob("a")}, "local", "");
  store.MarkRunning("a", 10.0);
  store.SetSlurmSubmitted("a", "51");
  store.UpdateProgress("a", 7, 0.07, 1.0);
  // Slurm ran the same job again (scontrol requeue): still RUNNING, attempt 2.
  AttemptEnd restart;
  restart.state = JobState::kCancelled;
  restart.reason = "Slurm requeued job 51 (restart 1)";
  restart.when = 20.0;
  restart.slurm_restarts = 1;
  store.EndAttempt("a", restart);
  auto a = store.Get("a");
  EXPECT_EQ(a->state, JobState::kRunning);
  EXPECT_EQ(a->attempt, 2);
  EXPECT_TRUE(a->slurm_live);
  EXPECT_EQ(a->slurm_restarts, 1);
  EXPECT_EQ(a->slurm_attempts, 2);
  EXPECT_EQ(a->started_time, 20.0);
  ASSERT_EQ(a->previous_attempts.size(), 1u);
  EXPECT_EQ(a->previous_attempts[0].attempt, 1);
  EXPECT_EQ(a->previous_attempts[0].reason, restart.reason);
  EXPECT_EQ(a->previous_attempts[0].step, 7);
  // A TIMEOUT that the daemon requeues: QUEUED, attempt 3, no longer live, the progress kept
  // (it resumes from the checkpoint).
  AttemptEnd timeout;
  timeout.state = JobState::kFailed;
  timeout.reason = "Slurm: TIMEOUT";
  timeout.when = 30.0;
  store.EndAttempt("a", timeout);
  a = store.Get("a");
  EXPECT_EQ(a->state, JobState::kQueued);
  EXPECT_EQ(a->reason, "Slurm: TIMEOUT");
  EXPECT_EQ(a->attempt, 3);
  EXPECT_FALSE(a->slurm_live);
  EXPECT_EQ(a->step, 7);
  ASSERT_EQ(a->previous_attempts.size(), 2u);
  EXPECT_EQ(a->previous_attempts[1].state, JobState::kFailed);
  EXPECT_THROW(store.EndAttempt("a", timeout), StoreError);  // not RUNNING
  // A user's retry starts the count of Slurm attempts again.
  store.MarkRunning("a", 40.0);
  store.SetSlurmSubmitted("a", "60");
  EXPECT_EQ(store.Get("a")->slurm_attempts, 3);
  ASSERT_TRUE(store.MarkFinished("a", JobState::kFailed, "x", 50.0));
  RequeueChange retry;
  retry.id = "a";
  retry.end_time = 1.0;
  store.Requeue({retry});
  a = store.Get("a");
  EXPECT_EQ(a->slurm_attempts, 0);
  EXPECT_FALSE(a->slurm_live);
}

TEST(SlurmStore, AJobWaitingInSlurmIsQueuedWithSlurmsReasonUntilSlurmStartsIt) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  const StudyRecord study = dlmfd::testing::StoreStudy("s-1", 1);
  JobRecord limited = StoreJob("a", "s-1");
  limited.time_limit_seconds = 5400;
  store.InsertJobs({limited, StoreJob("b", "s-1")}, "local", "", &study);
  EXPECT_EQ(store.Get("a")->time_limit_seconds, 5400);
  for (const char* id : {"a", "b"}) store.MarkRunning(id, 10.0);
  store.SetSlurmSubmitted("a", "40_0");
  store.SetSlurmSubmitted("b", "40_1");
  // Submitted: waiting in Slurm until squeue says otherwise.
  EXPECT_EQ(ShownState(*store.Get("a")), JobState::kQueued);
  // Slurm runs a and holds b back by the array's throttle.
  EXPECT_TRUE(store.SetSlurmState("a", "RUNNING", "", false, 12.0));
  EXPECT_TRUE(store.SetSlurmState("b", "PENDING", "JobArrayTaskLimit", true, 12.0));
  EXPECT_FALSE(store.SetSlurmState("b", "PENDING", "JobArrayTaskLimit", true, 13.0));  // the same
  const JobRecord b = *store.Get("b");
  EXPECT_EQ(b.state, JobState::kRunning);  // in the executor's hands: the scheduler's count
  EXPECT_EQ(ShownState(b), JobState::kQueued);
  const v1::Job shown = ToProto(b, 15.0);
  EXPECT_EQ(shown.state(), v1::QUEUED);
  EXPECT_EQ(shown.slurm_state(), "PENDING");
  EXPECT_EQ(shown.slurm_reason(), "JobArrayTaskLimit");
  EXPECT_EQ(shown.started_time(), 0.0);
  EXPECT_EQ(shown.elapsed_seconds(), 0.0);  // no start shown, no time counted
  EXPECT_NE(shown.reason().find("Slurm: PENDING"), std::string::npos) << shown.reason();
  EXPECT_NE(shown.reason().find("JobArrayTaskLimit"), std::string::npos) << shown.reason();
  const v1::Job running = ToProto(*store.Get("a"), 15.0);
  EXPECT_EQ(running.state(), v1::RUNNING);
  EXPECT_EQ(running.reason(), "");
  EXPECT_EQ(running.started_time(), 12.0);  // Slurm started it
  EXPECT_EQ(running.elapsed_seconds(), 3.0);
  EXPECT_EQ(running.time_limit_seconds(), 5400);
  // List's states and the study's counts go by the shown state; the scheduler's by the stored.
  ListFilter queued;
  queued.owner = "local";
  queued.states = {JobState::kQueued};
  const auto listed = store.List(queued);
  ASSERT_EQ(listed.size(), 1u);
  EXPECT_EQ(listed[0].id, "b");
  ListFilter running_filter = queued;
  running_filter.states = {JobState::kRunning};
  ASSERT_EQ(store.List(running_filter).size(), 1u);
  EXPECT_EQ(store.List(running_filter)[0].id, "a");
  const StudyStats stats = store.StatsOfStudy("local", "s-1");
  EXPECT_EQ(stats.count[static_cast<size_t>(JobState::kQueued)], 1);
  EXPECT_EQ(stats.count[static_cast<size_t>(JobState::kRunning)], 1);
  EXPECT_EQ(stats.first_started_time, 12.0);
  EXPECT_EQ(store.CountRunningOfStudy("s-1"), 2);
  // Slurm starts b: RUNNING from then.
  EXPECT_TRUE(store.SetSlurmState("b", "RUNNING", "", false, 20.0));
  EXPECT_EQ(ToProto(*store.Get("b"), 20.0).state(), v1::RUNNING);
  EXPECT_EQ(store.Get("b")->started_time, 20.0);
  // An end clears Slurm's word.
  ASSERT_TRUE(store.MarkFinished("b", JobState::kCompleted, "", 30.0));
  EXPECT_EQ(store.Get("b")->slurm_state, "");
  EXPECT_FALSE(store.SetSlurmState("b", "COMPLETING", "", false, 31.0));  // not RUNNING
}

// The names of the columns of `table` and the number of its rows, read by SQLite directly.
struct TableShape {
  std::vector<std::string> columns;
  int64_t rows = 0;
};
TableShape ShapeOf(const std::string& path, const std::string& table) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  TableShape shape;
  sqlite3_stmt* info = nullptr;
  EXPECT_EQ(
      sqlite3_prepare_v2(db, ("PRAGMA table_info(" + table + ")").c_str(), -1, &info, nullptr),
      SQLITE_OK);
  while (sqlite3_step(info) == SQLITE_ROW) {
    shape.columns.emplace_back(reinterpret_cast<const char*>(sqlite3_column_text(info, 1)));
  }
  sqlite3_finalize(info);
  sqlite3_stmt* count = nullptr;
  EXPECT_EQ(sqlite3_prepare_v2(db, ("SELECT COUNT(*) FROM " + table).c_str(), -1, &count, nullptr),
            SQLITE_OK);
  if (sqlite3_step(count) == SQLITE_ROW) shape.rows = sqlite3_column_int64(count, 0);
  sqlite3_finalize(count);
  sqlite3_close(db);
  return shape;
}

TEST(SlurmStore, ASchemaNineStoreMovesItsSlurmRecordsToTheirOwnTable) {
  dlmfd::testing::TempDir dir;
  const std::string path = dir.path() + "/jobs.db";
  {
    JobStore store(path);
    store.InsertJobs({StoreJob("waiting"), StoreJob("ended"), StoreJob("local")}, "local", "");
  }
  // As the daemon of schema 9 left it: a job Slurm holds waiting after a restart of its array
  // task, one whose Slurm job ended, and one the local executor ran.
  dlmfd::testing::RollBackSchema(path, 9);
  const std::string running = std::to_string(static_cast<int>(JobState::kRunning));
  const std::string completed = std::to_string(static_cast<int>(JobState::kCompleted));
  dlmfd::testing::ExecuteOnStore(
      path,
      "UPDATE jobs SET state = " + running +
          ", slurm_job_id = '40_1', slurm_live = 1, slurm_attempts = 2, slurm_restarts = 1, "
          "slurm_state = 'PENDING', slurm_reason = 'BeginTime', slurm_waiting = 1 "
          "WHERE id = 'waiting';"
          "UPDATE jobs SET state = " +
          completed +
          ", slurm_job_id = '41', slurm_attempts = 1 WHERE id = 'ended';"
          "UPDATE jobs SET state = " +
          completed + ", started_time = 5 WHERE id = 'local';",
      "writing schema 9's Slurm columns");
  ASSERT_EQ(ShapeOf(path, "jobs").columns.size(), 41u);
  JobStore store(path);
  // The jobs table keeps no Slurm column; the two Slurm jobs have a row each.
  for (const std::string& column : ShapeOf(path, "jobs").columns) {
    EXPECT_EQ(column.rfind("slurm_", 0), std::string::npos) << column;
  }
  EXPECT_EQ(ShapeOf(path, "jobs").columns.size(), 34u);
  EXPECT_EQ(ShapeOf(path, "slurm_jobs").rows, 2);
  const JobRecord waiting = *store.Get("waiting");
  EXPECT_EQ(waiting.slurm_job_id, "40_1");
  EXPECT_TRUE(waiting.slurm_live);
  EXPECT_EQ(waiting.slurm_attempts, 2);
  EXPECT_EQ(waiting.slurm_restarts, 1);
  EXPECT_EQ(waiting.slurm_state, "PENDING");
  EXPECT_EQ(waiting.slurm_reason, "BeginTime");
  EXPECT_TRUE(waiting.slurm_waiting);
  EXPECT_EQ(ShownState(waiting), JobState::kQueued);
  const JobRecord ended = *store.Get("ended");
  EXPECT_EQ(ended.slurm_job_id, "41");
  EXPECT_FALSE(ended.slurm_live);
  EXPECT_EQ(ended.slurm_attempts, 1);
  const JobRecord local = *store.Get("local");
  EXPECT_EQ(local.slurm_job_id, "");
  EXPECT_EQ(local.slurm_attempts, 0);
  EXPECT_EQ(local.started_time, 5.0);
  // The moved record works on: Slurm starts the waiting job, its end is recorded, a deleted job
  // takes its Slurm row with it.
  EXPECT_TRUE(store.SetSlurmState("waiting", "RUNNING", "", false, 60.0));
  EXPECT_EQ(store.Get("waiting")->started_time, 60.0);
  EXPECT_EQ(ShownState(*store.Get("waiting")), JobState::kRunning);
  ASSERT_TRUE(store.MarkFinished("waiting", JobState::kCompleted, "", 70.0));
  EXPECT_FALSE(store.Get("waiting")->slurm_live);
  EXPECT_EQ(store.Get("waiting")->slurm_job_id, "40_1");
  store.Delete({"ended"});
  EXPECT_EQ(ShapeOf(path, "slurm_jobs").rows, 1);
}

}  // namespace
}  // namespace dlmfd::server
