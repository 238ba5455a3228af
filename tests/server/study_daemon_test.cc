// Studies against the real dlmfdd and dlmfd-solve (issue 14 points 1-3): a study is stored with its
// axes and counts (GetStudy, ListStudies), List selects by the effective scene and names an unknown
// study NOT_FOUND, an invalid point rejects the whole study, and Retry reruns finished jobs in
// their study, resuming a cancelled one from its checkpoint and starting a changed one afresh.
// Scenes are the 16 x 16 cavity of a few hundred steps at most.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "support/daemon_process.h"
#include "support/study_axis.h"

namespace dlmfd::testing {
namespace {

std::vector<v1::Job> ListWhere(v1::Jobs::Stub& stub, const std::string& study,
                               std::vector<std::string> where, grpc::Status* status = nullptr) {
  v1::ListRequest request;
  request.set_study_id(study);
  for (const auto& w : where) request.add_where(w);
  v1::ListResponse response;
  const grpc::Status s = stub.List(Context().get(), request, &response);
  if (status) *status = s;
  return {response.jobs().begin(), response.jobs().end()};
}

bool HasLog(const std::vector<v1::WatchEvent>& events, const std::string& text) {
  for (const auto& e : events) {
    if (e.has_log() && e.log().text() == text) return true;
  }
  return false;
}

TEST(Studies, AStudyIsStoredWithItsAxesAndFoundByTheEffectiveScene) {
  REQUIRE_SOLVER();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", {"--max-concurrent", "2"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();

  v1::SubmitStudyRequest request;
  request.set_scene(CavityScene(0.05));
  request.set_name("cavity-study");
  request.add_tags("study-e2e");
  (*request.mutable_labels())["project"] = "cavity";
  request.set_max_running(1);
  *request.add_axes() = ListAxis("fluid.viscosity", {"0.01", "0.02"}, "pair");
  *request.add_axes() = ListAxis("time.end", {"0.05", "0.1"}, "pair");
  v1::SubmitStudyResponse submitted;
  ASSERT_TRUE(stub->SubmitStudy(Context().get(), request, &submitted).ok());
  ASSERT_EQ(submitted.jobs_size(), 2);  // zipped: two points, not four
  EXPECT_EQ(submitted.jobs(1).parameters(0).key(), "fluid.viscosity");
  EXPECT_EQ(submitted.jobs(1).parameters(0).number(), 0.02);
  EXPECT_EQ(submitted.jobs(1).labels().at("project"), "cavity");
  for (const auto& job : submitted.jobs()) WaitFinished(*stub, job.id());

  v1::GetStudyRequest get;
  get.set_study_id(submitted.study_id());
  v1::Study study;
  ASSERT_TRUE(stub->GetStudy(Context().get(), get, &study).ok());
  EXPECT_EQ(study.name(), "cavity-study");
  EXPECT_EQ(study.jobs(), 2);
  EXPECT_EQ(study.completed(), 2);
  EXPECT_EQ(study.progress(), 1.0);
  EXPECT_EQ(study.max_running(), 1);
  ASSERT_EQ(study.axes_size(), 2);
  EXPECT_EQ(study.axes(0).zip(), "pair");
  v1::ListStudiesRequest list_studies;
  list_studies.set_tag("study-e2e");
  v1::ListStudiesResponse studies;
  ASSERT_TRUE(stub->ListStudies(Context().get(), list_studies, &studies).ok());
  ASSERT_EQ(studies.studies_size(), 1);
  EXPECT_EQ(studies.studies(0).id(), submitted.study_id());

  // An override's value, and one the scene file never names (the default density 1).
  EXPECT_EQ(ListWhere(*stub, submitted.study_id(), {"fluid.viscosity=0.02"}).size(), 1u);
  EXPECT_EQ(ListWhere(*stub, submitted.study_id(), {"fluid.viscosity=2e-2"}).size(), 1u);
  EXPECT_EQ(ListWhere(*stub, submitted.study_id(), {"fluid.density=1"}).size(), 2u);
  EXPECT_EQ(ListWhere(*stub, submitted.study_id(), {"domain.boundary.top.value.0=1.0"}).size(), 2u);
  EXPECT_EQ(ListWhere(*stub, "", {"fluid.viscosity=0.03"}).size(), 0u);
  grpc::Status status;
  ListWhere(*stub, "s-unknown", {}, &status);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND);
  get.set_study_id("s-unknown");
  EXPECT_EQ(stub->GetStudy(Context().get(), get, &study).error_code(), grpc::StatusCode::NOT_FOUND);
  ListWhere(*stub, "", {"fluid.viscosity"}, &status);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  // Issue 38: ranges and !=, and a key no job has is named, not an empty list.
  EXPECT_EQ(ListWhere(*stub, submitted.study_id(), {"fluid.viscosity>0.015"}).size(), 1u);
  EXPECT_EQ(
      ListWhere(*stub, submitted.study_id(), {"fluid.viscosity>=0.01", "time.end<0.1"}).size(), 1u);
  EXPECT_EQ(ListWhere(*stub, submitted.study_id(), {"fluid.viscosity!=0.01"}).size(), 1u);
  EXPECT_EQ(ListWhere(*stub, submitted.study_id(), {"title<1"}).size(), 0u);  // not a number
  ListWhere(*stub, "", {"fluid.viscosty=0.02"}, &status);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("fluid.viscosty"), std::string::npos)
      << status.error_message();
}

TEST(Studies, AnInvalidPointRejectsTheWholeStudy) {
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data");
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  v1::SubmitStudyRequest request;
  request.set_scene(CavityScene(0.05));
  *request.add_axes() = ListAxis("fluid.viscosity", {"0.01", "-1"});
  *request.add_axes() = ListAxis("time.end", {"0.05", "0.1"});
  v1::SubmitStudyResponse reply;
  const grpc::Status status = stub->SubmitStudy(Context().get(), request, &reply);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("fluid.viscosity"), std::string::npos);
  EXPECT_NE(status.error_message().find("study point fluid.viscosity=-1"), std::string::npos)
      << status.error_message();
  v1::ListStudiesResponse studies;
  ASSERT_TRUE(stub->ListStudies(Context().get(), v1::ListStudiesRequest(), &studies).ok());
  EXPECT_EQ(studies.studies_size(), 0);
  EXPECT_TRUE(ListWhere(*stub, "", {}).empty());
  // A wildcard over an array the scene does not have is invalid too, naming the key.
  request.clear_axes();
  *request.add_axes() = ListAxis("particles.*.density", {"1.5"});
  const grpc::Status wildcard = stub->SubmitStudy(Context().get(), request, &reply);
  EXPECT_EQ(wildcard.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(wildcard.error_message().find("particles.*.density"), std::string::npos)
      << wildcard.error_message();
}

TEST(Studies, RetryResumesACancelledJobAndStartsAChangedOneAfresh) {
  REQUIRE_SOLVER();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data");
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  v1::SubmitStudyRequest request;
  // 5000 steps: still running when the cancel comes, also on an idle machine (500 were not).
  request.set_scene(CavityScene(50.0));
  *request.add_axes() = ListAxis("fluid.viscosity", {"0.01"});
  v1::SubmitStudyResponse submitted;
  ASSERT_TRUE(stub->SubmitStudy(Context().get(), request, &submitted).ok());
  const std::string id = submitted.jobs(0).id();
  WaitForProgress(*stub, id);
  v1::CancelRequest cancel;
  cancel.set_job_id(id);
  v1::Job cancelled;
  ASSERT_TRUE(stub->Cancel(Context().get(), cancel, &cancelled).ok());
  const v1::Job first = WaitFinished(*stub, id);
  ASSERT_EQ(first.state(), v1::CANCELLED) << first.reason();
  ASSERT_LT(first.step(), 5000);

  // A running or queued job is not retried; an unknown one is not found.
  v1::RetryRequest unknown;
  unknown.add_job_ids("j-unknown");
  v1::RetryResponse retried;
  EXPECT_EQ(stub->Retry(Context().get(), unknown, &retried).error_code(),
            grpc::StatusCode::NOT_FOUND);

  v1::RetryRequest retry;
  retry.set_study_id(submitted.study_id());  // default states: failed, cancelled
  ASSERT_TRUE(stub->Retry(Context().get(), retry, &retried).ok());
  ASSERT_EQ(retried.jobs_size(), 1);
  EXPECT_EQ(retried.jobs(0).id(), id);
  EXPECT_EQ(retried.jobs(0).state(), v1::QUEUED);
  EXPECT_EQ(retried.jobs(0).attempt(), 2);
  EXPECT_EQ(retried.jobs(0).study_id(), submitted.study_id());
  const auto resumed_events = WatchAll(*stub, id);
  EXPECT_TRUE(HasLog(resumed_events, "solver resumed from results/checkpoint.h5"));
  const v1::Job second = WaitFinished(*stub, id);
  EXPECT_EQ(second.state(), v1::COMPLETED) << second.reason();
  EXPECT_EQ(second.step(), 5000);
  ASSERT_EQ(second.previous_attempts_size(), 1);
  EXPECT_EQ(second.previous_attempts(0).state(), v1::CANCELLED);
  EXPECT_EQ(second.previous_attempts(0).step(), first.step());

  // Nothing failed or cancelled is left: FAILED_PRECONDITION. A changed scene starts afresh.
  EXPECT_EQ(stub->Retry(Context().get(), retry, &retried).error_code(),
            grpc::StatusCode::FAILED_PRECONDITION);
  retry.add_states(v1::COMPLETED);
  retry.add_overrides("time.end=2");
  retry.add_overrides("fluid.viscosity=0.02");
  ASSERT_TRUE(stub->Retry(Context().get(), retry, &retried).ok());
  // The events of this attempt: after the retry's state event (a watch from 0 reads the whole
  // history of the job, its earlier attempts' too).
  const auto fresh_events = WatchAll(*stub, id, "", retried.jobs(0).last_seq());
  EXPECT_TRUE(HasLog(fresh_events, "solver started"));
  EXPECT_FALSE(HasLog(fresh_events, "solver resumed from results/checkpoint.h5"));
  const v1::Job third = WaitFinished(*stub, id);
  EXPECT_EQ(third.state(), v1::COMPLETED) << third.reason();
  EXPECT_EQ(third.step(), 200);
  EXPECT_EQ(third.attempt(), 3);
  EXPECT_EQ(third.parameters(0).text(), "0.02");  // the point follows the change of its axis
  EXPECT_EQ(first.name(), submitted.study_id() + "[fluid.viscosity=0.01]");
  EXPECT_EQ(third.name(), submitted.study_id() + "[fluid.viscosity=0.02]");  // and so does its name
  EXPECT_EQ(std::set<std::string>(third.overrides().begin(), third.overrides().end()),
            (std::set<std::string>{"fluid.viscosity=0.02", "time.end=2"}));
  // An invalid change is refused before anything is requeued.
  retry.clear_overrides();
  retry.add_overrides("fluid.viscosity=-1");
  const grpc::Status bad = stub->Retry(Context().get(), retry, &retried);
  EXPECT_EQ(bad.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(bad.error_message().find("job " + id), std::string::npos) << bad.error_message();
  v1::GetRequest get;
  get.set_job_id(id);
  v1::Job after;
  ASSERT_TRUE(stub->Get(Context().get(), get, &after).ok());
  EXPECT_EQ(after.attempt(), 3);
  EXPECT_EQ(after.state(), v1::COMPLETED);
}

}  // namespace
}  // namespace dlmfd::testing
