// Unit tests of the study parts of the daemon without a process (issue 14 points 1-3): the axes of
// a study (zipped, ranges, wildcard keys, typed values), the effective scene's values that `list
// --where` matches, the store's studies (schema 3: studies, labels, scene values, the per-study
// limit of the scheduler's queue, requeue of a retry) and the retry plan.
#include <gtest/gtest.h>

#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>

#include "dlmfd/scene/scene_file.h"
#include "job_store.h"
#include "retry_plan.h"
#include "scene_values.h"
#include "service_error.h"
#include "study_expansion.h"
#include "support/daemon_process.h"
#include "support/store_fixtures.h"
#include "support/study_axis.h"

namespace dlmfd::server {
namespace {

grpc::Status StatusOf(const std::function<void()>& body) { return Guarded(body); }

using testing::ListAxis;

v1::StudyAxis Range(const std::string& key, double start, double stop, int count, bool log) {
  v1::StudyAxis axis;
  axis.set_key(key);
  axis.mutable_range()->set_start(start);
  axis.mutable_range()->set_stop(stop);
  axis.mutable_range()->set_count(count);
  axis.mutable_range()->set_logarithmic(log);
  return axis;
}

v1::SubmitStudyRequest Request(std::vector<v1::StudyAxis> axes) {
  v1::SubmitStudyRequest request;
  for (auto& a : axes) *request.add_axes() = a;
  return request;
}

TEST(StudyAxes, ZippedAxesStepTogetherAndCrossTheGrid) {
  const StudyPlan plan =
      ExpandStudy(Request({ListAxis("a", {"1", "2", "3"}, "z"), ListAxis("g", {"x", "y"}),
                           ListAxis("b", {"10", "20", "30"}, "z")}),
                  100);
  ASSERT_EQ(plan.points.size(), 6u);  // 3 zipped x 2
  EXPECT_EQ(plan.points[0].label, "a=1,g=x,b=10");
  EXPECT_EQ(plan.points[1].label, "a=1,g=y,b=10");
  EXPECT_EQ(plan.points[2].label, "a=2,g=x,b=20");
  EXPECT_EQ(plan.points[5].label, "a=3,g=y,b=30");
  const grpc::Status unequal = StatusOf([] {
    ExpandStudy(Request({ListAxis("a", {"1", "2"}, "z"), ListAxis("b", {"1"}, "z")}), 9);
  });
  EXPECT_EQ(unequal.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(unequal.error_message().find("equal lengths"), std::string::npos)
      << unequal.error_message();
}

TEST(StudyAxes, LinearAndLogarithmicRangesIncludeBothEndsAsFloats) {
  const StudyPlan lin = ExpandStudy(Request({Range("fluid.viscosity", 0.1, 0.5, 5, false)}), 10);
  ASSERT_EQ(lin.points.size(), 5u);
  EXPECT_EQ(lin.points[0].label, "fluid.viscosity=0.1");
  EXPECT_EQ(lin.points[4].label, "fluid.viscosity=0.5");
  EXPECT_EQ(lin.points[2].parameters[0].type, "float");
  EXPECT_EQ(lin.points[2].parameters[0].text, "0.3");  // 12 digits, not 0.30000000000000004
  EXPECT_EQ(lin.points[2].parameters[0].number, 0.3);
  const StudyPlan log = ExpandStudy(Request({Range("k", 1e-3, 1e1, 5, true)}), 10);
  ASSERT_EQ(log.points.size(), 5u);
  EXPECT_EQ(log.points[0].overrides.back(), "k=0.001");
  EXPECT_EQ(log.points[4].overrides.back(), "k=10.0");  // a TOML float, not the integer 10
  for (int k = 1; k < 4; ++k) {
    EXPECT_NEAR(log.points[static_cast<size_t>(k)].parameters[0].number, std::pow(10.0, k - 3),
                1e-15 * std::pow(10.0, k - 3));
  }
  ASSERT_TRUE(lin.axes[0].is_range);
  EXPECT_EQ(lin.axes[0].values.size(), 5u);
  using grpc::StatusCode;
  EXPECT_EQ(StatusOf([] { ExpandStudy(Request({Range("k", 0, 1, 5, true)}), 10); }).error_code(),
            StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(StatusOf([] { ExpandStudy(Request({Range("k", -1, 1, 5, true)}), 10); }).error_code(),
            StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(StatusOf([] { ExpandStudy(Request({Range("k", 0, 1, 1, false)}), 10); }).error_code(),
            StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(StatusOf([] { ExpandStudy(Request({Range("k", 0, 1, 3, false)}), 2); }).error_code(),
            StatusCode::RESOURCE_EXHAUSTED);
  v1::StudyAxis both = Range("k", 0, 1, 3, false);
  both.add_values("1");
  EXPECT_EQ(StatusOf([&] { ExpandStudy(Request({both}), 10); }).error_code(),
            StatusCode::INVALID_ARGUMENT);
}

TEST(StudyAxes, ValuesAreTypedWithTheJob) {
  const StudyPlan plan = ExpandStudy(
      Request({ListAxis("particles.*.density", {"1.02"}), ListAxis("collisions.substeps", {"4"}),
               ListAxis("splitting.advection", {"wave"}), ListAxis("gravity", {"[0.0, -981.0]"}),
               ListAxis("accuracy.strict", {"true"})}),
      10);
  ASSERT_EQ(plan.points.size(), 1u);
  const auto& p = plan.points[0].parameters;
  ASSERT_EQ(p.size(), 5u);
  EXPECT_EQ(p[0].key, "particles.*.density");
  EXPECT_EQ(p[0].type, "float");
  EXPECT_EQ(p[0].number, 1.02);
  EXPECT_EQ(p[1].type, "integer");
  EXPECT_EQ(p[1].number, 4.0);
  EXPECT_EQ(p[2].type, "string");
  EXPECT_EQ(p[3].type, "array");
  EXPECT_EQ(p[4].type, "boolean");
}

// The effective scene holds what the file set as well as the overrides; numbers compare as numbers.
TEST(SceneValues, TheEffectiveSceneIsFlattenedWithNormalisedNumbers) {
  const Params params =
      ParseScene("[fluid]\nviscosity = 0.25\n[[particles]]\ncenter = [0.5, 0.5]\ndensity = 1.5\n",
                 {ParseOverride("time.end=2")});
  const auto values = FlattenParams(params);
  auto find = [&](const std::string& key) {
    for (const auto& [k, v] : values) {
      if (k == key) return v;
    }
    return std::string("<absent>");
  };
  EXPECT_EQ(find("fluid.viscosity"), NormalizedValue("0.25"));
  EXPECT_EQ(find("time.end"), NormalizedValue("2"));
  EXPECT_EQ(find("time.end"), NormalizedValue("2.0"));
  EXPECT_EQ(find("particles.0.density"), NormalizedValue("1.5"));
  EXPECT_EQ(find("particles.0.center"), NormalizedValue("[0.5, 0.5]"));
  EXPECT_EQ(find("particles.0.center.1"), NormalizedValue("0.5"));
  EXPECT_EQ(find("domain.boundary.left.type"), "wall");
  EXPECT_NE(NormalizedValue("0.1"), NormalizedValue("0.10000000000000002"));
}

// Admission flattens from the table of scene keys (FlattenParams); the same pairs as flattening the
// scene as run, written and read back as TOML, for every case file.
TEST(SceneValues, TheTableFlattensAsTheSceneAsRunReadsBack) {
  int cases = 0;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(std::string(DLMFD_SOURCE_DIR) + "/cases")) {
    if (entry.path().extension() != ".toml") continue;
    const Params params = LoadSceneFile(entry.path().string());
    auto from_table = FlattenParams(params);
    auto from_text = FlattenScene(WriteScene(params));
    std::sort(from_table.begin(), from_table.end());
    std::sort(from_text.begin(), from_text.end());
    EXPECT_EQ(from_table, from_text) << entry.path();
    ++cases;
  }
  EXPECT_GT(cases, 20);
}

JobRecord Job(const std::string& id, const std::string& study, int priority = 0) {
  JobRecord job = dlmfd::testing::StoreJob(id, study, priority);
  job.overrides = {"time.end=1"};
  return job;
}

StudyRecord Study(const std::string& id, int max_running) {
  StudyRecord study;
  study.id = id;
  study.owner = "local";
  study.name = "study";
  study.tags = {"t"};
  study.labels = {{"project", "pair"}};
  StoredAxis axis;
  axis.key = "a";
  axis.values = {"1", "2\tstill one value", ""};
  axis.is_range = true;
  axis.start = 0.1;
  axis.count = 3;
  study.axes = {axis};
  study.max_running = max_running;
  study.created_time = 5;
  return study;
}

// The scheduler's queue skips a study at its max_running and takes other jobs meanwhile.
TEST(StudyStore, AStudyAtItsLimitHoldsBackItsQueuedJobs) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  const StudyRecord study = Study("s-1", 1);
  store.InsertJobs({Job("a", "s-1", 5), Job("b", "s-1", 5)}, "local", "", &study);
  store.InsertJobs({Job("c", "", 0)}, "local", "");
  auto next = store.NextQueued();
  ASSERT_TRUE(next);
  EXPECT_EQ(next->id, "a");
  store.MarkRunning("a", 1);
  next = store.NextQueued();
  ASSERT_TRUE(next);
  EXPECT_EQ(next->id, "c");  // b waits, though its priority is higher
  store.MarkFinished("a", JobState::kCompleted, "", 2);
  next = store.NextQueued();
  ASSERT_TRUE(next);
  EXPECT_EQ(next->id, "b");
}

TEST(StudyStore, StudiesRoundTripWithTheirAxesAndCounts) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  const StudyRecord study = Study("s-1", 2);
  JobRecord a = Job("a", "s-1");
  a.parameters = {{"a", "1", "integer", 1.0}};
  a.labels = {{"project", "pair"}};
  JobRecord b = Job("b", "s-1");
  b.end_time = 4;
  store.InsertJobs({a, b}, "local", "", &study);
  store.MarkRunning("a", 10);
  store.MarkFinished("a", JobState::kFailed, "blow-up", 11);
  store.MarkRunning("b", 12);
  store.UpdateProgress("b", 5, 1.0, 4.0);
  auto back = store.GetStudy("local", "s-1");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->name, "study");
  EXPECT_EQ(back->tags, study.tags);
  EXPECT_EQ(back->labels, study.labels);
  ASSERT_EQ(back->axes.size(), 1u);
  EXPECT_EQ(back->axes[0].values, study.axes[0].values);  // a tab and an empty value survive
  EXPECT_TRUE(back->axes[0].is_range);
  EXPECT_EQ(back->axes[0].start, 0.1);
  EXPECT_EQ(back->max_running, 2);
  EXPECT_FALSE(store.GetStudy("bob", "s-1"));
  const StudyStats stats = store.StatsOfStudy("local", "s-1");
  EXPECT_EQ(stats.jobs, 2);
  EXPECT_EQ(stats.count[static_cast<size_t>(JobState::kFailed)], 1);
  EXPECT_EQ(stats.count[static_cast<size_t>(JobState::kRunning)], 1);
  EXPECT_DOUBLE_EQ(stats.progress_sum, 1.25);  // a finished: 1; b at t = 1 of 4
  EXPECT_EQ(stats.first_started_time, 10);
  EXPECT_EQ(stats.last_finished_time, 11);
  auto job = store.Get("a");
  ASSERT_TRUE(job);
  ASSERT_EQ(job->parameters.size(), 1u);
  EXPECT_EQ(job->parameters[0].type, "integer");
  EXPECT_EQ(job->labels, a.labels);
  EXPECT_EQ(store.ListStudies("local", "t", 0, 10).size(), 1u);
  EXPECT_EQ(store.ListStudies("local", "other", 0, 10).size(), 0u);
}

// `dlmfd delete --study S` removes the study with its jobs: `dlmfd studies` no longer lists it and
// `list --study S` no longer finds it. A study that keeps a job stays.
TEST(StudyStore, AStudyGoesWithItsLastJob) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  const StudyRecord study = Study("s-1", 0);
  store.InsertJobs({Job("a", "s-1"), Job("b", "s-1")}, "local", "", &study);
  store.InsertJobs({Job("c", "")}, "local", "");
  store.Delete({"a", "c"});
  EXPECT_TRUE(store.GetStudy("local", "s-1"));
  EXPECT_EQ(store.StatsOfStudy("local", "s-1").jobs, 1);
  store.Delete({"b"});
  EXPECT_FALSE(store.GetStudy("local", "s-1"));
  EXPECT_TRUE(store.ListStudies("local", "", 0, 10).empty());
}

TEST(StudyStore, ListSelectsOnTagsLabelsAndSceneValues) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  JobRecord a = Job("a", "");
  a.tags = {"x", "y"};
  a.labels = {{"case", "pair"}};
  a.scene_values = {{"particles.0.density", NormalizedValue("1.5")},
                    {"particles.1.density", NormalizedValue("1.02")},
                    {"fluid.viscosity", NormalizedValue("0.1")}};
  JobRecord b = Job("b", "");
  b.tags = {"x"};
  b.scene_values = {{"particles.0.density", NormalizedValue("1.02")},
                    {"fluid.viscosity", NormalizedValue("0.2")}};
  store.InsertJobs({a, b}, "local", "");
  auto ids = [&](const ListFilter& filter) {
    std::vector<std::string> out;
    for (const auto& job : store.List(filter)) out.push_back(job.id);
    return out;
  };
  ListFilter filter;
  filter.owner = "local";
  filter.tags = {"x"};
  EXPECT_EQ(ids(filter), (std::vector<std::string>{"b", "a"}));
  filter.tags = {"x", "y"};
  EXPECT_EQ(ids(filter), (std::vector<std::string>{"a"}));
  filter.tags = {};
  filter.labels = {{"case", "pair"}};
  EXPECT_EQ(ids(filter), (std::vector<std::string>{"a"}));
  filter.labels = {};
  filter.values = {ParseWhere("fluid.viscosity=0.10")};
  EXPECT_EQ(ids(filter), (std::vector<std::string>{"a"}));
  filter.values = {ParseWhere("particles.*.density=1.02")};
  EXPECT_EQ(ids(filter), (std::vector<std::string>{"b", "a"}));
  filter.values = {ParseWhere("particles.*.density=1.02"), ParseWhere("fluid.viscosity=0.2")};
  EXPECT_EQ(ids(filter), (std::vector<std::string>{"b"}));
  // Issue 38: != and the ranges, numbers compared as numbers (0.1 < 0.15 < 0.2).
  filter.values = {ParseWhere("fluid.viscosity!=0.1")};
  EXPECT_EQ(ids(filter), (std::vector<std::string>{"b"}));
  filter.values = {ParseWhere("fluid.viscosity<0.15")};
  EXPECT_EQ(ids(filter), (std::vector<std::string>{"a"}));
  filter.values = {ParseWhere("fluid.viscosity<=0.2"), ParseWhere("fluid.viscosity>=1e-1")};
  EXPECT_EQ(ids(filter), (std::vector<std::string>{"b", "a"}));
  filter.values = {ParseWhere("fluid.viscosity>0.2")};
  EXPECT_TRUE(ids(filter).empty());
  filter.values = {ParseWhere("particles.*.density>1.4")};
  EXPECT_EQ(ids(filter), (std::vector<std::string>{"a"}));
  // A key none of the owner's jobs has is unknown (a typo); an owner with no job knows every key.
  EXPECT_TRUE(store.SceneKeyKnown("local", "fluid.viscosity"));
  EXPECT_TRUE(store.SceneKeyKnown("local", "particles.*.density"));
  EXPECT_FALSE(store.SceneKeyKnown("local", "fluid.viscosty"));
  EXPECT_FALSE(store.SceneKeyKnown("local", "particles.?.density"));  // '?' is no wildcard
  EXPECT_TRUE(store.SceneKeyKnown("nobody", "fluid.viscosty"));
}

TEST(SceneValues, WhereTakesEqualityAndRangesAndNamesWhatItRefuses) {
  const SceneValueFilter equal = ParseWhere("particles.*.density=1.020");
  EXPECT_EQ(equal.pattern, "particles.*.density");
  EXPECT_EQ(equal.op, "=");
  EXPECT_EQ(equal.value, "1.02");
  EXPECT_EQ(ParseWhere("title!=a<b").op, "!=");
  EXPECT_EQ(ParseWhere("title!=a<b").value, "a<b");  // the first operator ends the key
  EXPECT_EQ(ParseWhere("title=x>=y").value, "x>=y");
  const SceneValueFilter at_least = ParseWhere("time.dt>=1e-3");
  EXPECT_EQ(at_least.op, ">=");
  EXPECT_EQ(at_least.bound, 1e-3);
  EXPECT_EQ(ParseWhere("time.dt<2").bound, 2.0);
  EXPECT_EQ(ParseWhere("time.dt>-inf").bound, -INFINITY);
  for (const char* bad : {"fluid.viscosity", "=1", "<1", "fluid.viscosity!1", "time.dt<abc",
                          "time.dt<nan", "time.dt<[1, 2]", "time.dt<=", "title>\"a\""}) {
    const grpc::Status status = StatusOf([&] { ParseWhere(bad); });
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << bad;
    EXPECT_EQ(status.error_message().rfind("where: ", 0), 0u) << status.error_message();
  }
}

TEST(StudyStore, RequeueRecordsTheAttemptAndRefusesAnUnfinishedJob) {
  dlmfd::testing::TempDir dir;
  JobStore store(dir.path() + "/jobs.db");
  store.InsertJobs({Job("a", "")}, "local", "");
  EXPECT_THROW(store.Requeue({{"a", {"time.end=1"}, {}, {}, {}, 1, false, "", {}}}), StoreError);
  store.MarkRunning("a", 10);
  store.UpdateProgress("a", 7, 0.7, 1.0);
  store.MarkFinished("a", JobState::kCancelled, "cancelled", 11);
  // It returns the records as written, which the Retry reply and event report: a Get after it
  // can already read a job the scheduler started.
  const std::vector<JobRecord> requeued =
      store.Requeue({{"a", {"time.end=1", "time.dt=0.01"}, {}, {}, {}, 1, true, "", {}}});
  ASSERT_EQ(requeued.size(), 1u);
  EXPECT_EQ(requeued[0].id, "a");
  EXPECT_EQ(requeued[0].state, JobState::kQueued);
  EXPECT_EQ(requeued[0].attempt, 2);
  auto job = store.Get("a");
  ASSERT_TRUE(job);
  EXPECT_EQ(job->state, JobState::kQueued);
  EXPECT_EQ(job->attempt, 2);
  EXPECT_TRUE(job->fresh_start);
  EXPECT_EQ(job->step, 0);  // a fresh start begins at step 0
  EXPECT_EQ(job->overrides, (std::vector<std::string>{"time.end=1", "time.dt=0.01"}));
  ASSERT_EQ(job->previous_attempts.size(), 1u);
  const AttemptRecord& first = job->previous_attempts[0];
  EXPECT_EQ(first.attempt, 1);
  EXPECT_EQ(first.state, JobState::kCancelled);
  EXPECT_EQ(first.reason, "cancelled");
  EXPECT_EQ(first.step, 7);
  EXPECT_EQ(first.started_time, 10);
  EXPECT_EQ(first.finished_time, 11);
  EXPECT_EQ(first.overrides, (std::vector<std::string>{"time.end=1"}));
  store.ClearFreshStart("a");
  EXPECT_FALSE(store.Get("a")->fresh_start);
}

// A store of schema 2 with a study gains the studies table with a row for that study.
TEST(StudyStore, ASchemaTwoStoreGainsItsStudiesAsRows) {
  dlmfd::testing::TempDir dir;
  const std::string path = dir.path() + "/jobs.db";
  {
    JobStore store(path);
    store.InsertJobs({Job("a", "s-old")}, "local", "");
  }
  // Back to schema 2, as an older daemon left it.
  dlmfd::testing::RollBackSchema(path, 2);
  JobStore store(path);
  auto study = store.GetStudy("local", "s-old");
  ASSERT_TRUE(study);
  EXPECT_TRUE(study->axes.empty());
  EXPECT_EQ(store.StatsOfStudy("local", "s-old").jobs, 1);
  EXPECT_EQ(store.Get("a")->attempt, 1);
}

// The names of a store's tables, columns and indexes (sqlite_master's SQL) that contain `word`.
std::vector<std::string> SchemaNamesWith(const std::string& path, const std::string& word) {
  sqlite3* db = nullptr;
  std::vector<std::string> names;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
    sqlite3_stmt* select = nullptr;
    sqlite3_prepare_v2(db, "SELECT name, sql FROM sqlite_master WHERE sql IS NOT NULL", -1, &select,
                       nullptr);
    while (select != nullptr && sqlite3_step(select) == SQLITE_ROW) {
      const std::string name = reinterpret_cast<const char*>(sqlite3_column_text(select, 0));
      const std::string sql = reinterpret_cast<const char*>(sqlite3_column_text(select, 1));
      if (sql.find(word) != std::string::npos) names.push_back(name);
    }
    sqlite3_finalize(select);
  }
  sqlite3_close(db);
  return names;
}

// Schema 11 (issue 39 point 5): the table of studies and a job's study column take the word users
// see. A store written under schema 10, with a study and its jobs, keeps them under the new names.
TEST(StudyStore, ASchemaTenStoreKeepsItsStudiesUnderTheNewNames) {
  dlmfd::testing::TempDir dir;
  const std::string path = dir.path() + "/jobs.db";
  {
    JobStore store(path);
    const StudyRecord study = Study("s-ten", 1);
    store.InsertJobs({Job("a", "s-ten"), Job("b", "s-ten"), Job("c", "")}, "local", "", &study);
  }
  // As the daemon of schema 10 left it, written through its own names.
  dlmfd::testing::RollBackSchema(path, 10);
  ASSERT_FALSE(SchemaNamesWith(path, "sweep").empty());
  dlmfd::testing::ExecuteOnStore(
      path,
      "UPDATE sweeps SET name = 'ten', overrides = 'time.end=1' WHERE id = 's-ten';"
      "UPDATE jobs SET sweep_id = '' WHERE id = 'b';",
      "writing schema 10's names");
  JobStore store(path);
  EXPECT_EQ(SchemaNamesWith(path, "sweep"), std::vector<std::string>{});
  const auto study = store.GetStudy("local", "s-ten");
  ASSERT_TRUE(study);
  EXPECT_EQ(study->name, "ten");
  EXPECT_EQ(study->max_running, 1);
  EXPECT_EQ(study->overrides, std::vector<std::string>{"time.end=1"});
  EXPECT_EQ(store.Get("a")->study_id, "s-ten");
  EXPECT_EQ(store.Get("b")->study_id, "");
  EXPECT_EQ(store.StatsOfStudy("local", "s-ten").jobs, 1);
  EXPECT_EQ(store.QueuedOfStudy("s-ten", 10).size(), 1u);  // found through the renamed column
  // New studies go into the renamed table.
  const StudyRecord second = Study("s-new", 0);
  store.InsertJobs({Job("d", "s-new")}, "local", "", &second);
  EXPECT_EQ(store.StudyJobs("local", "s-new").size(), 1u);
}

TEST(RetryPlan, SetReplacesTheSameKeyAndResumesOnlyTheSameUnfinishedScene) {
  EXPECT_EQ(MergeOverrides({"a=1", "b=2"}, {"b = 3", "c=4"}),
            (std::vector<std::string>{"a=1", "b = 3", "c=4"}));
  const auto parameters = UpdatedParameters({{"b", "2", "integer", 2}}, {"b=0.5"});
  EXPECT_EQ(parameters[0].text, "0.5");
  EXPECT_EQ(parameters[0].type, "float");
  JobRecord job = Job("a", "");
  job.state = JobState::kCancelled;
  EXPECT_TRUE(ResumesFromCheckpoint(job, job.overrides));
  EXPECT_FALSE(ResumesFromCheckpoint(job, MergeOverrides(job.overrides, {"time.dt=1"})));
  job.state = JobState::kCompleted;
  EXPECT_FALSE(ResumesFromCheckpoint(job, job.overrides));
}

// Issue 38: a retried study point is named after its new parameters; a name a user gave is kept.
TEST(RetryPlan, ARetriedPointIsRenamedAfterItsNewParameters) {
  const std::vector<ParameterValue> before = {{"fluid.relaxation_time", "3", "integer", 3},
                                              {"time.dt", "0.04", "float", 0.04}};
  const auto after = UpdatedParameters(before, {"time.dt=0.01"});
  EXPECT_EQ(RenamedPoint("wk[fluid.relaxation_time=3,time.dt=0.04]", before, after),
            "wk[fluid.relaxation_time=3,time.dt=0.01]");
  EXPECT_EQ(RenamedPoint("s-1f[fluid.relaxation_time=3,time.dt=0.04]", before, after),
            "s-1f[fluid.relaxation_time=3,time.dt=0.01]");
  EXPECT_EQ(RenamedPoint("my run", before, after), "my run");
  EXPECT_EQ(RenamedPoint("wk[time.dt=0.04]", before, after), "wk[time.dt=0.04]");
  EXPECT_EQ(RenamedPoint("single", {}, {}), "single");
}

}  // namespace
}  // namespace dlmfd::server
