// Unit tests of the daemon's parts without a process: the SQLite store, the configuration, the
// authenticator, the watcher queue's gap rules and snapshot downsampling, the study expansion, the
// checks of result-file paths and the cutting of error messages.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>

#include "auth.h"
#include "config.h"
#include "event_hub.h"
#include "job_store.h"
#include "result_files.h"
#include "service_error.h"
#include "study_expansion.h"
#include "support/daemon_process.h"
#include "watch_log.h"
#include "watcher_queue.h"

namespace dlmfd::server {
namespace {

JobRecord MakeJob(const std::string& id, int priority, const std::string& owner = "local") {
  JobRecord job;
  job.id = id;
  job.name = id;
  job.owner = owner;
  job.priority = priority;
  job.tags = {"t1", "t2"};
  job.results_dir = "/tmp/" + id;
  job.scene = "scene text";
  job.overrides = {"fluid.viscosity=0.1", "time.end=1"};
  return job;
}

TEST(JobStore, MigratesOnceAndReopens) {
  dlmfd::testing::TempDir dir;
  const std::string path = dir.path() + "/jobs.db";
  {
    JobStore store(path);
    store.InsertJobs({MakeJob("a", 0)}, "local", "");
  }
  JobStore store(path);  // a second open applies no migration twice
  auto job = store.Get("a");
  ASSERT_TRUE(job);
  EXPECT_EQ(job->overrides, (std::vector<std::string>{"fluid.viscosity=0.1", "time.end=1"}));
  EXPECT_EQ(job->tags, (std::vector<std::string>{"t1", "t2"}));
  EXPECT_EQ(job->state, JobState::kQueued);
}

// Schema 2 stores a job's accuracy warnings; a store of schema 1 gains the column, empty.
TEST(JobStore, AccuracyWarningsRoundTripAndASchemaOneStoreGainsTheColumn) {
  dlmfd::testing::TempDir dir;
  const std::string path = dir.path() + "/jobs.db";
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    const char* schema_one =
        "CREATE TABLE schema_version (version INTEGER NOT NULL);"
        "INSERT INTO schema_version (version) VALUES (1);"
        "CREATE TABLE jobs (ordinal INTEGER PRIMARY KEY AUTOINCREMENT, id TEXT NOT NULL UNIQUE,"
        " name TEXT NOT NULL, owner TEXT NOT NULL, state INTEGER NOT NULL,"
        " reason TEXT NOT NULL DEFAULT '', priority INTEGER NOT NULL DEFAULT 0,"
        " sweep_id TEXT NOT NULL DEFAULT '', created_time REAL NOT NULL DEFAULT 0,"
        " started_time REAL NOT NULL DEFAULT 0, finished_time REAL NOT NULL DEFAULT 0,"
        " step INTEGER NOT NULL DEFAULT 0, time REAL NOT NULL DEFAULT 0,"
        " end_time REAL NOT NULL DEFAULT 0, attempts INTEGER NOT NULL DEFAULT 0,"
        " results_dir TEXT NOT NULL, scene TEXT NOT NULL, overrides TEXT NOT NULL DEFAULT '',"
        " client_request_id TEXT NOT NULL DEFAULT '', last_seq INTEGER NOT NULL DEFAULT 0,"
        " cancel_requested INTEGER NOT NULL DEFAULT 0);"
        "CREATE TABLE job_tags (job_id TEXT NOT NULL, tag TEXT NOT NULL,"
        " PRIMARY KEY (job_id, tag));"
        "CREATE TABLE requests (owner TEXT NOT NULL, request_key TEXT NOT NULL,"
        " job_ids TEXT NOT NULL, PRIMARY KEY (owner, request_key));"
        "INSERT INTO jobs (id, name, owner, state, results_dir, scene)"
        " VALUES ('old', 'old', 'local', 1, '/tmp/old', 'scene text');";
    ASSERT_EQ(sqlite3_exec(db, schema_one, nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(db);
  }
  JobStore store(path);
  auto old = store.Get("old");
  ASSERT_TRUE(old);
  EXPECT_TRUE(old->warnings.empty());

  JobRecord job = MakeJob("warned", 0);
  job.warnings = {{"nu dt / h^2", 0.44236800000000003, "<= 0.195", "time.dt", "0.0004",
                   "0.00013333333333333334", "docs/evidence/work_precision.md (d) dt ladder"},
                  {"D / h (particles.0, the smallest of 2 below the bound)", 19.2, ">= 120",
                   "domain.h", "0.010416666666666666", "0.001488095238095238",
                   "docs/evidence/work_precision.md (d), Which settings 3"}};
  store.InsertJobs({job}, "local", "");
  auto back = store.Get("warned");
  ASSERT_TRUE(back);
  ASSERT_EQ(back->warnings.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back->warnings[i].setting, job.warnings[i].setting);
    EXPECT_EQ(back->warnings[i].value, job.warnings[i].value);  // 17 digits: bit for bit
    EXPECT_EQ(back->warnings[i].allowed, job.warnings[i].allowed);
    EXPECT_EQ(back->warnings[i].key, job.warnings[i].key);
    EXPECT_EQ(back->warnings[i].current, job.warnings[i].current);
    EXPECT_EQ(back->warnings[i].suggested, job.warnings[i].suggested);
    EXPECT_EQ(back->warnings[i].source, job.warnings[i].source);
  }
}

// Schema 7 stores what each "auto" of a job's scene became: key, value, rule and the numbers in
// their order, each number bit for bit; a job without one reads back none.
TEST(JobStore, NumericsChoicesRoundTrip) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  JobRecord job = MakeJob("auto", 0);
  job.numerics = {
      {"splitting.constraint",
       "paper",
       "particles cross more than 0.3 of a cell a step (U_p dt / h > 0.3)",
       {{"nu dt / h^2", 0.09216}, {"U_p dt / h", 1.1916131250474034}, {"Re_p", 248.25}}}};
  store.InsertJobs({job, MakeJob("named", 0)}, "local", "");
  const auto back = store.Get("auto");
  ASSERT_TRUE(back);
  ASSERT_EQ(back->numerics.size(), 1u);
  EXPECT_EQ(back->numerics[0].key, job.numerics[0].key);
  EXPECT_EQ(back->numerics[0].value, job.numerics[0].value);
  EXPECT_EQ(back->numerics[0].rule, job.numerics[0].rule);
  EXPECT_EQ(back->numerics[0].numbers, job.numerics[0].numbers);  // 17 digits: bit for bit
  EXPECT_TRUE(store.Get("named")->numerics.empty());
}

TEST(JobStore, QueueOrderIsPriorityThenAge) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  store.InsertJobs({MakeJob("low", -5)}, "local", "");
  store.InsertJobs({MakeJob("high-old", 3)}, "local", "");
  store.InsertJobs({MakeJob("high-new", 3)}, "local", "");
  std::vector<std::string> order;
  while (auto next = store.NextQueued()) {
    order.push_back(next->id);
    store.MarkRunning(next->id, 1.0);
  }
  EXPECT_EQ(order, (std::vector<std::string>{"high-old", "high-new", "low"}));
  EXPECT_EQ(store.CountRunning(), 3);
  EXPECT_EQ(store.Get("low")->attempts, 1);
}

TEST(JobStore, RequestKeyMakesInsertIdempotentPerOwner) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  auto first = store.InsertJobs({MakeJob("a", 0)}, "local", "k1");
  auto retry = store.InsertJobs({MakeJob("b", 0)}, "local", "k1");
  EXPECT_FALSE(first.existed);
  EXPECT_TRUE(retry.existed);
  ASSERT_EQ(retry.jobs.size(), 1u);
  EXPECT_EQ(retry.jobs[0].id, "a");
  EXPECT_FALSE(store.Get("b"));
  auto other_user = store.InsertJobs({MakeJob("c", 0, "bob")}, "bob", "k1");
  EXPECT_FALSE(other_user.existed);
}

TEST(JobStore, FinishedStateIsFinal) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  store.InsertJobs({MakeJob("a", 0)}, "local", "");
  EXPECT_TRUE(store.CancelQueued("a", "cancelled", 2.0));
  EXPECT_FALSE(store.CancelQueued("a", "cancelled", 3.0));
  EXPECT_FALSE(store.MarkFinished("a", JobState::kCompleted, "", 4.0));
  EXPECT_EQ(store.Get("a")->state, JobState::kCancelled);
  EXPECT_THROW(store.MarkRunning("a", 5.0), StoreError);
}

TEST(JobStore, RestartRequeuesRunningAndHonoursRequestedCancels) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  store.InsertJobs({MakeJob("run", 0), MakeJob("cancel-me", 0), MakeJob("queued", 0)}, "local", "");
  store.MarkRunning("run", 1.0);
  store.MarkRunning("cancel-me", 1.0);
  store.SetCancelRequested("cancel-me");
  EXPECT_EQ(store.RequeueRunning(2.0), (std::vector<std::string>{"run"}));
  EXPECT_EQ(store.Get("run")->state, JobState::kQueued);
  EXPECT_EQ(store.Get("cancel-me")->state, JobState::kCancelled);
  EXPECT_EQ(store.Get("queued")->state, JobState::kQueued);
}

TEST(JobStore, ListFiltersAndPages) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  for (int i = 0; i < 5; ++i) store.InsertJobs({MakeJob("j" + std::to_string(i), 0)}, "local", "");
  auto other = MakeJob("x", 0, "bob");
  other.tags = {"special"};
  store.InsertJobs({other}, "bob", "");
  ListFilter filter;
  filter.owner = "local";
  filter.limit = 2;
  auto page = store.List(filter);
  ASSERT_EQ(page.size(), 2u);
  EXPECT_EQ(page[0].id, "j4");
  filter.before_ordinal = page[1].ordinal;
  page = store.List(filter);
  ASSERT_EQ(page.size(), 2u);
  EXPECT_EQ(page[0].id, "j2");
  filter = ListFilter{};
  filter.owner = "local";
  filter.tag = "special";
  EXPECT_TRUE(store.List(filter).empty());
  filter.owner = "bob";
  EXPECT_EQ(store.List(filter).size(), 1u);
}

std::map<std::string, std::string> gEnv;
const char* FakeEnv(const char* name) {
  auto it = gEnv.find(name);
  return it == gEnv.end() ? nullptr : it->second.c_str();
}

TEST(Config, FlagBeatsEnvironmentBeatsFileBeatsDefault) {
  dlmfd::testing::TempDir dir;
  const std::string file = dir.path() + "/dlmfdd.toml";
  std::ofstream(file) << "max_concurrent = 3\nwatcher_buffer = 99\nmax_queued = 7\n";
  gEnv = {{"DLMFD_WATCHER_BUFFER", "77"}, {"DLMFD_MAX_QUEUED", "8"}, {"HOME", dir.path()}};
  const char* argv[] = {"dlmfdd", "--config", file.c_str(), "--max-queued",
                        "9",      "--solver", "/bin/true"};
  Config config;
  ASSERT_TRUE(LoadConfig(7, argv, FakeEnv, config));
  EXPECT_EQ(config.max_concurrent, 3);         // file
  EXPECT_EQ(config.watcher_buffer, 77);        // environment over file
  EXPECT_EQ(config.max_queued, 9);             // flag over environment
  EXPECT_EQ(config.listen, "127.0.0.1:7443");  // default
  EXPECT_EQ(config.data_dir, dir.path() + "/.local/share/dlmfd");
}

TEST(Config, RejectsUnknownKeysAndBadValues) {
  dlmfd::testing::TempDir dir;
  const std::string file = dir.path() + "/dlmfdd.toml";
  std::ofstream(file) << "max_concurent = 3\n";
  gEnv = {};
  const char* argv[] = {"dlmfdd", "--config", file.c_str()};
  Config config;
  EXPECT_THROW(LoadConfig(3, argv, FakeEnv, config), ConfigError);
  const char* argv2[] = {"dlmfdd", "--max-concurrent", "0"};
  EXPECT_THROW(LoadConfig(3, argv2, FakeEnv, config), ConfigError);
  const char* argv3[] = {"dlmfdd", "--max-concurrent", "two"};
  EXPECT_THROW(LoadConfig(3, argv3, FakeEnv, config), ConfigError);
}

TEST(Config, NonLoopbackNeedsTokens) {
  gEnv = {};
  const char* argv[] = {"dlmfdd", "--listen", "0.0.0.0:7443"};
  Config config;
  EXPECT_THROW(LoadConfig(3, argv, FakeEnv, config), ConfigError);
  EXPECT_TRUE(IsLoopbackAddress("127.0.0.1:7443"));
  EXPECT_TRUE(IsLoopbackAddress("[::1]:7443"));
  EXPECT_TRUE(IsLoopbackAddress("localhost:1"));
  EXPECT_TRUE(IsLoopbackAddress("unix:/tmp/s"));
  EXPECT_FALSE(IsLoopbackAddress("[::]:7443"));
  EXPECT_FALSE(IsLoopbackAddress("10.0.0.1:7443"));
  EXPECT_FALSE(IsLoopbackAddress("128.0.0.1:7443"));
}

TEST(Auth, BearerTokensNameUsers) {
  Authenticator open(std::map<std::string, std::string>{});
  EXPECT_EQ(open.UserOfHeader(nullptr), "local");
  Authenticator auth(std::map<std::string, std::string>{{"0123456789abcdef-alice", "alice"}});
  const std::string good = "Bearer 0123456789abcdef-alice";
  const std::string wrong = "Bearer 0123456789abcdef-alicf";
  const std::string basic = "Basic 0123456789abcdef-alice";
  EXPECT_EQ(auth.UserOfHeader(&good), "alice");
  for (const std::string* header : {static_cast<const std::string*>(nullptr), &wrong, &basic}) {
    try {
      auth.UserOfHeader(header);
      ADD_FAILURE() << "accepted";
    } catch (const ServiceError& e) {
      EXPECT_EQ(e.code(), grpc::StatusCode::UNAUTHENTICATED);
    }
  }
}

v1::WatchEvent Progress(int64_t seq) {
  v1::WatchEvent event;
  event.set_seq(seq);
  event.mutable_progress()->set_step(seq);
  return event;
}

v1::WatchEvent LogEvent(const std::string& text) {
  v1::WatchEvent event;
  event.mutable_log()->set_text(text);
  return event;
}

v1::WatchEvent Snapshot(int64_t seq) {
  v1::WatchEvent event;
  event.set_seq(seq);
  auto* s = event.mutable_snapshot();
  s->set_nx(2);
  s->set_ny(2);
  for (int i = 0; i < 9; ++i) s->add_values(static_cast<float>(i));
  return event;
}

v1::WatchEvent State(int64_t seq, v1::JobState state = v1::RUNNING) {
  v1::WatchEvent event;
  event.set_seq(seq);
  event.mutable_state()->set_state(state);
  return event;
}

v1::WatchEvent Head() { return State(0); }

// What a watcher was sent after its head: "N" per event, "gap A-B" per Gap.
std::vector<std::string> Drain(WatcherQueue& queue) {
  std::vector<std::string> sent;
  v1::WatchEvent out;
  bool head = true;
  while (queue.Pop(&out) == WatcherQueue::Next::kEvent) {
    if (head) {
      EXPECT_EQ(out.seq(), 0);  // the summary
      head = false;
      continue;
    }
    sent.push_back(out.has_gap() ? "gap " + std::to_string(out.gap().from_seq()) + "-" +
                                       std::to_string(out.gap().to_seq())
                                 : std::to_string(out.seq()));
  }
  return sent;
}

std::vector<std::string> Numbers(int64_t from, int64_t to) {
  std::vector<std::string> out;
  for (int64_t seq = from; seq <= to; ++seq) out.push_back(std::to_string(seq));
  return out;
}

// Issue 38: a slow watcher lost events; they are in the log, and it reads them back from there.
TEST(WatcherQueue, ASlowWatcherCatchesUpFromTheLogAndMissesNothing) {
  dlmfd::testing::TempDir dir;
  WatchLog log(dir.path());
  WatchOptions options;
  options.capacity = 4;
  WatcherQueue queue(options, dir.path());
  EXPECT_TRUE(queue.Start(Head(), 0, 0));  // takes the send token
  for (int64_t seq = 1; seq <= 10; ++seq) {
    const v1::WatchEvent event = seq % 3 == 0 ? State(seq) : Progress(seq);
    ASSERT_TRUE(log.Append(event, {}, false));
    EXPECT_FALSE(queue.Push(event));
  }
  EXPECT_EQ(Drain(queue), Numbers(1, 10));
  EXPECT_GE(queue.overflows(), 1);
  EXPECT_EQ(queue.dropped(), 0);
}

TEST(WatcherQueue, TheCatchUpReadsItsRangeAndNamesWhatTheLogLacks) {
  dlmfd::testing::TempDir dir;
  WatchLog log(dir.path());
  for (int64_t seq : {1, 2, 4, 5, 8}) ASSERT_TRUE(log.Append(Progress(seq), {}, false));
  WatchOptions options;
  options.capacity = 2;  // chunks of one event
  WatcherQueue queue(options, dir.path());
  queue.Start(Head(), 1, 6);
  queue.Push(Progress(7));  // live, after the range
  EXPECT_EQ(Drain(queue), (std::vector<std::string>{"2", "gap 3-3", "4", "5", "gap 6-6", "7"}));
  WatcherQueue empty(options, dir.path() + "/none");
  empty.Start(Head(), 0, 3);
  EXPECT_EQ(Drain(empty), (std::vector<std::string>{"gap 1-3"}));
}

TEST(WatcherQueue, NewerSnapshotReplacesUnsentOne) {
  dlmfd::testing::TempDir dir;
  WatchOptions options;
  options.include_snapshots = true;
  WatcherQueue queue(options, dir.path());
  queue.Start(Head(), 0, 0);
  queue.Push(Snapshot(1));
  queue.Push(Progress(2));
  queue.Push(Snapshot(3));
  EXPECT_EQ(Drain(queue), (std::vector<std::string>{"2", "gap 1-1", "3"}));
  EXPECT_EQ(queue.dropped(), 1);
}

TEST(WatcherQueue, SnapshotsOnlyWhenAskedAndCancelTakesToken) {
  dlmfd::testing::TempDir dir;
  WatcherQueue queue(WatchOptions{}, dir.path());
  EXPECT_FALSE(queue.Push(Snapshot(1)));
  v1::WatchEvent out;
  EXPECT_EQ(queue.Pop(&out), WatcherQueue::Next::kEmpty);  // gives the token back
  EXPECT_TRUE(queue.Cancel());
  EXPECT_EQ(queue.Pop(&out), WatcherQueue::Next::kClosed);
  EXPECT_FALSE(queue.Push(Progress(2)));
}

// Snapshots' values live beside the log: a watcher that asks for them reads them whole, the
// others skip their numbers.
TEST(WatchLog, SnapshotsAreReadWholeOnlyByWatchersThatAskForThem) {
  dlmfd::testing::TempDir dir;
  WatchLog log(dir.path());
  ASSERT_TRUE(log.Append(Progress(1), {"progress", 10, "", 0}, false));
  ASSERT_TRUE(log.Append(Snapshot(2), {"snapshot", 10, "slurm:7", 123}, false));
  ASSERT_TRUE(log.Append(State(3), {}, true));
  ASSERT_TRUE(log.Append(Progress(4), {"progress", 0, "slurm:7", 456}, false));
  const WatchLogState state = log.Recover();
  EXPECT_EQ(state.last_seq, 4);
  EXPECT_EQ(state.high_water, (std::map<std::string, int64_t>{{"progress", 0}}));
  EXPECT_EQ(state.source_offset.at("slurm:7"), 456);
  std::vector<v1::WatchEvent> with, without;
  WatchLog::Reader(dir.path(), 0, 4, true).Next(10, with);
  WatchLog::Reader(dir.path(), 0, 4, false).Next(10, without);
  ASSERT_EQ(with.size(), 4u);
  EXPECT_EQ(with[1].snapshot().values_size(), 9);
  EXPECT_EQ(with[1].snapshot().values(8), 8.0f);
  ASSERT_EQ(without.size(), 3u);
  EXPECT_EQ(without[1].seq(), 3);
  // A record cut short by a crash is cut off, and the log goes on after the last whole one.
  const std::string path = dir.path() + "/" + WatchLog::kFile;
  std::ofstream(path, std::ios::app) << std::string("\x20\x01\x02", 3);
  EXPECT_EQ(log.Recover().last_seq, 4);
  ASSERT_TRUE(log.Append(Progress(5), {}, false));
  std::vector<v1::WatchEvent> all;
  WatchLog::Reader(dir.path(), 3, 5, false).Next(10, all);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].seq(), 5);
}

// A watcher attached to the hub at from_seq (woken by nothing: the test pops it).
std::shared_ptr<WatcherQueue> AttachedWatcher(EventHub& hub, const JobRecord& job,
                                              int64_t from_seq) {
  auto queue = std::make_shared<WatcherQueue>(WatchOptions{}, hub.LogDirectory(job.id));
  queue->SetWake([] {});
  hub.Attach(job, from_seq, queue);
  return queue;
}

// The sequence numbers the watcher got after its head; no Gap, and each state event's job has its
// own number.
std::vector<int64_t> SeqsWithoutGaps(WatcherQueue& queue) {
  std::vector<int64_t> seqs;
  v1::WatchEvent out;
  bool head = true;
  while (queue.Pop(&out) == WatcherQueue::Next::kEvent) {
    EXPECT_FALSE(out.has_gap()) << out.DebugString();
    if (head) {
      EXPECT_EQ(out.seq(), 0);
      head = false;
      continue;
    }
    seqs.push_back(out.seq());
    if (out.has_state()) {
      EXPECT_EQ(out.state().job().last_seq(), out.seq());
    }
  }
  return seqs;
}

std::vector<int64_t> Range(int64_t from, int64_t to) {
  std::vector<int64_t> out;
  for (int64_t seq = from; seq <= to; ++seq) out.push_back(seq);
  return out;
}

// A store holding one running job "a", and the directory its watch log goes to.
struct OneRunningJob {
  OneRunningJob() {
    store.InsertJobs({MakeJob("a", 0)}, "local", "");
    store.MarkRunning("a", 1.0);
  }
  EventHub::JobDirectory JobDir() const {
    return [this](const std::string& id) { return dir.path() + "/jobs/" + id; };
  }
  dlmfd::testing::TempDir dir;
  JobStore store{dir.path() + "/jobs.db"};
};

TEST(EventHub, ACleanRestartResumesRightAfterTheLastNumberIssued) {
  OneRunningJob one;
  JobStore& store = one.store;
  std::filesystem::create_directories(one.dir.path() + "/jobs/a");
  {
    EventHub hub(store, one.JobDir());
    hub.PublishState(*store.Get("a"));  // seq 1
    for (int i = 0; i < 3; ++i) hub.Publish("a", Progress(0));
    EXPECT_EQ(hub.LastIssued("a"), 4);
    hub.RecordIssued();  // the daemon's clean shutdown
  }
  EXPECT_EQ(store.Get("a")->last_seq, 4);
  // The next daemon: a watcher that saw everything reconnects and misses nothing.
  EventHub hub(store, one.JobDir());
  hub.Recover(one.dir.path() + "/watch_seq");
  auto queue = AttachedWatcher(hub, *store.Get("a"), 4);
  hub.Publish("a", Progress(0));
  store.MarkFinished("a", JobState::kCompleted, "", 2.0);
  hub.PublishState(*store.Get("a"));
  EXPECT_EQ(SeqsWithoutGaps(*queue), (std::vector<int64_t>{5, 6}));
  EXPECT_EQ(store.Get("a")->last_seq, 6);
}

// Issue 38: after a kill -9 the next daemon learns the last number from the log, and a watcher
// that reconnects with the last number it saw, or with 0, gets every event once.
TEST(EventHub, AfterAKillEveryWatcherGetsEveryEventOnceFromTheLog) {
  OneRunningJob one;
  JobStore& store = one.store;
  std::filesystem::create_directories(one.dir.path() + "/jobs/a");
  {
    EventHub hub(store, one.JobDir());
    hub.PublishState(*store.Get("a"));  // seq 1
    for (int i = 0; i < 3; ++i) hub.Publish("a", Progress(0));
    // Killed here: no RecordIssued.
  }
  EXPECT_EQ(store.Get("a")->last_seq, 0);
  EventHub hub(store, one.JobDir());
  hub.Recover(one.dir.path() + "/watch_seq");
  EXPECT_EQ(store.Get("a")->last_seq, 4);
  auto saw_all = AttachedWatcher(hub, *store.Get("a"), 4);
  auto saw_two = AttachedWatcher(hub, *store.Get("a"), 2);
  auto saw_none = AttachedWatcher(hub, *store.Get("a"), 0);
  hub.Publish("a", Progress(0));
  store.MarkFinished("a", JobState::kCompleted, "", 2.0);
  hub.PublishState(*store.Get("a"));
  EXPECT_EQ(SeqsWithoutGaps(*saw_all), (std::vector<int64_t>{5, 6}));
  EXPECT_EQ(SeqsWithoutGaps(*saw_two), Range(3, 6));
  EXPECT_EQ(SeqsWithoutGaps(*saw_none), Range(1, 6));
  EXPECT_EQ(store.Get("a")->last_seq, 6);
  // Issue 38: a watch of a finished job sent only its final state, whatever from_seq said.
  auto late = AttachedWatcher(hub, *store.Get("a"), 3);
  EXPECT_EQ(SeqsWithoutGaps(*late), Range(4, 6));
}

// Issue 38: a resumed solver sent the particle samples of the steps since its checkpoint again,
// under new numbers. Each lane goes by its step, across daemons; a fresh start counts anew.
TEST(EventHub, AResumedSolversStepsAreNotPublishedAgain) {
  OneRunningJob one;
  JobStore& store = one.store;
  std::filesystem::create_directories(one.dir.path() + "/jobs/a");
  auto particles = [](int64_t step) {
    v1::WatchEvent event;
    event.mutable_particles()->set_step(step);
    return event;
  };
  {
    EventHub hub(store, one.JobDir());
    hub.PublishState(*store.Get("a"));  // 1
    for (int64_t step : {10, 20, 30}) {
      EXPECT_TRUE(hub.Publish("a", particles(step), {"particles", step, "slurm:5", step * 100}));
    }
    EXPECT_TRUE(hub.Publish("a", Progress(0), {"progress", 30, "", 0}));  // 5
  }
  EventHub hub(store, one.JobDir());
  hub.Recover(one.dir.path() + "/watch_seq");
  hub.PublishState(*store.Get("a"));  // 6: the daemon's restart runs the job again
  EXPECT_EQ(hub.SourceOffset(*store.Get("a"), "slurm:5"), 3000);
  EXPECT_FALSE(hub.Publish("a", particles(20), {"particles", 20, "", 0}));
  EXPECT_FALSE(hub.Publish("a", particles(30), {"particles", 30, "", 0}));
  EXPECT_FALSE(hub.Publish("a", Progress(0), {"progress", 30, "", 0}));
  EXPECT_TRUE(hub.Publish("a", particles(40), {"particles", 40, "", 0}));  // 7
  EXPECT_TRUE(hub.Publish("a", LogEvent("resumed"), {}));                  // 8: no lane
  EXPECT_EQ(hub.LastIssued("a"), 8);
  // A retry that starts afresh: a new timeline, its steps published from 0 again.
  store.MarkFinished("a", JobState::kFailed, "x", 2.0);
  hub.PublishState(*store.Get("a"));  // 9
  RequeueChange change;
  change.id = "a";
  change.fresh_start = true;
  const JobRecord requeued = store.Requeue({change}).front();
  hub.PublishState(requeued, true);  // 10
  EXPECT_TRUE(hub.Publish("a", particles(10), {"particles", 10, "", 0}));
  EXPECT_EQ(hub.LastIssued("a"), 11);
}

// The store commits a final state before the hub numbers its event. A record read in between
// (Get, List) reports the number that event takes: a finished job's last_seq counts its final
// state, so a retry's first event is the number right after it.
TEST(EventHub, AJobReadAsFinishedReportsItsFinalStateEventsNumber) {
  OneRunningJob one;
  JobStore& store = one.store;
  std::filesystem::create_directories(one.dir.path() + "/jobs/a");
  EventHub hub(store, one.JobDir());
  hub.PublishState(*store.Get("a"));  // seq 1
  hub.Publish("a", Progress(0));      // seq 2
  store.MarkFinished("a", JobState::kCompleted, "", 2.0);
  const JobRecord finished = *store.Get("a");
  EXPECT_EQ(hub.ReportedLastSeq(finished), 3);  // the final state event's, still to come
  auto queue = AttachedWatcher(hub, finished, 2);
  hub.PublishState(finished);
  EXPECT_EQ(SeqsWithoutGaps(*queue), (std::vector<int64_t>{3}));
  EXPECT_EQ(hub.ChannelCount(), 0u);
  EXPECT_EQ(hub.ReportedLastSeq(finished), 3);  // the stale record: the store's number
  EXPECT_EQ(store.Get("a")->last_seq, 3);
}

// A daemon of an older version journaled its numbers in DATA/watch_seq: the next one reads them
// once and removes the directory.
TEST(EventHub, TheJournalOfAnOlderDaemonIsReadOnceAndRemoved) {
  OneRunningJob one;
  const std::string journal = one.dir.path() + "/watch_seq";
  std::filesystem::create_directories(journal);
  const int64_t seq = 37;
  std::ofstream(journal + "/a", std::ios::binary).write(reinterpret_cast<const char*>(&seq), 8);
  one.store.SetLastSeq("a", 1000);  // the end of the block it had reserved
  EventHub hub(one.store, one.JobDir());
  hub.Recover(journal);
  EXPECT_EQ(one.store.Get("a")->last_seq, 37);
  EXPECT_FALSE(std::filesystem::exists(journal));
}

TEST(Downsample, KeepsCornersAndLimits) {
  v1::Snapshot full;
  full.set_nx(8);
  full.set_ny(4);
  for (int j = 0; j <= 4; ++j) {
    for (int i = 0; i <= 8; ++i) full.add_values(static_cast<float>(10 * j + i));
  }
  auto small = DownsampleSnapshot(full, 3, 2);
  EXPECT_EQ(small.nx(), 2);
  EXPECT_EQ(small.ny(), 1);
  ASSERT_EQ(small.values_size(), 6);
  EXPECT_EQ(small.values(0), 0.0f);
  EXPECT_EQ(small.values(1), 4.0f);
  EXPECT_EQ(small.values(2), 8.0f);
  EXPECT_EQ(small.values(5), 48.0f);
  auto same = DownsampleSnapshot(full, 0, 0);
  EXPECT_EQ(same.values_size(), full.values_size());
}

v1::SubmitStudyRequest StudyOf(std::vector<std::pair<std::string, std::vector<std::string>>> axes) {
  v1::SubmitStudyRequest request;
  request.add_overrides("time.end=1");
  for (const auto& [key, values] : axes) {
    auto* axis = request.add_axes();
    axis->set_key(key);
    for (const auto& v : values) axis->add_values(v);
  }
  return request;
}

grpc::StatusCode CodeOf(const std::function<void()>& body) { return Guarded(body).error_code(); }

TEST(StudyExpansion, CartesianProductWithTheLastAxisFastest) {
  const auto points = ExpandStudy(StudyOf({{"a", {"1", "2"}}, {"b", {"x", "y", "z"}}}), 6).points;
  ASSERT_EQ(points.size(), 6u);
  EXPECT_EQ(points[0].label, "a=1,b=x");
  EXPECT_EQ(points[1].label, "a=1,b=y");
  EXPECT_EQ(points[3].label, "a=2,b=x");
  EXPECT_EQ(points[5].overrides, (std::vector<std::string>{"time.end=1", "a=2", "b=z"}));
}

TEST(StudyExpansion, InvalidAxesAndTooManyPointsAreRefusedAsAWhole) {
  using grpc::StatusCode;
  EXPECT_EQ(CodeOf([] { ExpandStudy(StudyOf({}), 10); }), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(CodeOf([] { ExpandStudy(StudyOf({{"", {"1"}}}), 10); }), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(CodeOf([] {
              ExpandStudy(StudyOf({{"a=b", {"1"}}}), 10);
            }),
            StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(CodeOf([] {
              ExpandStudy(StudyOf({{"a", {"1"}}, {"a", {"2"}}}), 10);
            }),
            StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(CodeOf([] { ExpandStudy(StudyOf({{"a", {}}}), 10); }), StatusCode::INVALID_ARGUMENT);
  const grpc::Status big = Guarded([] { ExpandStudy(StudyOf({{"a", {"1", "2", "3"}}}), 2); });
  EXPECT_EQ(big.error_code(), StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(big.error_message().find("max_queued = 2"), std::string::npos) << big.error_message();
}

TEST(ResultFiles, ListsSortedAndChecksRequestedPaths) {
  dlmfd::testing::TempDir dir;
  const std::filesystem::path root = dir.path() + "/results";
  std::filesystem::create_directories(root / "fields");
  std::ofstream(root / "summary.json") << "{}";
  std::ofstream(root / "fields" / "snap_000000.h5") << "h5";
  EXPECT_EQ(ResultFilePaths(root),
            (std::vector<std::string>{"fields/snap_000000.h5", "summary.json"}));
  EXPECT_TRUE(ResultFilePaths(root / "absent").empty());
  EXPECT_EQ(CheckedResultPath(root, "fields/./snap_000000.h5"), "fields/snap_000000.h5");
  using grpc::StatusCode;
  EXPECT_EQ(CodeOf([&] { CheckedResultPath(root, "/etc/passwd"); }), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(CodeOf([&] { CheckedResultPath(root, "fields/../../x"); }),
            StatusCode::INVALID_ARGUMENT);
  std::filesystem::create_symlink("/etc", root / "out");
  EXPECT_EQ(CodeOf([&] { CheckedResultPath(root, "out/passwd"); }), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(CodeOf([&] { CheckedResultPath(root, "absent.h5"); }), StatusCode::NOT_FOUND);
  EXPECT_EQ(CodeOf([&] { CheckedResultPath(root, "fields"); }), StatusCode::NOT_FOUND);
}

TEST(ResultFiles, SymbolicLinksAndNulBytesLeadNowhere) {
  dlmfd::testing::TempDir dir;
  const std::filesystem::path root = dir.path() + "/results";
  std::filesystem::create_directories(root / "fields");
  std::filesystem::create_directories(dir.path() + "/elsewhere");
  std::ofstream(root / "summary.json") << "{}";
  std::ofstream(dir.path() + "/elsewhere/secret") << "secret";
  std::filesystem::create_symlink(dir.path() + "/elsewhere/secret", root / "secret");
  std::filesystem::create_symlink(dir.path() + "/elsewhere", root / "elsewhere");
  std::filesystem::create_symlink(root / "summary.json", root / "fields" / "summary.json");
  EXPECT_EQ(ResultFilePaths(root), (std::vector<std::string>{"summary.json"}));
  using grpc::StatusCode;
  for (const std::string link : {"secret", "elsewhere/secret", "fields/summary.json"}) {
    const grpc::Status status = Guarded([&] { CheckedResultPath(root, link); });
    EXPECT_EQ(status.error_code(), StatusCode::INVALID_ARGUMENT) << link;
    EXPECT_NE(status.error_message().find("symbolic link"), std::string::npos)
        << status.error_message();
  }
  EXPECT_EQ(CodeOf([&] { CheckedResultPath(root, std::string("summary.json\0x", 14)); }),
            StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(CodeOf([&] { CheckedResultPath(root, "summary.json/x"); }),
            StatusCode::INVALID_ARGUMENT);
  const int fd = OpenResultFile(root, "summary.json");
  EXPECT_GE(fd, 0);
  close(fd);
}

// Issue 38: a results directory that is itself a symbolic link was followed by ListFiles and Fetch;
// a path with a trailing slash was served as the file and made the CLI create a directory.
TEST(ResultFiles, AResultsDirectoryThatIsALinkServesNothingAndPathsNameFiles) {
  dlmfd::testing::TempDir dir;
  const std::filesystem::path elsewhere = dir.path() + "/elsewhere";
  std::filesystem::create_directories(elsewhere);
  std::ofstream(elsewhere / "secret") << "secret";
  const std::filesystem::path root = dir.path() + "/results";
  std::filesystem::create_directory_symlink(elsewhere, root);
  EXPECT_TRUE(ResultFilePaths(root).empty());
  v1::ListFilesResponse listed;
  DescribeResultFiles(root, &listed);
  EXPECT_EQ(listed.files_size(), 0);
  const grpc::Status status = Guarded([&] { CheckedResultPath(root, "secret"); });
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("symbolic link"), std::string::npos)
      << status.error_message();
  const std::filesystem::path real = dir.path() + "/real";
  std::filesystem::create_directories(real);
  std::ofstream(real / "summary.json") << "{}";
  const grpc::Status slash = Guarded([&] { CheckedResultPath(real, "summary.json/"); });
  EXPECT_EQ(slash.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(slash.error_message().find("expected a file"), std::string::npos)
      << slash.error_message();
}

TEST(ServiceError, MessagesCutLongValuesAndShowControlBytes) {
  EXPECT_EQ(CutForMessage("0.1"), "0.1");
  EXPECT_EQ(CutForMessage(std::string("a\0b\n", 4)), "a\\x00b\\x0a");
  const std::string cut = CutForMessage(std::string(1000, 'x'), 10);
  EXPECT_EQ(cut, "xxxxxxxxxx... (1000 bytes)");
  // A cut never splits a UTF-8 character: "é" is 2 bytes, 10 bytes keep 4 of them whole.
  std::string accents;
  for (int i = 0; i < 20; ++i) accents += "\xc3\xa9";
  EXPECT_EQ(CutForMessage(accents, 9), accents.substr(0, 8) + "... (40 bytes)");
  const std::string message =
      "fluid.viscosity = \"" + std::string(1'000'000, 'x') + "\" is not allowed: expected > 0";
  const std::string bounded = BoundMessage(message);
  EXPECT_LE(bounded.size(), kMessageBytes + 40);
  EXPECT_EQ(bounded.rfind("fluid.viscosity = \"", 0), 0u);
  const std::string allowed = "\" is not allowed: expected > 0";
  EXPECT_EQ(bounded.substr(bounded.size() - allowed.size()), allowed);
  EXPECT_NE(bounded.find("bytes cut"), std::string::npos);
  EXPECT_EQ(BoundMessage("short\nmessage"), "short\nmessage");
  const grpc::Status status = ToStatus(std::make_exception_ptr(
      ServiceError(grpc::StatusCode::INVALID_ARGUMENT, std::string(100'000, 'm'))));
  EXPECT_LE(status.error_message().size(), kMessageBytes + 40);
}

}  // namespace
}  // namespace dlmfd::server
