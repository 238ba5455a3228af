// Issue 14 points 4-6 against the real daemon on loopback (its SQLite store, the real solver):
// the Table rpc of a study, the solver log and inputs after the end, Delete, SetPriority,
// Hold/Release, the disk quota and the per-job limits; and the store's schema 4 and the typing of
// parameters as units.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include "dlmfd/io/diagnostics_csv.h"
#include "dlmfd/solver/run_summary.h"
#include "job_store.h"
#include "job_table.h"
#include "support/daemon_process.h"
#include "support/store_fixtures.h"

namespace dlmfd::testing {
namespace {
namespace fs = std::filesystem;
using grpc::StatusCode;
using server::JobRecord;
using server::JobState;
using server::JobStore;

// Two disks settling in a closed box, 16 x 32 cells, 20 steps: a fraction of a second.
std::string PairScene() {
  return "title = \"two disks settling\"\n"
         "gravity = [0.0, -981.0]\n"
         "[domain]\nsize = [1.0, 2.0]\nh = 0.0625\n"
         "[domain.boundary]\nleft = { type = \"wall\" }\nright = { type = \"wall\" }\n"
         "bottom = { type = \"wall\" }\ntop = { type = \"wall\" }\n"
         "[fluid]\ndensity = 1.0\nviscosity = 0.1\n"
         "[time]\ndt = 0.002\nend = 0.04\n"
         "[[particles]]\ncenter = [0.5, 1.5]\ndiameter = 0.25\ndensity = 1.5\n"
         "[[particles]]\ncenter = [0.5, 1.0]\ndiameter = 0.25\ndensity = 1.5\n"
         "[particle_mesh]\nh = 0.0625\n"
         "[output]\nfields_every = 0\nparticles_every = 0\ncheckpoint_every = 0\n";
}

void AwaitState(v1::Jobs::Stub& stub, const std::string& id, v1::JobState state) {
  while (GetJob(stub, id).state() != state)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

TEST(StudyTable, ParametersAreTypedAsTomlReadsThem) {
  const auto int_value = server::TypedParameter("output.every=1_000");
  EXPECT_EQ(int_value.key(), "output.every");
  ASSERT_EQ(int_value.value_case(), v1::Parameter::kIntValue);
  EXPECT_EQ(int_value.int_value(), 1000);
  const auto big = server::TypedParameter("time.steps=9007199254740993");
  ASSERT_EQ(big.value_case(), v1::Parameter::kIntValue);  // int64, not rounded through a double
  EXPECT_EQ(big.int_value(), 9007199254740993LL);
  const auto real = server::TypedParameter("fluid.viscosity=1e-2");
  ASSERT_EQ(real.value_case(), v1::Parameter::kDoubleValue);
  EXPECT_EQ(real.double_value(), 0.01);
  EXPECT_EQ(server::TypedParameter("fluid.density=1.01").double_value(), 1.01);
  EXPECT_TRUE(std::isinf(server::TypedParameter("a=-inf").double_value()));
  const auto flag = server::TypedParameter("accuracy.strict=true");
  ASSERT_EQ(flag.value_case(), v1::Parameter::kBoolValue);
  EXPECT_TRUE(flag.bool_value());
  const auto text = server::TypedParameter("splitting.advection=\"wave\"");
  ASSERT_EQ(text.value_case(), v1::Parameter::kTextValue);
  EXPECT_EQ(text.text_value(), "wave");
  EXPECT_EQ(server::TypedParameter("particles.0.center=[0.5, 1.0]").text_value(), "[0.5, 1.0]");
  EXPECT_EQ(server::TypedParameter("x=1_").value_case(), v1::Parameter::kTextValue);
}

// Schema 4 (held, disk_bytes) applied over a schema 2 store (the "if version < 4" rule).
TEST(JobStoreSchemaFour, AppliesOverSchemaTwoAndHoldsPriorityAndDelete) {
  TempDir dir;
  const std::string path = dir.path() + "/jobs.db";
  {
    JobStore store(path);
    store.InsertJobs({StoreJob("old")}, "local", "");
  }
  // Back to schema 2: a store written before schemas 3 and later.
  RollBackSchema(path, 2);
  JobStore store(path);
  EXPECT_EQ(JobStore::SchemaVersion(), 11);
  auto old = store.Get("old");
  ASSERT_TRUE(old);
  EXPECT_FALSE(old->held);
  EXPECT_EQ(old->disk_bytes, 0);

  store.InsertJobs({StoreJob("a"), StoreJob("b")}, "local", "request-1");
  ASSERT_TRUE(store.SetHeld("old", true));
  ASSERT_TRUE(store.SetPriority("b", 7));
  auto next = store.NextQueued();  // old is held; b has the higher priority
  ASSERT_TRUE(next);
  EXPECT_EQ(next->id, "b");
  store.MarkRunning("b", 1.0);
  EXPECT_FALSE(store.SetHeld("b", true));  // only a QUEUED job is held
  ASSERT_TRUE(store.MarkFinished("b", JobState::kCompleted, "", 2.0));
  EXPECT_FALSE(store.SetPriority("b", 1));  // finished
  store.SetDiskBytes("b", 12345);
  EXPECT_EQ(store.Get("b")->disk_bytes, 12345);

  // Deleting a job of a request keeps the request for the rest; deleting all forgets it.
  store.Delete({"a"});
  EXPECT_FALSE(store.Get("a"));
  ASSERT_EQ(store.FindRequest("local", "request-1").size(), 1u);
  store.Delete({"b"});
  EXPECT_TRUE(store.FindRequest("local", "request-1").empty());
  auto again = store.InsertJobs({StoreJob("c")}, "local", "request-1");
  EXPECT_FALSE(again.existed);
  EXPECT_EQ(store.OwnerJobs("local").size(), 2u);  // old and c
}

// A study over the viscosity: one row per point, the parameter typed, the summary's quantities
// as in the results' summary.json, the true minimum gap that of every step of diagnostics.csv.
TEST(StudyTable, StudyRowsCarryTypedParametersAndTheSummary) {
  REQUIRE_SOLVER();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data");
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  v1::SubmitStudyRequest study;
  study.set_scene(PairScene());
  study.set_name("pair");
  auto* axis = study.add_axes();
  axis->set_key("fluid.viscosity");
  axis->add_values("0.1");
  axis->add_values("0.2");
  v1::SubmitStudyResponse submitted;
  {
    auto context = Context();
    ASSERT_TRUE(stub->SubmitStudy(context.get(), study, &submitted).ok());
  }
  for (const auto& job : submitted.jobs()) {
    ASSERT_EQ(WaitFinished(*stub, job.id()).state(), v1::COMPLETED);
  }
  v1::TableRequest request;
  request.set_study_id(submitted.study_id());
  v1::TableResponse table;
  {
    auto context = Context();
    const grpc::Status status = stub->Table(context.get(), request, &table);
    ASSERT_TRUE(status.ok()) << status.error_message();
  }
  ASSERT_EQ(table.rows_size(), 2);
  for (int k = 0; k < 2; ++k) {
    const v1::TableRow& row = table.rows(k);
    EXPECT_EQ(row.job_id(), submitted.jobs(k).id());
    ASSERT_EQ(row.parameters_size(), 1);
    EXPECT_EQ(row.parameters(0).key(), "fluid.viscosity");
    ASSERT_EQ(row.parameters(0).value_case(), v1::Parameter::kDoubleValue);
    EXPECT_EQ(row.parameters(0).double_value(), k == 0 ? 0.1 : 0.2);
    ASSERT_TRUE(row.has_summary());
    EXPECT_EQ(row.status(), "completed");
    EXPECT_EQ(row.steps(), 20);
    const std::string results = submitted.jobs(k).results_dir();
    const solver::RunSummary summary =
        solver::ReadRunSummary(results + "/" + solver::kRunSummaryFile);
    EXPECT_EQ(row.fall_speed(), summary.fall_speed);
    EXPECT_EQ(row.reynolds(), summary.reynolds);
    EXPECT_GT(row.fall_speed(), 0.0);  // the disks fall
    // Re = rho U D / eta with the row's own numbers.
    EXPECT_NEAR(row.reynolds(), 1.0 * row.fall_speed() * 0.25 / (k == 0 ? 0.1 : 0.2), 1e-12);
    EXPECT_EQ(row.deborah(), 0.0);  // Newtonian
    EXPECT_TRUE(std::isnan(row.max_tra()));
    ASSERT_EQ(row.particles_size(), 2);
    EXPECT_EQ(row.particles(0).radius(), 0.125);
    EXPECT_EQ(row.particles(1).y(), summary.particles[1].position[1]);
    EXPECT_EQ(row.particles(1).angle(),
              summary.particles[1].angle);  // theta, as the solver wrote it
    EXPECT_FALSE(std::isnan(row.particles(1).angle()));
    // The true minimum gap over the run: the smallest pair gap of every step (uncapped: 0.25 at
    // the start, beyond the cell size 2 R + 1.5 h = 0.34375 minus 2 R).
    const DiagnosticsTable diagnostics = ReadDiagnostics(results + "/diagnostics.csv");
    const int column = diagnostics.Column("particle_pair_gap");
    ASSERT_GE(column, 0);
    double smallest = INFINITY;
    for (const auto& r : diagnostics.rows) smallest = std::min(smallest, r[column]);
    EXPECT_EQ(row.min_gap(), smallest);
    EXPECT_LE(row.min_gap(), 0.25);
    EXPECT_GT(row.min_gap(), 0.2);
  }
  // A job named instead of a study; a queued job has no summary yet; another user's job is not
  // found; neither or both selectors is an invalid request.
  v1::TableRequest by_job;
  by_job.add_job_ids(submitted.jobs(1).id());
  v1::TableResponse one;
  {
    auto context = Context();
    ASSERT_TRUE(stub->Table(context.get(), by_job, &one).ok());
  }
  ASSERT_EQ(one.rows_size(), 1);
  EXPECT_EQ(one.rows(0).job_id(), submitted.jobs(1).id());
  v1::TableRequest both = by_job;
  both.set_study_id(submitted.study_id());
  v1::TableResponse none;
  {
    auto context = Context();
    EXPECT_EQ(stub->Table(context.get(), both, &none).error_code(), StatusCode::INVALID_ARGUMENT);
  }
  v1::TableRequest unknown;
  unknown.set_study_id("s-unknown");
  {
    auto context = Context();
    EXPECT_EQ(stub->Table(context.get(), unknown, &none).error_code(), StatusCode::NOT_FOUND);
  }
}

// The solver log of a finished job is served whole, with finished set; the inputs as submitted and
// as run are fetchable.
TEST(JobLogAndInputs, ServedAfterTheEnd) {
  REQUIRE_SOLVER();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data");
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  v1::SubmitRequest submit;
  submit.set_scene(CavityScene(0.05));
  submit.add_overrides("fluid.viscosity=0.02");
  v1::Job job;
  {
    auto context = Context();
    ASSERT_TRUE(stub->Submit(context.get(), submit, &job).ok());
  }
  ASSERT_EQ(WaitFinished(*stub, job.id()).state(), v1::COMPLETED);
  const std::string log_file = dir.path() + "/data/jobs/" + job.id() + "/solver.log";
  std::ifstream in(log_file);
  const std::string on_disk((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(on_disk.empty());
  std::string read;
  for (;;) {
    v1::ReadLogRequest request;
    request.set_job_id(job.id());
    request.set_offset(static_cast<int64_t>(read.size()));
    request.set_max_bytes(100);  // in pieces
    v1::LogChunk chunk;
    auto context = Context();
    ASSERT_TRUE(stub->ReadLog(context.get(), request, &chunk).ok());
    EXPECT_TRUE(chunk.finished());
    EXPECT_EQ(chunk.size(), static_cast<int64_t>(on_disk.size()));
    EXPECT_EQ(chunk.offset(), static_cast<int64_t>(read.size()));
    EXPECT_LE(chunk.data().size(), 100u);
    read += chunk.data();
    if (chunk.data().empty()) break;
  }
  EXPECT_EQ(read, on_disk);
  EXPECT_NE(read.find("completed after 5 steps"), std::string::npos) << read;
  {
    v1::ReadLogRequest request;
    request.set_job_id(job.id());
    request.set_max_bytes(2 << 20);
    v1::LogChunk chunk;
    auto context = Context();
    EXPECT_EQ(stub->ReadLog(context.get(), request, &chunk).error_code(),
              StatusCode::INVALID_ARGUMENT);
  }
  v1::GetInputsRequest inputs_request;
  inputs_request.set_job_id(job.id());
  v1::JobInputs inputs;
  {
    auto context = Context();
    ASSERT_TRUE(stub->GetInputs(context.get(), inputs_request, &inputs).ok());
  }
  EXPECT_EQ(inputs.scene(), CavityScene(0.05));
  ASSERT_EQ(inputs.overrides_size(), 1);
  EXPECT_EQ(inputs.overrides(0), "fluid.viscosity=0.02");
  std::ifstream as_run(job.results_dir() + "/scene.toml");
  const std::string scene_toml((std::istreambuf_iterator<char>(as_run)),
                               std::istreambuf_iterator<char>());
  EXPECT_EQ(inputs.scene_as_run(), scene_toml);
  EXPECT_NE(inputs.scene_as_run().find("viscosity = 0.02"), std::string::npos)
      << inputs.scene_as_run();
}

// Delete: a running job only with force (cancelled first); records and directories go; another
// user's job is not found; a retried client_request_id of deleted jobs makes new ones.
TEST(JobHousekeeping, DeleteRemovesRecordsAndDirectories) {
  REQUIRE_SOLVER();
  TempDir dir;
  const std::string tokens = dir.path() + "/tokens";
  std::ofstream(tokens) << "alice-token-0123456789 alice\nbob-token-0123456789ab bob\n";
  DaemonProcess daemon(dir.path() + "/data", {"--tokens-file", tokens, "--max-concurrent", "1"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  const std::string alice = "alice-token-0123456789", bob = "bob-token-0123456789ab";
  const v1::Job done = SubmitScene(*stub, CavityScene(0.05), alice);
  ASSERT_EQ(WaitFinished(*stub, done.id(), alice).state(), v1::COMPLETED);
  const v1::Job running = SubmitScene(*stub, CavityScene(10000.0), alice);
  const v1::Job queued = SubmitScene(*stub, CavityScene(0.05), alice);
  for (;;) {  // running has started
    auto context = Context(alice);
    v1::GetRequest get;
    get.set_job_id(running.id());
    v1::Job now;
    ASSERT_TRUE(stub->Get(context.get(), get, &now).ok());
    if (now.state() == v1::RUNNING && now.step() > 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const fs::path jobs = fs::path(dir.path()) / "data" / "jobs";
  ASSERT_TRUE(fs::exists(jobs / done.id() / "results" / "summary.json"));
  auto remove = [&](std::vector<std::string> ids, bool force, const std::string& token,
                    v1::DeleteResponse* response) {
    v1::DeleteRequest request;
    for (const auto& id : ids) request.add_job_ids(id);
    request.set_force(force);
    auto context = Context(token);
    return stub->Delete(context.get(), request, response);
  };
  v1::DeleteResponse response;
  // Bob sees none of them; without force the running job stops the whole request.
  EXPECT_EQ(remove({done.id()}, false, bob, &response).error_code(), StatusCode::NOT_FOUND);
  const grpc::Status refused = remove({done.id(), running.id()}, false, alice, &response);
  EXPECT_EQ(refused.error_code(), StatusCode::FAILED_PRECONDITION);
  EXPECT_NE(refused.error_message().find(running.id()), std::string::npos);
  EXPECT_TRUE(fs::exists(jobs / done.id()));
  // The finished and the queued job go without force.
  ASSERT_TRUE(remove({done.id(), queued.id()}, false, alice, &response).ok());
  EXPECT_EQ(response.deleted_size(), 2);
  EXPECT_GT(response.freed_bytes(), 0);
  EXPECT_FALSE(fs::exists(jobs / done.id()));
  // With force the running job is cancelled, then deleted.
  ASSERT_TRUE(remove({running.id()}, true, alice, &response).ok());
  EXPECT_FALSE(fs::exists(jobs / running.id()));
  for (const std::string& id : {done.id(), running.id(), queued.id()}) {
    auto context = Context(alice);
    v1::GetRequest get;
    get.set_job_id(id);
    v1::Job gone;
    EXPECT_EQ(stub->Get(context.get(), get, &gone).error_code(), StatusCode::NOT_FOUND) << id;
  }
  v1::ListRequest list;
  v1::ListResponse listed;
  auto context = Context(alice);
  ASSERT_TRUE(stub->List(context.get(), list, &listed).ok());
  EXPECT_EQ(listed.jobs_size(), 0);
}

// Hold keeps a queued job from starting; release lets it start; priority reorders the queue.
TEST(JobHousekeeping, HoldReleaseAndPriority) {
  REQUIRE_SOLVER();
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data", {"--max-concurrent", "1"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  const v1::Job blocker = SubmitScene(*stub, CavityScene(10000.0));
  AwaitState(*stub, blocker.id(), v1::RUNNING);
  const v1::Job first = SubmitScene(*stub, CavityScene(0.05));
  const v1::Job second = SubmitScene(*stub, CavityScene(0.05));
  auto call = [&](auto method, const std::string& id, v1::Job* out) {
    v1::HoldRequest request;
    request.set_job_id(id);
    auto context = Context();
    return ((*stub).*method)(context.get(), request, out);
  };
  v1::Job held;
  ASSERT_TRUE(call(&v1::Jobs::Stub::Hold, first.id(), &held).ok());
  EXPECT_TRUE(held.held());
  EXPECT_EQ(held.state(), v1::QUEUED);
  EXPECT_EQ(call(&v1::Jobs::Stub::Hold, blocker.id(), &held).error_code(),
            StatusCode::FAILED_PRECONDITION);  // running
  v1::SetPriorityRequest priority;
  priority.set_job_id(second.id());
  priority.set_priority(5);
  v1::Job changed;
  {
    auto context = Context();
    ASSERT_TRUE(stub->SetPriority(context.get(), priority, &changed).ok());
  }
  EXPECT_EQ(changed.priority(), 5);
  priority.set_priority(5000);
  {
    auto context = Context();
    EXPECT_EQ(stub->SetPriority(context.get(), priority, &changed).error_code(),
              StatusCode::INVALID_ARGUMENT);
  }
  // The blocker ends: second runs and completes; first, held, stays queued.
  v1::CancelRequest cancel;
  cancel.set_job_id(blocker.id());
  {
    auto context = Context();
    ASSERT_TRUE(stub->Cancel(context.get(), cancel, &changed).ok());
  }
  ASSERT_EQ(WaitFinished(*stub, second.id()).state(), v1::COMPLETED);
  const v1::Job still = GetJob(*stub, first.id());
  EXPECT_EQ(still.state(), v1::QUEUED);
  EXPECT_TRUE(still.held());
  v1::Job released;
  ASSERT_TRUE(call(&v1::Jobs::Stub::Release, first.id(), &released).ok());
  EXPECT_FALSE(released.held());
  ASSERT_EQ(WaitFinished(*stub, first.id()).state(), v1::COMPLETED);
  priority.set_job_id(first.id());
  priority.set_priority(1);
  auto context = Context();
  EXPECT_EQ(stub->SetPriority(context.get(), priority, &changed).error_code(),
            StatusCode::FAILED_PRECONDITION);  // finished
}

// The disk quota per user, and the limits on steps, snapshots and wall time per job.
TEST(JobHousekeeping, QuotaAndLimitsAreNamedErrors) {
  REQUIRE_SOLVER();
  TempDir dir;
  const std::string tokens = dir.path() + "/tokens";
  std::ofstream(tokens) << "alice-token-0123456789 alice\nbob-token-0123456789ab bob\n";
  DaemonProcess daemon(dir.path() + "/data", {"--tokens-file", tokens, "--max-user-disk-mb", "1",
                                              "--max-steps", "2000000", "--max-snapshots", "50"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  const std::string alice = "alice-token-0123456789", bob = "bob-token-0123456789ab";
  auto submit_to = [](v1::Jobs::Stub& to, const std::string& scene, const std::string& token) {
    v1::SubmitRequest request;
    request.set_scene(scene);
    auto context = Context(token);
    v1::Job job;
    const grpc::Status status = to.Submit(context.get(), request, &job);
    return std::make_pair(status, job);
  };
  auto submit = [&](const std::string& scene, const std::string& token) {
    return submit_to(*stub, scene, token);
  };
  const auto steps = submit(CavityScene(30000.0), alice);  // 3e6 steps
  EXPECT_EQ(steps.first.error_code(), StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(steps.first.error_message().find("max_steps = 2000000"), std::string::npos)
      << steps.first.error_message();
  const auto snapshots = submit(CavityScene(1.0) + "[output]\nfields_every = 0.01\n", alice);
  EXPECT_EQ(snapshots.first.error_code(), StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(snapshots.first.error_message().find("max_snapshots = 50"), std::string::npos)
      << snapshots.first.error_message();
  // Wall time: a run of 10^6 steps is stopped after 2 s and ends FAILED naming the limit. In a
  // daemon of its own: the limit holds for every job of a daemon, and the quota's filler below
  // may take longer than 2 s (a sanitizer build on a loaded machine); what the long run writes in
  // 2 s grows with the machine's speed and must not count toward alice's quota either.
  {
    DaemonProcess timed(dir.path() + "/timed", {"--max-wall-seconds", "2"});
    ASSERT_TRUE(timed.Start()) << timed.Log();
    auto timed_stub = timed.Stub();
    const auto long_run =
        submit_to(*timed_stub, CavityScene(10000.0) + "[output]\nfields_every = 0\n", "");
    ASSERT_TRUE(long_run.first.ok()) << long_run.first.error_message();
    const v1::Job stopped = WaitFinished(*timed_stub, long_run.second.id());
    EXPECT_EQ(stopped.state(), v1::FAILED);
    EXPECT_NE(stopped.reason().find("max_wall_seconds = 2"), std::string::npos) << stopped.reason();
  }
  // Quota: 1 MiB. 21 snapshots of a 64 x 64 grid (about 0.1 MB each) fill it.
  const std::string big =
      "title = \"cavity 64x64\"\n[domain]\nsize = [1.0, 1.0]\nh = 0.015625\n"
      "[domain.boundary]\nleft = { type = \"wall\" }\n"
      "right = { type = \"wall\" }\nbottom = { type = \"wall\" }\n"
      "top = { type = \"velocity\", profile = \"uniform\", value = [1.0, 0.0] }\n"
      "[fluid]\nviscosity = 0.01\n[time]\ndt = 0.01\nend = 0.2\n"
      "[output]\nfields_every = 0.01\n";
  const auto filler = submit(big, alice);
  ASSERT_TRUE(filler.first.ok()) << filler.first.error_message();
  const v1::Job filled = WaitFinished(*stub, filler.second.id(), alice);
  ASSERT_EQ(filled.state(), v1::COMPLETED) << filled.reason();
  EXPECT_GT(filled.disk_bytes(), 1 << 20);
  const auto over = submit(CavityScene(0.05), alice);
  EXPECT_EQ(over.first.error_code(), StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(over.first.error_message().find("max_user_disk_mb = 1"), std::string::npos)
      << over.first.error_message();
  EXPECT_TRUE(submit(CavityScene(0.05), bob).first.ok());  // per user
  // A retry runs a job again and writes as much: the quota holds for it too (issue 38: a retry
  // grew a user's jobs past a 50 MB quota to 333 MB).
  {
    v1::RetryRequest retry;
    retry.add_job_ids(filler.second.id());
    v1::RetryResponse retried;
    auto context = Context(alice);
    const grpc::Status refused = stub->Retry(context.get(), retry, &retried);
    EXPECT_EQ(refused.error_code(), StatusCode::RESOURCE_EXHAUSTED);
    EXPECT_NE(refused.error_message().find("max_user_disk_mb = 1"), std::string::npos)
        << refused.error_message();
    EXPECT_EQ(GetJob(*stub, filler.second.id(), alice).state(), v1::COMPLETED);
  }
  // Deleting frees the quota.
  v1::DeleteRequest request;
  request.add_job_ids(filler.second.id());
  v1::DeleteResponse response;
  {
    auto context = Context(alice);
    ASSERT_TRUE(stub->Delete(context.get(), request, &response).ok());
  }
  EXPECT_TRUE(submit(CavityScene(0.05), alice).first.ok());
}

}  // namespace
}  // namespace dlmfd::testing
