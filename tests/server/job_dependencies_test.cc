// Job dependencies (issue 38: Slurm's --dependency=afterok): the store's schema 8 over an existing
// store of schema 7, and the real daemon on loopback (its SQLite store, the real solver): a job
// after another starts only once that one COMPLETED; a dependency that ends CANCELLED or FAILED
// cancels its dependants, and theirs in turn; Submit refuses what could never run.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "job_store.h"
#include "support/daemon_process.h"
#include "support/store_fixtures.h"

namespace dlmfd::testing {
namespace {
using grpc::StatusCode;
using server::JobRecord;
using server::JobState;
using server::JobStore;

grpc::Status SubmitAfter(v1::Jobs::Stub& stub, const std::string& scene,
                         const std::vector<std::string>& after, v1::Job* job) {
  v1::SubmitRequest request;
  request.set_scene(scene);
  for (const auto& id : after) request.add_after(id);
  auto context = Context();
  return stub.Submit(context.get(), request, job);
}

TEST(JobStoreSchemaEight, DependenciesOverAnExistingStore) {
  TempDir dir;
  const std::string path = dir.path() + "/jobs.db";
  {
    JobStore store(path);
    store.InsertJobs({StoreJob("old")}, "local", "");
  }
  RollBackSchema(path, JobStore::SchemaVersion() - 1);  // as the daemon before left it
  JobStore store(path);
  ASSERT_TRUE(store.Get("old"));
  EXPECT_TRUE(store.Get("old")->after.empty());

  JobRecord second = StoreJob("second", "", 5);  // a higher priority than old's
  second.after = {"old"};
  JobRecord third = StoreJob("third", "", 9);
  third.after = {"second", "old"};
  store.InsertJobs({second, third}, "local", "");
  EXPECT_EQ(store.Get("third")->after, (std::vector<std::string>{"second", "old"}));
  EXPECT_EQ(store.Get("second")->reason, "dependency: waiting for job old to complete");

  // Only old may start, whatever the priorities.
  ASSERT_EQ(store.NextQueued()->id, "old");
  store.MarkRunning("old", 1.0);
  EXPECT_FALSE(store.NextQueued());
  ASSERT_TRUE(store.MarkFinished("old", JobState::kCompleted, "", 2.0));
  ASSERT_EQ(store.NextQueued()->id, "second");
  EXPECT_TRUE(store.Blocked().empty());
  store.MarkRunning("second", 3.0);
  ASSERT_TRUE(store.MarkFinished("second", JobState::kFailed, "diverged", 4.0));
  EXPECT_FALSE(store.NextQueued());
  const auto blocked = store.Blocked();
  ASSERT_EQ(blocked.size(), 1u);
  EXPECT_EQ(blocked[0].first, "third");
  EXPECT_EQ(blocked[0].second, "dependency second failed (FAILED)");

  // A deleted dependency blocks for good too.
  JobRecord orphan = StoreJob("orphan");
  orphan.after = {"gone"};
  store.InsertJobs({StoreJob("gone"), orphan}, "local", "");
  store.Delete({"gone"});
  const auto after_delete = store.Blocked();
  ASSERT_EQ(after_delete.size(), 2u);
  EXPECT_EQ(after_delete[1].first, "orphan");
  EXPECT_EQ(after_delete[1].second, "dependency gone was deleted");
}

// afterok on the real daemon with room for every job at once: the dependant still waits.
TEST(JobDependencies, RunsAfterCompletionAndCancelledWhenADependencyFails) {
  if (!SolverAvailable()) GTEST_SKIP() << "dlmfd-solve is not built: " << kSolverPath;
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", {"--max-concurrent", "4"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();

  v1::Job first, second;
  ASSERT_TRUE(SubmitAfter(*stub, CavityScene(0.3), {}, &first).ok());
  ASSERT_TRUE(SubmitAfter(*stub, CavityScene(0.05), {first.id(), first.id()}, &second).ok());
  ASSERT_EQ(second.after_size(), 1);  // once
  EXPECT_EQ(second.after(0), first.id());
  const v1::Job done_first = WaitFinished(*stub, first.id());
  const v1::Job done_second = WaitFinished(*stub, second.id());
  ASSERT_EQ(done_first.state(), v1::COMPLETED);
  ASSERT_EQ(done_second.state(), v1::COMPLETED) << done_second.reason();
  EXPECT_GE(done_second.started_time(), done_first.finished_time());

  // A chain behind a long job: cancelling it cancels both, each naming its own dependency.
  v1::Job blocker, middle, last;
  ASSERT_TRUE(SubmitAfter(*stub, CavityScene(10000.0), {}, &blocker).ok());
  ASSERT_TRUE(SubmitAfter(*stub, CavityScene(0.05), {blocker.id()}, &middle).ok());
  ASSERT_TRUE(SubmitAfter(*stub, CavityScene(0.05), {middle.id(), second.id()}, &last).ok());
  EXPECT_EQ(GetJob(*stub, middle.id()).reason(),
            "dependency: waiting for job " + blocker.id() + " to complete");
  EXPECT_EQ(GetJob(*stub, last.id()).state(), v1::QUEUED);
  v1::CancelRequest cancel;
  cancel.set_job_id(blocker.id());
  v1::Job cancelled;
  {
    auto context = Context();
    ASSERT_TRUE(stub->Cancel(context.get(), cancel, &cancelled).ok());
  }
  ASSERT_EQ(WaitFinished(*stub, blocker.id()).state(), v1::CANCELLED);
  const v1::Job middle_end = WaitFinished(*stub, middle.id());
  EXPECT_EQ(middle_end.state(), v1::CANCELLED);
  EXPECT_EQ(middle_end.reason(), "dependency " + blocker.id() + " failed (CANCELLED)");
  EXPECT_EQ(middle_end.started_time(), 0);  // never ran
  const v1::Job last_end = WaitFinished(*stub, last.id());
  EXPECT_EQ(last_end.state(), v1::CANCELLED);
  EXPECT_EQ(last_end.reason(), "dependency " + middle.id() + " failed (CANCELLED)");

  // What could never run is refused at once, naming the field.
  v1::Job refused;
  grpc::Status status = SubmitAfter(*stub, CavityScene(0.05), {middle.id()}, &refused);
  EXPECT_EQ(status.error_code(), StatusCode::FAILED_PRECONDITION);
  EXPECT_NE(status.error_message().find("after: job " + middle.id() + " has ended CANCELLED"),
            std::string::npos)
      << status.error_message();
  status = SubmitAfter(*stub, CavityScene(0.05), {"j-no-such-job"}, &refused);
  EXPECT_EQ(status.error_code(), StatusCode::NOT_FOUND) << status.error_message();
  status = SubmitAfter(*stub, CavityScene(0.05), {""}, &refused);
  EXPECT_EQ(status.error_code(), StatusCode::INVALID_ARGUMENT) << status.error_message();
  daemon.Kill(SIGTERM);
  EXPECT_EQ(daemon.Wait(), 0) << daemon.Log();
}

}  // namespace
}  // namespace dlmfd::testing
