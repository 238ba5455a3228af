// Accounting and usage against the real daemon on loopback (its SQLite store, the real solver):
// each job's exit status, CPU time, peak memory and elapsed time (sacct's ExitCode, TotalCPU,
// MaxRSS, Elapsed; issue 38), the store's schema 9 over an existing store, and GetUsage: a
// user's disk against the quota and jobs per state, another user's jobs not counted.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "dlmfd/solver/exit_codes.h"
#include "job_store.h"
#include "support/daemon_process.h"
#include "support/store_fixtures.h"

namespace dlmfd::testing {
namespace {
using server::JobState;
using server::JobStore;

v1::Usage UsageOf(v1::Jobs::Stub& stub, const std::string& token) {
  auto context = Context(token);
  v1::Usage usage;
  const grpc::Status status = stub.GetUsage(context.get(), v1::GetUsageRequest(), &usage);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return usage;
}

TEST(JobStoreSchemaNine, AccountingOverAnExistingStoreAndClearedByARetry) {
  TempDir dir;
  const std::string path = dir.path() + "/jobs.db";
  {
    JobStore store(path);
    store.InsertJobs({StoreJob("old")}, "local", "");
  }
  RollBackSchema(path, JobStore::SchemaVersion() - 1);
  JobStore store(path);
  auto old = store.Get("old");
  ASSERT_TRUE(old);
  EXPECT_EQ(old->exit_code, -1);  // no run ended yet
  EXPECT_EQ(old->cpu_seconds, 0);
  store.MarkRunning("old", 1.0);
  // Two runs of one attempt (a daemon restart between): CPU adds up, the peak is the largest.
  store.RecordUsage("old", {-1, 9, 2.5, 300});
  store.RecordUsage("old", {0, 0, 1.25, 200});
  old = store.Get("old");
  EXPECT_EQ(old->exit_code, 0);
  EXPECT_EQ(old->exit_signal, 0);
  EXPECT_EQ(old->cpu_seconds, 3.75);
  EXPECT_EQ(old->peak_memory_bytes, 300);
  store.RecordUsage("old", {-1, 0, -1, -1});  // not measured: adds nothing
  EXPECT_EQ(store.Get("old")->cpu_seconds, 3.75);
  ASSERT_TRUE(store.MarkFinished("old", JobState::kCompleted, "", 2.0));
  server::RequeueChange retry;
  retry.id = "old";
  store.Requeue({retry});
  old = store.Get("old");
  EXPECT_EQ(old->exit_code, -1);
  EXPECT_EQ(old->cpu_seconds, 0);
  EXPECT_EQ(old->peak_memory_bytes, 0);
}

// A completed and a cancelled job: their exit status, CPU time and peak memory as wait4 measured
// the solver, their elapsed time; then each user's usage.
TEST(JobAccounting, ExitCpuMemoryElapsedAndEachUsersUsage) {
  if (!SolverAvailable()) GTEST_SKIP() << "dlmfd-solve is not built: " << kSolverPath;
  TempDir dir;
  const std::string tokens = dir.path() + "/tokens";
  std::ofstream(tokens) << "alice-token-0123456789 alice\nbob-token-0123456789ab bob\n";
  DaemonProcess daemon(dir.path() + "/data", {"--tokens-file", tokens, "--max-user-disk-mb", "64"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  const std::string alice = "alice-token-0123456789", bob = "bob-token-0123456789ab";

  const v1::Job done = WaitFinished(*stub, SubmitScene(*stub, CavityScene(0.2), alice).id(), alice);
  ASSERT_EQ(done.state(), v1::COMPLETED) << done.reason();
  ASSERT_TRUE(done.has_exit_code());
  EXPECT_EQ(done.exit_code(), solver::kExitCompleted);
  EXPECT_EQ(done.exit_signal(), 0);
  EXPECT_GT(done.cpu_seconds(), 0);
  // The solver's resident set: at least its code and libraries (several MiB), below 1 GiB.
  EXPECT_GT(done.peak_memory_bytes(), 4 << 20);
  EXPECT_LT(done.peak_memory_bytes(), int64_t{1} << 30);
  EXPECT_DOUBLE_EQ(done.elapsed_seconds(), done.finished_time() - done.started_time());

  const v1::Job long_job = SubmitScene(*stub, CavityScene(10000.0), alice);
  while (true) {
    v1::GetRequest get;
    get.set_job_id(long_job.id());
    v1::Job now;
    auto context = Context(alice);
    ASSERT_TRUE(stub->Get(context.get(), get, &now).ok());
    if (now.state() == v1::RUNNING && now.step() > 0) {
      EXPECT_GT(now.elapsed_seconds(), 0);  // so far
      EXPECT_FALSE(now.has_exit_code());
      break;
    }
  }
  v1::CancelRequest cancel;
  cancel.set_job_id(long_job.id());
  v1::Job cancelled;
  {
    auto context = Context(alice);
    ASSERT_TRUE(stub->Cancel(context.get(), cancel, &cancelled).ok());
  }
  cancelled = WaitFinished(*stub, long_job.id(), alice);
  ASSERT_EQ(cancelled.state(), v1::CANCELLED);
  ASSERT_TRUE(cancelled.has_exit_code());
  EXPECT_EQ(cancelled.exit_code(), solver::kExitCancelled);

  const v1::Job bobs = WaitFinished(*stub, SubmitScene(*stub, CavityScene(0.05), bob).id(), bob);
  ASSERT_EQ(bobs.state(), v1::COMPLETED);
  const v1::Usage usage = UsageOf(*stub, alice);
  EXPECT_EQ(usage.user(), "alice");
  EXPECT_EQ(usage.jobs(), 2);
  EXPECT_EQ(usage.completed(), 1);
  EXPECT_EQ(usage.cancelled(), 1);
  EXPECT_EQ(usage.queued() + usage.running() + usage.failed(), 0);
  EXPECT_EQ(usage.disk_bytes(), done.disk_bytes() + cancelled.disk_bytes());
  EXPECT_GT(usage.disk_bytes(), 0);
  EXPECT_EQ(usage.disk_quota_bytes(), int64_t{64} << 20);
  EXPECT_EQ(usage.queue_unfinished(), 0);
  EXPECT_GT(usage.queue_limit(), 0);
  const v1::Usage of_bob = UsageOf(*stub, bob);
  EXPECT_EQ(of_bob.jobs(), 1);
  EXPECT_EQ(of_bob.disk_bytes(), bobs.disk_bytes());
  {
    auto context = Context("no-such-token-0123456789");
    v1::Usage none;
    EXPECT_EQ(stub->GetUsage(context.get(), v1::GetUsageRequest(), &none).error_code(),
              grpc::StatusCode::UNAUTHENTICATED);
  }
  daemon.Kill(SIGTERM);
  EXPECT_EQ(daemon.Wait(), 0) << daemon.Log();
}

}  // namespace
}  // namespace dlmfd::testing
