// The real dlmfdd process on a free loopback port, a temporary data directory and the real
// dlmfd-solve: security, malformed requests, idempotency, submit/watch/cancel/fetch, many watchers,
// a drained queue under the concurrency limit, and kill -9 with restart.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <set>
#include <thread>

#include "dlmfd/io/field_snapshot.h"
#include "support/daemon_process.h"

namespace dlmfd::testing {
namespace {
namespace fs = std::filesystem;
using grpc::StatusCode;

constexpr char kAlice[] = "alice-token-0123456789";
constexpr char kBob[] = "bob-token-0123456789ab";

v1::SubmitRequest CavityRequest(double end_time, const std::string& name = "cavity") {
  v1::SubmitRequest request;
  request.set_scene(CavityScene(end_time));
  request.set_name(name);
  return request;
}

v1::Job Submit(v1::Jobs::Stub& stub, const v1::SubmitRequest& request,
               const std::string& token = "") {
  auto context = Context(token);
  v1::Job job;
  auto status = stub.Submit(context.get(), request, &job);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return job;
}

TEST(Daemon, NonLoopbackWithoutTokensRefusesToStart) {
  TempDir dir;
  const std::string log = dir.path() + "/log";
  const std::string command =
      std::string(kDaemonPath) + " --listen 0.0.0.0:0 --data-dir " + dir.path() + "/data 2> " + log;
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  std::ifstream in(log);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("no tokens are configured"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(dir.path() + "/data/jobs.db"));
}

TEST(Daemon, MalformedRequestsGetTheRightCodesAndTheDaemonStaysHealthy) {
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", {"--max-scene-bytes", "4096", "--max-grid-nodes",
                                              "20000", "--max-queued", "3"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  int checked = 0;
  auto submit = [&](v1::SubmitRequest request, StatusCode expected, const std::string& in_message) {
    auto context = Context();
    v1::Job job;
    auto status = stub->Submit(context.get(), request, &job);
    EXPECT_EQ(status.error_code(), expected) << status.error_message();
    EXPECT_NE(status.error_message().find(in_message), std::string::npos)
        << status.error_message() << " lacks " << in_message;
    ++checked;
  };
  auto with_scene = [](const std::string& scene, std::vector<std::string> overrides = {}) {
    v1::SubmitRequest request;
    request.set_scene(scene);
    for (auto& o : overrides) request.add_overrides(o);
    return request;
  };
  const std::string good = CavityScene(0.1);
  submit(with_scene(""), StatusCode::INVALID_ARGUMENT, "scene");
  submit(with_scene("this is not toml ["), StatusCode::INVALID_ARGUMENT, "");
  submit(with_scene(good + "[fluid2]\nx = 1\n"), StatusCode::INVALID_ARGUMENT, "fluid2");
  submit(with_scene(good, {"fluid.viscosity=-1"}), StatusCode::INVALID_ARGUMENT, "fluid.viscosity");
  submit(with_scene(good, {"time.dt=0"}), StatusCode::INVALID_ARGUMENT, "time.dt");
  submit(with_scene(good, {"domain.h=0.3"}), StatusCode::INVALID_ARGUMENT, "domain");
  submit(with_scene(good, {"no-equals-sign"}), StatusCode::INVALID_ARGUMENT, "");
  submit(with_scene(good, {"=1"}), StatusCode::INVALID_ARGUMENT, "");
  submit(with_scene(good, {"fluid.viscosityy=1"}), StatusCode::INVALID_ARGUMENT, "viscosityy");
  submit(with_scene(good, {"fluid.viscosity=1\nx"}), StatusCode::INVALID_ARGUMENT, "line break");
  submit(with_scene(std::string(5000, '#')), StatusCode::RESOURCE_EXHAUSTED, "bytes");
  submit(with_scene(good, {"domain.h=0.001953125"}), StatusCode::RESOURCE_EXHAUSTED, "nodes");
  {
    auto request = with_scene(good);
    request.set_priority(5000);
    submit(request, StatusCode::INVALID_ARGUMENT, "priority");
  }
  {
    auto request = with_scene(good);
    request.add_tags("");
    submit(request, StatusCode::INVALID_ARGUMENT, "tags");
  }
  {
    auto request = with_scene(good);
    request.set_name(std::string(300, 'n'));
    submit(request, StatusCode::INVALID_ARGUMENT, "name");
  }
  {
    auto request = with_scene(good);
    request.set_client_request_id(std::string(200, 'r'));
    submit(request, StatusCode::INVALID_ARGUMENT, "client_request_id");
  }
  auto unary_code = [&](auto call) {
    auto context = Context();
    ++checked;
    return call(context.get()).error_code();
  };
  v1::Job job;
  v1::GetRequest get;
  EXPECT_EQ(unary_code([&](auto* c) { return stub->Get(c, get, &job); }),
            StatusCode::INVALID_ARGUMENT);
  get.set_job_id("j-doesnotexist");
  EXPECT_EQ(unary_code([&](auto* c) { return stub->Get(c, get, &job); }), StatusCode::NOT_FOUND);
  get.set_job_id(std::string(100, 'x'));
  EXPECT_EQ(unary_code([&](auto* c) { return stub->Get(c, get, &job); }),
            StatusCode::INVALID_ARGUMENT);
  v1::CancelRequest cancel;
  EXPECT_EQ(unary_code([&](auto* c) { return stub->Cancel(c, cancel, &job); }),
            StatusCode::INVALID_ARGUMENT);
  cancel.set_job_id("j-missing");
  EXPECT_EQ(unary_code([&](auto* c) { return stub->Cancel(c, cancel, &job); }),
            StatusCode::NOT_FOUND);
  v1::ListResponse list;
  v1::ListRequest list_request;
  list_request.set_page_size(-1);
  EXPECT_EQ(unary_code([&](auto* c) { return stub->List(c, list_request, &list); }),
            StatusCode::INVALID_ARGUMENT);
  list_request.set_page_size(5000);
  EXPECT_EQ(unary_code([&](auto* c) { return stub->List(c, list_request, &list); }),
            StatusCode::INVALID_ARGUMENT);
  list_request.set_page_size(10);
  list_request.set_page_token("abc");
  EXPECT_EQ(unary_code([&](auto* c) { return stub->List(c, list_request, &list); }),
            StatusCode::INVALID_ARGUMENT);
  list_request.set_page_token("");
  list_request.add_states(static_cast<v1::JobState>(42));
  EXPECT_EQ(unary_code([&](auto* c) { return stub->List(c, list_request, &list); }),
            StatusCode::INVALID_ARGUMENT);
  v1::SubmitStudyRequest study;
  v1::SubmitStudyResponse study_reply;
  study.set_scene(good);
  EXPECT_EQ(unary_code([&](auto* c) { return stub->SubmitStudy(c, study, &study_reply); }),
            StatusCode::INVALID_ARGUMENT);
  auto* axis = study.add_axes();
  axis->set_key("fluid.viscosity");
  EXPECT_EQ(unary_code([&](auto* c) { return stub->SubmitStudy(c, study, &study_reply); }),
            StatusCode::INVALID_ARGUMENT);
  axis->add_values("0.1");
  axis->add_values("-0.1");
  EXPECT_EQ(unary_code([&](auto* c) { return stub->SubmitStudy(c, study, &study_reply); }),
            StatusCode::INVALID_ARGUMENT);
  study.add_axes()->CopyFrom(*axis);
  EXPECT_EQ(unary_code([&](auto* c) { return stub->SubmitStudy(c, study, &study_reply); }),
            StatusCode::INVALID_ARGUMENT);
  study.clear_axes();
  auto* big = study.add_axes();
  big->set_key("fluid.viscosity");
  for (int i = 1; i <= 5; ++i) big->add_values(std::to_string(0.01 * i));
  EXPECT_EQ(unary_code([&](auto* c) { return stub->SubmitStudy(c, study, &study_reply); }),
            StatusCode::RESOURCE_EXHAUSTED);
  v1::CancelStudyRequest cancel_study;
  v1::CancelStudyResponse cancel_study_reply;
  EXPECT_EQ(
      unary_code([&](auto* c) { return stub->CancelStudy(c, cancel_study, &cancel_study_reply); }),
      StatusCode::INVALID_ARGUMENT);
  cancel_study.set_study_id("s-missing");
  EXPECT_EQ(
      unary_code([&](auto* c) { return stub->CancelStudy(c, cancel_study, &cancel_study_reply); }),
      StatusCode::NOT_FOUND);
  v1::ListFilesRequest files_request;
  v1::ListFilesResponse files;
  files_request.set_job_id("j-missing");
  EXPECT_EQ(unary_code([&](auto* c) { return stub->ListFiles(c, files_request, &files); }),
            StatusCode::NOT_FOUND);
  auto stream_code = [&](auto open) {
    auto context = Context();
    ++checked;
    return open(context.get());
  };
  auto watch = [&](v1::WatchRequest request) {
    return stream_code([&](grpc::ClientContext* c) {
      auto reader = stub->Watch(c, request);
      v1::WatchEvent event;
      while (reader->Read(&event)) {}
      return reader->Finish().error_code();
    });
  };
  v1::WatchRequest watch_request;
  EXPECT_EQ(watch(watch_request), StatusCode::INVALID_ARGUMENT);
  watch_request.set_job_id("j-missing");
  EXPECT_EQ(watch(watch_request), StatusCode::NOT_FOUND);
  watch_request.set_from_seq(-3);
  EXPECT_EQ(watch(watch_request), StatusCode::INVALID_ARGUMENT);
  watch_request.set_from_seq(0);
  watch_request.set_snapshot_max_width(100000);
  EXPECT_EQ(watch(watch_request), StatusCode::INVALID_ARGUMENT);
  // Queue three valid jobs (the limit), then the fourth is refused; fetch paths are checked.
  std::string job_id = Submit(*stub, CavityRequest(100.0)).id();
  {
    // A study that does not fit names what it adds (issue 38: a 10,000-point study against one
    // unfinished job said "1 unfinished jobs, the limit is 10000").
    v1::SubmitStudyRequest too_big;
    too_big.set_scene(good);
    auto* viscosity = too_big.add_axes();
    viscosity->set_key("fluid.viscosity");
    for (const char* value : {"0.1", "0.2", "0.3"}) viscosity->add_values(value);
    v1::SubmitStudyResponse swept;
    auto context = Context();
    const grpc::Status status = stub->SubmitStudy(context.get(), too_big, &swept);
    EXPECT_EQ(status.error_code(), StatusCode::RESOURCE_EXHAUSTED);
    EXPECT_NE(status.error_message().find("no room for 3 jobs: 1 unfinished and 3 new make 4, "
                                          "over the limit of max_queued = 3"),
              std::string::npos)
        << status.error_message();
    ++checked;
  }
  for (int i = 0; i < 2; ++i) job_id = Submit(*stub, CavityRequest(100.0)).id();
  submit(with_scene(good), StatusCode::RESOURCE_EXHAUSTED,
         "queue is full: 3 unfinished jobs, at the limit of max_queued = 3");
  auto fetch = [&](const std::string& id, const std::string& path) {
    v1::FetchRequest request;
    request.set_job_id(id);
    request.set_path(path);
    return stream_code([&](grpc::ClientContext* c) {
      auto reader = stub->Fetch(c, request);
      v1::FileChunk chunk;
      while (reader->Read(&chunk)) {}
      return reader->Finish().error_code();
    });
  };
  EXPECT_EQ(fetch(job_id, "../../jobs.db"), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(fetch(job_id, "/etc/passwd"), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(fetch(job_id, "no-such-file"), StatusCode::NOT_FOUND);
  EXPECT_EQ(fetch("j-missing", ""), StatusCode::NOT_FOUND);
  // Cancel everything; a second cancel of a finished job is FAILED_PRECONDITION.
  for (auto& j : [&] {
         auto context = Context();
         v1::ListRequest all;
         v1::ListResponse reply;
         stub->List(context.get(), all, &reply);
         return std::vector<v1::Job>(reply.jobs().begin(), reply.jobs().end());
       }()) {
    cancel.set_job_id(j.id());
    auto context = Context();
    EXPECT_TRUE(stub->Cancel(context.get(), cancel, &job).ok());
  }
  WaitFinished(*stub, job_id);
  cancel.set_job_id(job_id);
  EXPECT_EQ(unary_code([&](auto* c) { return stub->Cancel(c, cancel, &job); }),
            StatusCode::FAILED_PRECONDITION);
  EXPECT_GE(checked, 30);
  EXPECT_TRUE(daemon.Healthy());
}

TEST(Daemon, UsersSeeAndCancelOnlyTheirOwnJobs) {
  TempDir dir;
  const std::string tokens = dir.path() + "/tokens";
  std::ofstream(tokens) << "# token user\n" << kAlice << " alice\n" << kBob << " bob\n";
  DaemonProcess daemon(dir.path() + "/data", {"--tokens-file", tokens});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  EXPECT_TRUE(daemon.Healthy());  // health needs no token
  {
    auto context = Context();
    v1::Job job;
    EXPECT_EQ(stub->Submit(context.get(), CavityRequest(0.1), &job).error_code(),
              StatusCode::UNAUTHENTICATED);
    auto bad = Context("not-a-known-token-at-all");
    EXPECT_EQ(stub->Submit(bad.get(), CavityRequest(0.1), &job).error_code(),
              StatusCode::UNAUTHENTICATED);
  }
  const v1::Job job = Submit(*stub, CavityRequest(100.0), kAlice);
  EXPECT_EQ(job.owner(), "alice");
  v1::Job out;
  v1::GetRequest get;
  get.set_job_id(job.id());
  EXPECT_EQ(stub->Get(Context(kBob).get(), get, &out).error_code(), StatusCode::NOT_FOUND);
  v1::CancelRequest cancel;
  cancel.set_job_id(job.id());
  EXPECT_EQ(stub->Cancel(Context(kBob).get(), cancel, &out).error_code(), StatusCode::NOT_FOUND);
  v1::ListFilesRequest files;
  files.set_job_id(job.id());
  v1::ListFilesResponse files_reply;
  EXPECT_EQ(stub->ListFiles(Context(kBob).get(), files, &files_reply).error_code(),
            StatusCode::NOT_FOUND);
  {
    auto context = Context(kBob);
    v1::WatchRequest watch;
    watch.set_job_id(job.id());
    auto reader = stub->Watch(context.get(), watch);
    v1::WatchEvent event;
    EXPECT_FALSE(reader->Read(&event));
    EXPECT_EQ(reader->Finish().error_code(), StatusCode::NOT_FOUND);
  }
  {
    auto context = Context(kBob);
    v1::FetchRequest fetch;
    fetch.set_job_id(job.id());
    auto reader = stub->Fetch(context.get(), fetch);
    v1::FileChunk chunk;
    EXPECT_FALSE(reader->Read(&chunk));
    EXPECT_EQ(reader->Finish().error_code(), StatusCode::NOT_FOUND);
  }
  v1::ListResponse list;
  ASSERT_TRUE(stub->List(Context(kBob).get(), v1::ListRequest(), &list).ok());
  EXPECT_EQ(list.jobs_size(), 0);
  ASSERT_TRUE(stub->List(Context(kAlice).get(), v1::ListRequest(), &list).ok());
  ASSERT_EQ(list.jobs_size(), 1);
  ASSERT_TRUE(stub->Get(Context(kAlice).get(), get, &out).ok());
  EXPECT_NE(out.state(), v1::CANCELLED);  // bob's cancel changed nothing
  ASSERT_TRUE(stub->Cancel(Context(kAlice).get(), cancel, &out).ok());
  EXPECT_EQ(WaitFinished(*stub, job.id(), kAlice).state(), v1::CANCELLED);
}

TEST(Daemon, RetriedSubmitWithTheSameRequestIdQueuesOnce) {
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", {"--max-concurrent", "1"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  auto request = CavityRequest(0.05);
  request.set_client_request_id("retry-me");
  const v1::Job first = Submit(*stub, request);
  const v1::Job second = Submit(*stub, request);
  EXPECT_EQ(first.id(), second.id());
  v1::ListResponse list;
  ASSERT_TRUE(stub->List(Context().get(), v1::ListRequest(), &list).ok());
  EXPECT_EQ(list.jobs_size(), 1);
}

TEST(Daemon, SubmitWatchFetchEndToEnd) {
  REQUIRE_SOLVER();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data");
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  const v1::Job job = Submit(*stub, CavityRequest(0.3));
  auto events = WatchAll(*stub, job.id());
  ASSERT_FALSE(events.empty());
  ASSERT_TRUE(events.back().has_state()) << daemon.Log();
  EXPECT_EQ(events.back().state().state(), v1::COMPLETED) << events.back().state().reason();
  int progress = 0;
  int64_t last_seq = 0;
  for (const auto& event : events) {
    if (event.has_gap()) continue;
    EXPECT_GE(event.seq(), last_seq);
    last_seq = event.seq();
    if (event.has_progress()) ++progress;
  }
  EXPECT_GT(progress, 0);
  // A late watch of the finished job: its final state as the summary (seq 0), then every event
  // after from_seq, read from the job's watch log, and the end (issue 38: only the final state).
  auto late = WatchAll(*stub, job.id());
  ASSERT_EQ(late.size(), events.size());
  EXPECT_EQ(late[0].seq(), 0);
  EXPECT_EQ(late[0].state().state(), v1::COMPLETED);
  for (size_t i = 1; i < late.size(); ++i) {
    EXPECT_EQ(late[i].SerializeAsString(), events[i].SerializeAsString()) << i;
  }
  v1::ListFilesRequest files_request;
  files_request.set_job_id(job.id());
  v1::ListFilesResponse files;
  ASSERT_TRUE(stub->ListFiles(Context().get(), files_request, &files).ok());
  std::map<std::string, int64_t> sizes;
  for (const auto& f : files.files()) sizes[f.path()] = f.size();
  ASSERT_TRUE(sizes.count("summary.json")) << files.DebugString();
  v1::FetchRequest fetch;
  fetch.set_job_id(job.id());
  auto context = Context();
  auto reader = stub->Fetch(context.get(), fetch);
  std::map<std::string, std::string> fetched;
  v1::FileChunk chunk;
  while (reader->Read(&chunk)) {
    EXPECT_LE(chunk.data().size(), 1u << 20);
    EXPECT_EQ(chunk.offset(), static_cast<int64_t>(fetched[chunk.path()].size()));
    fetched[chunk.path()] += chunk.data();
  }
  ASSERT_TRUE(reader->Finish().ok());
  for (const auto& [path, size] : sizes) {
    EXPECT_EQ(static_cast<int64_t>(fetched[path].size()), size) << path;
  }
  std::ifstream summary(job.results_dir() + "/summary.json");
  std::string text((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
  EXPECT_EQ(fetched["summary.json"], text);
  EXPECT_NE(text.find("completed"), std::string::npos);
}

TEST(Daemon, LastSeqIsTheLastNumberIssuedNotAReservedBlock) {
  REQUIRE_SOLVER();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data");
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  const v1::Job job = Submit(*stub, CavityRequest(0.1));
  const auto events = WatchAll(*stub, job.id());
  ASSERT_FALSE(events.empty());
  ASSERT_TRUE(events.back().has_state());
  const int64_t last = events.back().seq();
  for (const auto& event : events) {
    if (event.has_state() && event.seq() > 0) {
      EXPECT_EQ(event.state().job().last_seq(), event.seq()) << event.DebugString();
    }
  }
  v1::GetRequest get;
  get.set_job_id(job.id());
  v1::Job got;
  ASSERT_TRUE(stub->Get(Context().get(), get, &got).ok());
  EXPECT_EQ(got.last_seq(), last);
  v1::ListResponse list;
  ASSERT_TRUE(stub->List(Context().get(), v1::ListRequest(), &list).ok());
  ASSERT_EQ(list.jobs_size(), 1);
  EXPECT_EQ(list.jobs(0).last_seq(), last);
  // A late watch of the finished job from that number: the summary alone, numbered 0.
  const auto late = WatchAll(*stub, job.id(), "", last);
  ASSERT_EQ(late.size(), 1u);
  EXPECT_EQ(late[0].seq(), 0);
  EXPECT_EQ(late[0].state().job().last_seq(), last);
}

TEST(Daemon, CancelStopsARunningJobAndKeepsPartialResults) {
  REQUIRE_SOLVER();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data");
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  const v1::Job job = Submit(*stub, CavityRequest(1.0e4));
  WaitForProgress(*stub, job.id());
  v1::CancelRequest cancel;
  cancel.set_job_id(job.id());
  v1::Job reply;
  ASSERT_TRUE(stub->Cancel(Context().get(), cancel, &reply).ok());
  const v1::Job done = WaitFinished(*stub, job.id());
  EXPECT_EQ(done.state(), v1::CANCELLED) << done.reason();
  EXPECT_GT(done.step(), 0);
  EXPECT_TRUE(fs::exists(job.results_dir() + "/summary.json"));
}

TEST(Daemon, HundredWatchersOfOneJobAllSeeItFinish) {
  REQUIRE_SOLVER();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data");
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  auto request = CavityRequest(0.3);
  request.add_overrides("output.fields_every=0.02");
  const v1::Job job = Submit(*stub, request);
  constexpr int kWatchers = 100;
  std::atomic<int> completed{0};
  std::vector<std::thread> watchers;
  for (int w = 0; w < kWatchers; ++w) {
    watchers.emplace_back([&, w] {
      auto context = Context();
      v1::WatchRequest watch;
      watch.set_job_id(job.id());
      watch.set_include_snapshots(w % 2 == 0);
      watch.set_snapshot_max_width(8);
      watch.set_snapshot_max_height(8);
      auto reader = stub->Watch(context.get(), watch);
      v1::WatchEvent event, last;
      while (reader->Read(&event)) {
        if (event.has_snapshot()) {
          EXPECT_LE(event.snapshot().nx(), 7);
          EXPECT_EQ(event.snapshot().values_size(),
                    (event.snapshot().nx() + 1) * (event.snapshot().ny() + 1));
        }
        last = event;
      }
      if (reader->Finish().ok() && last.has_state() && last.state().state() == v1::COMPLETED) {
        ++completed;
      }
    });
  }
  for (auto& t : watchers) t.join();
  EXPECT_EQ(completed.load(), kWatchers) << daemon.Log();
  EXPECT_TRUE(daemon.Healthy());
}

TEST(Daemon, TwoHundredQueuedJobsDrainWithinTheConcurrencyLimit) {
  REQUIRE_SOLVER();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", {"--max-concurrent", "2", "--log-level", "warn"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  constexpr int kJobs = 200;
  std::vector<std::string> ids;
  for (int i = 0; i < kJobs; ++i) {
    auto request = CavityRequest(0.02, "tiny-" + std::to_string(i));
    request.set_priority(i % 3);
    ids.push_back(Submit(*stub, request).id());
  }
  std::vector<std::pair<double, int>> edges;  // (time, +1 start / -1 finish)
  for (const auto& id : ids) {
    const v1::Job job = WaitFinished(*stub, id);
    EXPECT_EQ(job.state(), v1::COMPLETED) << id << ": " << job.reason();
    EXPECT_EQ(job.attempts(), 1);
    edges.emplace_back(job.started_time(), +1);
    edges.emplace_back(job.finished_time(), -1);
  }
  std::sort(edges.begin(), edges.end());  // at equal times a finish (-1) comes before a start
  int running = 0, peak = 0;
  for (const auto& [time, delta] : edges) {
    running += delta;
    peak = std::max(peak, running);
  }
  EXPECT_LE(peak, 2);
  EXPECT_EQ(peak, 2);  // the limit was used, not just respected
}

// dt = 0.05 on the 16 x 16 cavity: U dt / h = 0.8, outside the accuracy envelope's 0.64. The job
// record carries the warning and the "auto" choices from admission on (Get), and still after a
// restart of the daemon;
// with accuracy.strict = true the same scene is INVALID_ARGUMENT naming time.dt.
TEST(Daemon, JobRecordCarriesTheAccuracyWarningsThroughGetAndARestart) {
  TempDir dir;
  const std::string data = dir.path() + "/data";
  auto request = CavityRequest(0.1, "outside");
  request.add_overrides("time.dt=0.05");
  auto check = [](const v1::Job& job) {
    ASSERT_EQ(job.warnings_size(), 1);
    const v1::AccuracyWarning& w = job.warnings(0);
    EXPECT_EQ(w.setting(), "U dt / h");
    EXPECT_DOUBLE_EQ(w.value(), 0.8);
    EXPECT_EQ(w.allowed(), "<= 0.64");
    EXPECT_EQ(w.key(), "time.dt");
    EXPECT_EQ(w.current(), "0.05");
    EXPECT_EQ(w.suggested(), "0.025");
    EXPECT_NE(w.source().find("work_precision.md"), std::string::npos);
    // And what the scene's "auto" coupling and particle mesh became (no particles: rule 1 of
    // scene/auto_coupling.h and of scene/auto_particle_mesh.h).
    ASSERT_EQ(job.numerics_size(), 2);
    EXPECT_EQ(job.numerics(1).key(), "particle_mesh.kind");
    EXPECT_EQ(job.numerics(1).value(), "collocation");
    EXPECT_EQ(job.numerics(1).rule(), "no particles");
    EXPECT_EQ(job.numerics(0).key(), "splitting.constraint");
    EXPECT_EQ(job.numerics(0).value(), "incremental");
    EXPECT_EQ(job.numerics(0).rule(), "no particles");
    ASSERT_GE(job.numerics(0).numbers_size(), 1);
    EXPECT_EQ(job.numerics(0).numbers(0).name(), "nu dt / h^2");
    EXPECT_DOUBLE_EQ(job.numerics(0).numbers(0).value(), 0.01 * 0.05 / (0.0625 * 0.0625));
  };
  std::string id;
  {
    // The one solver slot is taken by a long job, so this one stays queued: a queued job already
    // shows its warnings.
    DaemonProcess daemon(data, {"--max-concurrent", "1"});
    ASSERT_TRUE(daemon.Start()) << daemon.Log();
    auto stub = daemon.Stub();
    Submit(*stub, CavityRequest(1.0e4, "blocker"));
    const v1::Job job = Submit(*stub, request);
    check(job);
    id = job.id();
    v1::GetRequest get;
    get.set_job_id(id);
    v1::Job out;
    ASSERT_TRUE(stub->Get(Context().get(), get, &out).ok());
    EXPECT_EQ(out.state(), v1::QUEUED);
    check(out);
    EXPECT_EQ(Submit(*stub, CavityRequest(0.1, "inside")).warnings_size(), 0);

    auto strict = request;
    strict.add_overrides("accuracy.strict=true");
    auto context = Context();
    v1::Job rejected;
    const grpc::Status status = stub->Submit(context.get(), strict, &rejected);
    EXPECT_EQ(status.error_code(), StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(status.error_message().find("time.dt"), std::string::npos) << status.error_message();
    EXPECT_NE(status.error_message().find("accuracy.strict"), std::string::npos);
    daemon.Kill(SIGKILL);
    daemon.Wait();
  }
  DaemonProcess daemon(data, {"--max-concurrent", "1"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  v1::GetRequest get;
  get.set_job_id(id);
  v1::Job out;
  ASSERT_TRUE(stub->Get(Context().get(), get, &out).ok());
  check(out);
}

TEST(Daemon, KillNineAndRestartResumesRunningAndKeepsQueued) {
  REQUIRE_SOLVER();
  TempDir dir;
  const std::string data = dir.path() + "/data";
  auto request = CavityRequest(1.5);
  request.add_overrides("output.checkpoint_every=0.2");
  request.add_overrides("output.fields_every=0.5");
  std::string reference_dir, resumed_dir, queued_id, running_id;
  {
    // The reference: the same scene without interruption, in its own data directory.
    TempDir ref;
    // Same OpenMP team size in every run: reductions in another order round differently.
    DaemonProcess daemon(ref.path() + "/data", {"--solver-threads", "2"});
    ASSERT_TRUE(daemon.Start()) << daemon.Log();
    auto stub = daemon.Stub();
    const v1::Job job = Submit(*stub, request);
    ASSERT_EQ(WaitFinished(*stub, job.id()).state(), v1::COMPLETED);
    reference_dir = dir.path() + "/reference";
    fs::copy(job.results_dir(), reference_dir, fs::copy_options::recursive);
  }
  {
    DaemonProcess daemon(data, {"--max-concurrent", "1", "--solver-threads", "2"});
    ASSERT_TRUE(daemon.Start()) << daemon.Log();
    auto stub = daemon.Stub();
    const v1::Job running = Submit(*stub, request);
    const v1::Job queued = Submit(*stub, CavityRequest(0.05, "stays-queued"));
    running_id = running.id();
    queued_id = queued.id();
    resumed_dir = running.results_dir();
    // Wait for a checkpoint of the running job, then kill the daemon without warning.
    while (!fs::exists(resumed_dir + "/checkpoint.h5")) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    daemon.Kill(SIGKILL);
    EXPECT_EQ(daemon.Wait(), 128 + SIGKILL);
  }
  {
    DaemonProcess daemon(data, {"--max-concurrent", "1", "--solver-threads", "2"});
    ASSERT_TRUE(daemon.Start()) << daemon.Log();
    auto stub = daemon.Stub();
    const v1::Job resumed = WaitFinished(*stub, running_id);
    EXPECT_EQ(resumed.state(), v1::COMPLETED) << resumed.reason();
    EXPECT_EQ(resumed.attempts(), 2);
    EXPECT_NE(daemon.Log().find("job " + running_id + ": solver pid"), std::string::npos);
    EXPECT_NE(daemon.Log().find("started with --resume"), std::string::npos) << daemon.Log();
    const v1::Job later = WaitFinished(*stub, queued_id);
    EXPECT_EQ(later.state(), v1::COMPLETED);
    EXPECT_EQ(later.attempts(), 1);
    EXPECT_GE(later.started_time(), resumed.finished_time());
  }
  // Final results equal the uninterrupted run's: every field snapshot, bit for bit.
  int compared = 0;
  for (const auto& entry : fs::directory_iterator(reference_dir + "/fields")) {
    const std::string name = entry.path().filename().string();
    const auto expected = ReadFieldSnapshot(entry.path().string());
    const auto actual = ReadFieldSnapshot(resumed_dir + "/fields/" + name);
    EXPECT_EQ(actual.step, expected.step) << name;
    for (const auto& [field, array] : expected.fields) {
      ASSERT_TRUE(actual.fields.count(field)) << name << " " << field;
      EXPECT_EQ(actual.fields.at(field).values, array.values) << name << " " << field;
    }
    ++compared;
  }
  EXPECT_GE(compared, 3);
}

// The daemon reserves watch numbers in blocks; after a kill -9 the next one must still know the
// last number it issued: a watcher that saw every event reconnects and is told of no Gap, Get
// reports that number, and the next event takes the number right after it.
TEST(Daemon, AfterKillNineAWatcherThatSawEverythingIsToldOfNoGap) {
  REQUIRE_SOLVER();
  TempDir dir;
  const std::string data = dir.path() + "/data";
  std::string blocker_id, queued_id;
  int64_t seen = 0;
  {
    DaemonProcess daemon(data, {"--max-concurrent", "1"});
    ASSERT_TRUE(daemon.Start()) << daemon.Log();
    auto stub = daemon.Stub();
    queued_id = Submit(*stub, CavityRequest(0.05, "retried")).id();
    const int64_t first_run = WaitFinished(*stub, queued_id).last_seq();
    auto blocker = CavityRequest(1.0e4, "blocker");
    blocker.set_priority(10);  // runs first again after the restart
    blocker_id = Submit(*stub, blocker).id();
    while (GetJob(*stub, blocker_id).state() != v1::RUNNING) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    // Retried behind the blocker, the job stays queued: its one new event (QUEUED again) took a
    // number of a freshly reserved block, and the watcher can see every event before the kill.
    v1::RetryRequest retry;
    retry.add_job_ids(queued_id);
    v1::RetryResponse retried;
    ASSERT_TRUE(stub->Retry(Context().get(), retry, &retried).ok());
    const int64_t issued = GetJob(*stub, queued_id).last_seq();
    ASSERT_EQ(issued, first_run + 1);
    auto context = Context();
    v1::WatchRequest watch;
    watch.set_job_id(queued_id);
    auto reader = stub->Watch(context.get(), watch);
    v1::WatchEvent event;
    while (seen < issued && reader->Read(&event)) seen = std::max(seen, event.seq());
    ASSERT_EQ(seen, issued);
    daemon.Kill(SIGKILL);
    EXPECT_EQ(daemon.Wait(), 128 + SIGKILL);
    context->TryCancel();
    reader->Finish();
  }
  DaemonProcess daemon(data, {"--max-concurrent", "1"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  EXPECT_EQ(GetJob(*stub, queued_id).last_seq(), seen);
  auto context = Context();
  v1::WatchRequest watch;
  watch.set_job_id(queued_id);
  watch.set_from_seq(seen);
  auto reader = stub->Watch(context.get(), watch);
  std::vector<int64_t> seqs;
  v1::WatchEvent event;
  ASSERT_TRUE(reader->Read(&event));  // attached: later events reach this watcher
  EXPECT_FALSE(event.has_gap()) << event.DebugString();
  seqs.push_back(event.seq());
  for (const std::string& id : {queued_id, blocker_id}) {
    v1::CancelRequest cancel;
    cancel.set_job_id(id);
    v1::Job reply;
    ASSERT_TRUE(stub->Cancel(Context().get(), cancel, &reply).ok());
  }
  while (reader->Read(&event)) {
    EXPECT_FALSE(event.has_gap()) << event.DebugString();
    seqs.push_back(event.seq());
  }
  EXPECT_TRUE(reader->Finish().ok());
  // The current state (a summary, numbered 0), then the cancel with the next number.
  EXPECT_EQ(seqs, (std::vector<int64_t>{0, seen + 1}));
  EXPECT_EQ(WaitFinished(*stub, blocker_id).state(), v1::CANCELLED);
}

}  // namespace
}  // namespace dlmfd::testing
