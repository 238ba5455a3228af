// Studies from the command line (issue 14 points 1-4, 8): the real dlmfd, dlmfdd (loopback, a
// tokens file, its SQLite store) and dlmfd-solve. A study of the 16 x 16 cavity (a few tens of
// steps per point) is listed, shown, watched, fetched one folder per point and selected by tag,
// label and scene value; `--json` numbers are numbers; the live line fits the terminal. No
// wall-clock limits: waits poll until a state is reached.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "support/cli_harness.h"

namespace dlmfd::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

class StudiesCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    for (const std::string* binary : {&kClient, &kDaemon, &kSolver})
      ASSERT_TRUE(fs::exists(*binary)) << *binary << " is not built";
    root_ = fs::path(::testing::TempDir()) / ("dlmfd_studies_e2e_" + std::to_string(getpid()));
    fs::remove_all(root_);
    daemon_ = new CliDaemon(root_);
    std::ofstream(root_ / "cavity.toml") << kCavity;
    std::string error;
    ASSERT_TRUE(daemon_->Start("127.0.0.1:0", error)) << error;
  }
  static void TearDownTestSuite() {
    delete daemon_;
    daemon_ = nullptr;
    fs::remove_all(root_);
  }
  static CliRun Cli(const std::vector<std::string>& args) {
    std::vector<std::string> argv(1, kClient);
    argv.insert(argv.end(), args.begin(), args.end());
    return Execute(argv, daemon_->Env());
  }
  static std::string Scene() { return (root_ / "cavity.toml").string(); }

  static fs::path root_;
  static CliDaemon* daemon_;
};

fs::path StudiesCliTest::root_;
CliDaemon* StudiesCliTest::daemon_ = nullptr;

TEST_F(StudiesCliTest, AStudyIsListedShownWatchedFetchedAndSelected) {
  const CliRun study =
      Cli({"study", Scene(), "--zip", "fluid.viscosity=0.01,0.02", "--zip", "time.end=0.1,0.2",
           "--range", "time.dt=0.01:0.02:2", "--tag", "grid-e2e", "--label", "project=cavity",
           "--max-running", "1", "--name", "cavity-study", "-q"});
  ASSERT_EQ(study.code, 0) << study.err;
  const std::string id = FirstLine(study.out);
  ASSERT_EQ(id.rfind("s-", 0), 0u) << study.out;

  const CliRun watch = Cli({"watch", "--study", id, "--interval", "0.2"});
  EXPECT_EQ(watch.code, 0) << watch.out << watch.err;  // every point completed
  EXPECT_THAT(watch.out, HasSubstr(id + " 4 jobs  0 queued  0 running  4 done  0 failed"));

  const CliRun studies = Cli({"studies", "--tag", "grid-e2e"});
  ASSERT_EQ(studies.code, 0) << studies.err;
  EXPECT_THAT(studies.out, HasSubstr("ID"));
  EXPECT_THAT(studies.out, HasSubstr(id + "  cavity-study  grid-e2e  4     0       0        4"));
  EXPECT_THAT(studies.out, HasSubstr("100%"));

  const CliRun show = Cli({"show", "--study", id});
  ASSERT_EQ(show.code, 0) << show.err;
  EXPECT_THAT(show.out, HasSubstr("axis:        fluid.viscosity=0.01,0.02  (zipped: zip)"));
  EXPECT_THAT(show.out, HasSubstr("axis:        time.dt=0.01,0.02  (linear range 0.01:0.02:2)"));
  EXPECT_THAT(show.out, HasSubstr("max running: 1"));
  EXPECT_THAT(show.out, HasSubstr("labels:      project=cavity"));
  EXPECT_THAT(show.out, HasSubstr("jobs:        4: 0 queued, 0 running, 4 completed"));

  // Selection by tag, label and by a value of the effective scene (file or override).
  const CliRun by_tag = Cli({"list", "--tag", "grid-e2e", "--tag", id, "--json"});
  ASSERT_EQ(by_tag.code, 0) << by_tag.err;
  EXPECT_EQ(std::count(by_tag.out.begin(), by_tag.out.end(), '\n'), 4);
  const CliRun by_value =
      Cli({"list", "--study", id, "--where", "fluid.viscosity=0.02", "--where", "time.dt=0.02"});
  ASSERT_EQ(by_value.code, 0) << by_value.err;
  EXPECT_THAT(by_value.out, HasSubstr("[time.dt=0.02,fluid.viscosity=0.02,time.end=0.2]"));
  EXPECT_EQ(std::count(by_value.out.begin(), by_value.out.end(), '\n'), 2);  // header + 1
  const CliRun from_file = Cli({"list", "--label", "project=cavity", "--where", "fluid.density=1"});
  EXPECT_EQ(std::count(from_file.out.begin(), from_file.out.end(), '\n'), 5);
  const CliRun unknown = Cli({"list", "--study", "s-unknown"});
  EXPECT_EQ(unknown.code, 3) << unknown.err;
  EXPECT_THAT(unknown.err, HasSubstr("study s-unknown not found"));
  EXPECT_EQ(Cli({"show", "--tag", "no-such-tag"}).code, 3);

  // One folder per point, named by its parameters (axes in the order --grid, --range, --zip).
  const fs::path out = root_ / "fetched";
  const CliRun fetch =
      Cli({"fetch", "--study", id, "--out", out.string(), "--path", "summary.json"});
  ASSERT_EQ(fetch.code, 0) << fetch.err;
  EXPECT_TRUE(fs::exists(out / "time.dt=0.01,fluid.viscosity=0.01,time.end=0.1" / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "time.dt=0.02,fluid.viscosity=0.02,time.end=0.2" / "summary.json"));
  EXPECT_THAT(Slurp(out / "time.dt=0.02,fluid.viscosity=0.02,time.end=0.2" / "summary.json"),
              HasSubstr("\"completed\""));
  int folders = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(out)) ++folders;
  EXPECT_EQ(folders, 4);
  // Each folder has its job (job.json, as `show --json` prints it): the name and the overrides
  // of its point, which `dlmfd plot FOLDER` names in its caption.
  const std::string point =
      Slurp(out / "time.dt=0.02,fluid.viscosity=0.02,time.end=0.2" / "job.json");
  EXPECT_THAT(point, HasSubstr("\"name\":\"cavity-study["));
  EXPECT_THAT(point, HasSubstr("\"time.dt=0.02\""));
  EXPECT_THAT(point, HasSubstr("\"fluid.viscosity=0.02\""));
  EXPECT_THAT(point, HasSubstr("\"time.end=0.2\""));
  EXPECT_THAT(point, HasSubstr("\"study_id\":\"" + id + "\""));

  // --json: 64-bit integers are numbers.
  const CliRun json = Cli({"show", "--study", id, "--json"});
  ASSERT_EQ(json.code, 0) << json.err;
  EXPECT_THAT(json.out, HasSubstr("\"jobs\":4"));
  EXPECT_THAT(json.out, Not(HasSubstr("\"step\":\"")));
  EXPECT_TRUE(std::regex_search(json.out, std::regex("\"step\":(10|20)[,}]"))) << json.out;
  EXPECT_TRUE(std::regex_search(json.out, std::regex("\"last_seq\":[0-9]+[,}]"))) << json.out;
}

TEST_F(StudiesCliTest, RetryRerunsACancelledPointInItsStudy) {
  const CliRun study = Cli({"study", Scene(), "--grid", "time.end=0.1,1000", "-q"});
  ASSERT_EQ(study.code, 0) << study.err;
  const std::string id = FirstLine(study.out);
  std::string long_job;
  for (;;) {  // until the long point runs and the short one has completed
    const CliRun running =
        Cli({"list", "--study", id, "--where", "time.end=1000", "--state", "running", "-q"});
    const CliRun completed = Cli({"list", "--study", id, "--state", "completed", "-q"});
    ASSERT_EQ(running.code, 0) << running.err;
    long_job = FirstLine(running.out);
    if (!long_job.empty() && !completed.out.empty()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const CliRun cancel = Cli({"cancel", "--study", id});
  ASSERT_EQ(cancel.code, 0) << cancel.err;
  const CliRun watch = Cli({"watch", "--study", id, "--interval", "0.2"});
  EXPECT_EQ(watch.code, 1) << watch.out << watch.err;  // one point was cancelled
  EXPECT_THAT(watch.out, HasSubstr("1 cancelled"));

  const CliRun running = Cli({"retry", long_job, "--set", "time.end=0.2"});
  ASSERT_EQ(running.code, 0) << running.err;
  EXPECT_THAT(running.out, HasSubstr(long_job + " queued (attempt 2)"));
  const CliRun done = Cli({"watch", "--study", id, "--interval", "0.2"});
  EXPECT_EQ(done.code, 0) << done.out << done.err;
  const CliRun show = Cli({"show", long_job});
  ASSERT_EQ(show.code, 0) << show.err;
  EXPECT_THAT(show.out, HasSubstr("study:       " + id));
  EXPECT_THAT(show.out, HasSubstr("  attempt 1: cancelled (cancelled)"));
  EXPECT_THAT(show.out, HasSubstr("parameter:   time.end = 0.2 (float)"));
  const CliRun nothing = Cli({"retry", "--study", id});
  EXPECT_EQ(nothing.code, 6) << nothing.err;  // nothing failed or cancelled is left
  EXPECT_EQ(Cli({"retry", "--study", id, "--state", "running"}).code, 2);
}

// The live line of `watch` stays within the terminal's width: every redraw ("\r\033[K" + line)
// is at most COLUMNS - 1 characters, so the terminal never wraps it.
TEST_F(StudiesCliTest, TheLiveLineFitsTheTerminal) {
  const CliRun submit = Cli({"submit", Scene(), "--set", "time.end=3"});
  ASSERT_EQ(submit.code, 0) << submit.err;
  const std::string job = FirstLine(submit.out);
  for (int columns : {80, 40}) {
    auto env = daemon_->Env();
    env["COLUMNS"] = std::to_string(columns);
    const CliRun watch = ExecuteOnTerminal({kClient, "watch", job}, env, columns);
    EXPECT_EQ(watch.code, 0) << watch.out;
    std::size_t redraws = 0;
    for (std::size_t at = watch.out.find("\r\033[K"); at != std::string::npos;
         at = watch.out.find("\r\033[K", at + 1)) {
      const std::size_t begin = at + 4;
      const std::size_t end = watch.out.find_first_of("\r\n", begin);
      const std::string line = watch.out.substr(begin, end - begin);
      EXPECT_LE(line.size(), static_cast<std::size_t>(columns - 1)) << line;
      if (!line.empty()) ++redraws;
    }
    EXPECT_GT(redraws, 0u) << watch.out;
    EXPECT_THAT(watch.out, HasSubstr(job.substr(0, 10)));
  }
}

}  // namespace
}  // namespace dlmfd::testing
