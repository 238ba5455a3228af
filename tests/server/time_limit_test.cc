// A job's own wall-time limit against the real daemon on loopback (its SQLite store, the real
// solver): SubmitRequest and SubmitStudyRequest.time_limit_seconds is checked (not negative, not
// over the daemon's limit, the message naming the field and the limit), stored with each job and
// reported by Get; the local executor stops a run past it (the solver checkpoints) and the job
// ends FAILED naming the job's limit, with no daemon-wide limit set.
#include <gtest/gtest.h>

#include <string>

#include "support/daemon_process.h"

namespace dlmfd::testing {
namespace {
using grpc::StatusCode;

grpc::Status SubmitWithLimit(v1::Jobs::Stub& stub, int64_t seconds, v1::Job* job,
                             const std::string& scene = CavityScene(0.1)) {
  v1::SubmitRequest request;
  request.set_scene(scene);
  request.set_time_limit_seconds(seconds);
  return stub.Submit(Context().get(), request, job);
}

grpc::Status StudyWithLimit(v1::Jobs::Stub& stub, int64_t seconds, v1::SubmitStudyResponse* study) {
  v1::SubmitStudyRequest request;
  request.set_scene(CavityScene(0.1));
  request.set_time_limit_seconds(seconds);
  auto* axis = request.add_axes();
  axis->set_key("fluid.viscosity");
  axis->add_values("0.01");
  axis->add_values("0.02");
  return stub.SubmitStudy(Context().get(), request, study);
}

void ExpectRefused(const grpc::Status& status, const std::string& limit) {
  EXPECT_EQ(status.error_code(), StatusCode::INVALID_ARGUMENT) << status.error_message();
  EXPECT_EQ(status.error_message().rfind("time_limit_seconds = ", 0), 0u) << status.error_message();
  EXPECT_NE(status.error_message().find(limit), std::string::npos) << status.error_message();
}

TEST(JobTimeLimit, IsCheckedAgainstTheDaemonsLimitAndStoredWithEachJob) {
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", {"--max-wall-seconds", "3600"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  v1::Job job;
  ExpectRefused(SubmitWithLimit(*stub, -1, &job), "max_wall_seconds");
  ExpectRefused(SubmitWithLimit(*stub, 3601, &job), "1 to 3600 (max_wall_seconds)");
  v1::SubmitStudyResponse study;
  ExpectRefused(StudyWithLimit(*stub, 7200, &study), "max_wall_seconds");
  // Within it: stored, reported, and the same for every point of a study.
  ASSERT_TRUE(SubmitWithLimit(*stub, 1800, &job).ok());
  EXPECT_EQ(job.time_limit_seconds(), 1800);
  v1::GetRequest get;
  get.set_job_id(job.id());
  v1::Job got;
  ASSERT_TRUE(stub->Get(Context().get(), get, &got).ok());
  EXPECT_EQ(got.time_limit_seconds(), 1800);
  ASSERT_TRUE(StudyWithLimit(*stub, 600, &study).ok());
  ASSERT_EQ(study.jobs_size(), 2);
  for (const v1::Job& point : study.jobs()) EXPECT_EQ(point.time_limit_seconds(), 600);
  // None asked: the daemon's limit applies, the job carries 0.
  ASSERT_TRUE(SubmitWithLimit(*stub, 0, &job).ok());
  EXPECT_EQ(job.time_limit_seconds(), 0);
  EXPECT_EQ(WaitFinished(*stub, job.id()).state(), v1::COMPLETED);
}

TEST(JobTimeLimit, WithoutADaemonLimitAYearIsTheMost) {
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", {});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  v1::Job job;
  ExpectRefused(SubmitWithLimit(*stub, 525600LL * 60 + 1, &job), "365 days");
  EXPECT_TRUE(SubmitWithLimit(*stub, 525600LL * 60, &job).ok());
}

TEST(JobTimeLimit, TheLocalExecutorStopsARunPastTheJobsLimit) {
  if (!SolverAvailable()) GTEST_SKIP() << "dlmfd-solve is not built: " << kSolverPath;
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", {});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  // 10^6 steps: far more than 2 s on any machine.
  v1::Job job;
  ASSERT_TRUE(
      SubmitWithLimit(*stub, 2, &job, CavityScene(10000.0) + "[output]\nfields_every = 0\n").ok());
  const v1::Job stopped = WaitFinished(*stub, job.id());
  EXPECT_EQ(stopped.state(), v1::FAILED);
  EXPECT_NE(stopped.reason().find("wall time limit: the solver ran longer than the job's "
                                  "time_limit_seconds = 2"),
            std::string::npos)
      << stopped.reason();
}

}  // namespace
}  // namespace dlmfd::testing
