// The real dlmfdd on loopback with its SQLite store: requests it must refuse and how it says so
// (unreadable bodies, NUL bytes, huge values, a reused client_request_id, overrides over the scene
// size limit), what a queued job reports, and result files that are symbolic links.
#include <grpcpp/generic/generic_stub.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "../support/raw_grpc_call.h"
#include "support/daemon_process.h"

namespace dlmfd::testing {
namespace {
namespace fs = std::filesystem;
using grpc::StatusCode;

v1::SubmitRequest Cavity(double end_time = 0.1) {
  v1::SubmitRequest request;
  request.set_scene(CavityScene(end_time));
  return request;
}

grpc::Status SubmitStatus(v1::Jobs::Stub& stub, const v1::SubmitRequest& request,
                          v1::Job* job = nullptr) {
  v1::Job ignored;
  return stub.Submit(Context().get(), request, job ? job : &ignored);
}

// Expects `status` to be `code` with a message that holds `field`.
void ExpectNamed(const grpc::Status& status, StatusCode code, const std::string& field) {
  EXPECT_EQ(status.error_code(), code) << status.error_message();
  EXPECT_NE(status.error_message().find(field), std::string::npos)
      << status.error_message() << " lacks " << field;
}

grpc::Status FetchStatus(v1::Jobs::Stub& stub, const std::string& job_id, const std::string& path,
                         std::map<std::string, std::string>* files = nullptr) {
  auto context = Context();
  v1::FetchRequest request;
  request.set_job_id(job_id);
  request.set_path(path);
  auto reader = stub.Fetch(context.get(), request);
  v1::FileChunk chunk;
  while (reader->Read(&chunk)) {
    if (files) (*files)[chunk.path()] += chunk.data();
  }
  return reader->Finish();
}

// Sends `body` as the raw request of `method` ("/dlmfd.v1.Jobs/Submit"); returns the status.
grpc::Status RawCall(const DaemonProcess& daemon, const std::string& method,
                     const std::string& body) {
  grpc::GenericStub generic(daemon.Channel());
  grpc::ClientContext context;
  return RawUnaryCall(generic, context, method, body);
}

TEST(RequestChecks, AnUnreadableRequestBodyIsInvalidArgumentNamingTheRequest) {
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data");
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  // Field 1 announced with 5 bytes and cut after 2; field 1 (a string) that is not UTF-8.
  const std::string truncated(
      "\x0a\x05"
      "ab",
      4),
      not_utf8("\x0a\x02\xff\xfe", 4);
  for (const auto& [method, type] :
       std::vector<std::pair<std::string, std::string>>{{"Submit", "dlmfd.v1.SubmitRequest"},
                                                        {"Get", "dlmfd.v1.GetRequest"},
                                                        {"Watch", "dlmfd.v1.WatchRequest"},
                                                        {"Fetch", "dlmfd.v1.FetchRequest"}}) {
    for (const std::string& body : {truncated, not_utf8}) {
      ExpectNamed(RawCall(daemon, "/dlmfd.v1.Jobs/" + method, body), StatusCode::INVALID_ARGUMENT,
                  type);
    }
  }
  // A method that does not exist stays UNIMPLEMENTED.
  EXPECT_EQ(RawCall(daemon, "/dlmfd.v1.Jobs/NoSuchRpc", "").error_code(),
            StatusCode::UNIMPLEMENTED);
  EXPECT_TRUE(daemon.Healthy());
}

TEST(RequestChecks, NulBytesAreRefusedNamingTheField) {
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", {"--max-concurrent", "1"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  const std::string nul("\0", 1);
  {
    auto request = Cavity();
    request.add_overrides("fluid.viscosity=0.1" + nul + "x");
    ExpectNamed(SubmitStatus(*stub, request), StatusCode::INVALID_ARGUMENT, "overrides");
  }
  {
    auto request = Cavity();
    request.set_name("cavity" + nul + "hidden");
    ExpectNamed(SubmitStatus(*stub, request), StatusCode::INVALID_ARGUMENT, "name");
  }
  {
    auto request = Cavity();
    request.add_tags("t" + nul);
    ExpectNamed(SubmitStatus(*stub, request), StatusCode::INVALID_ARGUMENT, "tags");
  }
  {
    auto request = Cavity();
    request.set_client_request_id("id" + nul);
    ExpectNamed(SubmitStatus(*stub, request), StatusCode::INVALID_ARGUMENT, "client_request_id");
  }
  {
    auto request = Cavity();
    request.set_scene(request.scene() + "# " + nul + "\n");
    ExpectNamed(SubmitStatus(*stub, request), StatusCode::INVALID_ARGUMENT, "scene");
  }
  {
    v1::SubmitStudyRequest study;
    study.set_scene(CavityScene(0.1));
    auto* axis = study.add_axes();
    axis->set_key("fluid.viscosity");
    axis->add_values("0.1" + nul);
    v1::SubmitStudyResponse reply;
    ExpectNamed(stub->SubmitStudy(Context().get(), study, &reply), StatusCode::INVALID_ARGUMENT,
                "axes");
  }
  v1::Job job;
  ASSERT_TRUE(SubmitStatus(*stub, Cavity(100.0), &job).ok());
  {
    v1::GetRequest get;
    get.set_job_id(job.id() + nul);
    v1::Job out;
    ExpectNamed(stub->Get(Context().get(), get, &out), StatusCode::INVALID_ARGUMENT, "job_id");
  }
  ExpectNamed(FetchStatus(*stub, job.id(), "scene.toml" + nul + "x"), StatusCode::INVALID_ARGUMENT,
              "path");
  v1::ListResponse list;
  ASSERT_TRUE(stub->List(Context().get(), v1::ListRequest(), &list).ok());
  EXPECT_EQ(list.jobs_size(), 1);  // nothing refused was queued
  EXPECT_TRUE(daemon.Healthy());
}

TEST(RequestChecks, AHugeBadValueGetsAShortMessageNamingTheKey) {
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data");
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  auto request = Cavity();
  request.add_overrides("fluid.viscosity=" + std::string(1'000'000, 'x'));
  const grpc::Status status = SubmitStatus(*stub, request);
  ExpectNamed(status, StatusCode::INVALID_ARGUMENT, "fluid.viscosity");
  // The daemon's bound on a message (service_error.h, kMessageBytes = 1024) plus the note of the
  // cut; gRPC's own limit on the metadata a client accepts is 8 KiB.
  EXPECT_LE(status.error_message().size(), 1100u);
  EXPECT_NE(status.error_message().find("bytes cut"), std::string::npos) << status.error_message();
  auto named = Cavity();
  named.set_name(std::string(1'000'000, 'n'));
  const grpc::Status name_status = SubmitStatus(*stub, named);
  ExpectNamed(name_status, StatusCode::INVALID_ARGUMENT, "name");
  EXPECT_LE(name_status.error_message().size(), 1100u);
}

TEST(RequestChecks, OverridesCountTowardTheSceneSizeLimit) {
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", {"--max-scene-bytes", "4096"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  auto request = Cavity();
  ASSERT_LT(request.scene().size(), 1000u);
  request.add_overrides("title=\"" + std::string(3900, 't') + "\"");
  ExpectNamed(SubmitStatus(*stub, request), StatusCode::RESOURCE_EXHAUSTED, "max_scene_bytes");
  v1::SubmitStudyRequest study;
  study.set_scene(request.scene());
  study.add_overrides(request.overrides(0));
  auto* axis = study.add_axes();
  axis->set_key("fluid.viscosity");
  axis->add_values("0.1");
  v1::SubmitStudyResponse reply;
  ExpectNamed(stub->SubmitStudy(Context().get(), study, &reply), StatusCode::RESOURCE_EXHAUSTED,
              "max_scene_bytes");
  auto small = Cavity();
  small.add_overrides("title=\"" + std::string(2000, 't') + "\"");
  EXPECT_TRUE(SubmitStatus(*stub, small).ok());
}

TEST(RequestChecks, ARetriedRequestIdWithAnotherRequestIsAlreadyExists) {
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", {"--max-concurrent", "1"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  auto request = Cavity(100.0);
  request.set_client_request_id("study-1");
  v1::Job first, again;
  ASSERT_TRUE(SubmitStatus(*stub, request, &first).ok());
  ASSERT_TRUE(SubmitStatus(*stub, request, &again).ok());
  EXPECT_EQ(again.id(), first.id());
  auto other_scene = request;
  other_scene.set_scene(CavityScene(50.0));
  ExpectNamed(SubmitStatus(*stub, other_scene), StatusCode::ALREADY_EXISTS, "client_request_id");
  auto other_overrides = request;
  other_overrides.add_overrides("fluid.viscosity=0.02");
  ExpectNamed(SubmitStatus(*stub, other_overrides), StatusCode::ALREADY_EXISTS,
              "client_request_id");
  v1::SubmitStudyRequest study;
  study.set_scene(CavityScene(100.0));
  study.set_client_request_id("study-1");
  auto* axis = study.add_axes();
  axis->set_key("fluid.viscosity");
  axis->add_values("0.1");
  axis->add_values("0.2");
  v1::SubmitStudyResponse study_first, study_again;
  ASSERT_TRUE(stub->SubmitStudy(Context().get(), study, &study_first).ok());
  ASSERT_TRUE(stub->SubmitStudy(Context().get(), study, &study_again).ok());
  EXPECT_EQ(study_again.study_id(), study_first.study_id());
  axis->set_values(1, "0.3");
  v1::SubmitStudyResponse refused;
  ExpectNamed(stub->SubmitStudy(Context().get(), study, &refused), StatusCode::ALREADY_EXISTS,
              "client_request_id");
  v1::ListResponse list;
  ASSERT_TRUE(stub->List(Context().get(), v1::ListRequest(), &list).ok());
  EXPECT_EQ(list.jobs_size(), 3);
}

TEST(RequestChecks, AQueuedJobReportsTheScenesEndTime) {
  TempDir dir;
  // One job at a time: the second job stays QUEUED behind a long first one.
  DaemonProcess daemon(dir.path() + "/data", {"--max-concurrent", "1"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  v1::Job running, queued;
  ASSERT_TRUE(SubmitStatus(*stub, Cavity(100.0), &running).ok());
  ASSERT_TRUE(SubmitStatus(*stub, Cavity(0.75), &queued).ok());
  EXPECT_EQ(queued.end_time(), 0.75);
  v1::GetRequest get;
  get.set_job_id(queued.id());
  v1::Job got;
  ASSERT_TRUE(stub->Get(Context().get(), get, &got).ok());
  EXPECT_EQ(got.end_time(), 0.75);
  v1::ListResponse list;
  ASSERT_TRUE(stub->List(Context().get(), v1::ListRequest(), &list).ok());
  std::set<double> end_times;
  for (const auto& job : list.jobs()) end_times.insert(job.end_time());
  EXPECT_EQ(end_times, (std::set<double>{0.75, 100.0}));
}

TEST(RequestChecks, SymbolicLinksInResultsAreNeitherListedNorServed) {
  REQUIRE_SOLVER();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data");
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  v1::Job job;
  ASSERT_TRUE(SubmitStatus(*stub, Cavity(0.05), &job).ok());
  ASSERT_EQ(WaitFinished(*stub, job.id()).state(), v1::COMPLETED);
  const fs::path results = job.results_dir();
  ASSERT_TRUE(fs::exists(results / "summary.json"));
  const fs::path outside = dir.path() + "/outside";
  fs::create_directories(outside);
  std::ofstream(outside / "secret.txt") << "not the job's";
  fs::create_symlink(outside / "secret.txt", results / "secret.txt");
  fs::create_symlink(outside, results / "outside");
  fs::create_symlink(results / "summary.json", results / "summary-link.json");
  v1::ListFilesRequest list_request;
  list_request.set_job_id(job.id());
  v1::ListFilesResponse listed;
  ASSERT_TRUE(stub->ListFiles(Context().get(), list_request, &listed).ok());
  std::set<std::string> paths;
  for (const auto& file : listed.files()) paths.insert(file.path());
  EXPECT_TRUE(paths.count("summary.json"));
  for (const char* link : {"secret.txt", "outside/secret.txt", "summary-link.json"}) {
    EXPECT_FALSE(paths.count(link)) << link;
  }
  std::map<std::string, std::string> fetched;
  ASSERT_TRUE(FetchStatus(*stub, job.id(), "", &fetched).ok());
  EXPECT_TRUE(fetched.count("summary.json"));
  for (const auto& [path, data] : fetched) {
    EXPECT_EQ(data.find("not the job's"), std::string::npos) << path;
    EXPECT_TRUE(paths.count(path)) << path;
  }
  EXPECT_EQ(fetched.size(), paths.size());
  for (const char* link : {"secret.txt", "outside/secret.txt", "summary-link.json"}) {
    EXPECT_EQ(FetchStatus(*stub, job.id(), link).error_code(), StatusCode::INVALID_ARGUMENT)
        << link;
  }
}

}  // namespace
}  // namespace dlmfd::testing
