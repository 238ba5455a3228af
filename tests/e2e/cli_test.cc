// The dlmfd CLI end to end: the real dlmfdd (loopback, a temporary data directory with its SQLite
// store, a tokens file), the real dlmfd-solve and the real dlmfd binary, driven as a user would.
// Scenes are a 16 x 16 lid-driven cavity of 10 steps, so each job takes a fraction of a second.
// No wall-clock limits: the waits below poll until a state is reached and fail only through
// ctest's own timeout.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../support/walled_box_scene.h"
#include "dlmfd/io/field_snapshot.h"
#include "support/cli_harness.h"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

using dlmfd::testing::CliRun;
using dlmfd::testing::Execute;
using dlmfd::testing::FirstLine;
using dlmfd::testing::kCavity;
using dlmfd::testing::kClient;
using dlmfd::testing::kDaemon;
using dlmfd::testing::kSolver;
using dlmfd::testing::Slurp;

class CliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string* binaries[] = {&kClient, &kDaemon, &kSolver};
    for (const std::string* binary : binaries)
      ASSERT_TRUE(fs::exists(*binary)) << *binary << " is not built";
    root_ = fs::path(::testing::TempDir()) / ("dlmfd_cli_e2e_" + std::to_string(getpid()));
    fs::remove_all(root_);
    daemon_ = new dlmfd::testing::CliDaemon(root_);
    std::ofstream(root_ / "cavity.toml") << kCavity;
    StartDaemon("127.0.0.1:0");
  }

  // Starts dlmfdd on `listen` with the suite's data directory; waits until it has written its port.
  static void StartDaemon(const std::string& listen) {
    std::string error;
    ASSERT_TRUE(daemon_->Start(listen, error)) << error;
    server_ = daemon_->server();
  }

  static void TearDownTestSuite() {
    delete daemon_;
    daemon_ = nullptr;
    fs::remove_all(root_);
  }

  // The environment of a user with no config file, unless a test writes one into home/.
  static std::map<std::string, std::string> Env(bool with_server = true, bool with_token = true) {
    return daemon_->Env(with_server, with_token);
  }

  static CliRun Cli(const std::vector<std::string>& args,
                    const std::map<std::string, std::string>& env = Env(),
                    std::atomic<bool>* printed = nullptr) {
    std::vector<std::string> argv(1, kClient);
    for (const std::string& a : args) argv.push_back(a);
    return Execute(argv, env, printed);
  }

  // Polls `show --json` until the job's state appears in it.
  static void AwaitState(const std::string& job, const std::string& state) {
    for (;;) {
      const CliRun show = Cli({"show", job, "--json"});
      ASSERT_EQ(show.code, 0) << show.err;
      if (show.out.find("\"state\":\"" + state + "\"") != std::string::npos) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }

  static fs::path root_;
  static dlmfd::testing::CliDaemon* daemon_;
  static std::string server_;
};

fs::path CliTest::root_;
dlmfd::testing::CliDaemon* CliTest::daemon_ = nullptr;
std::string CliTest::server_;

TEST_F(CliTest, HealthServesAndAClosedPortIsUnavailable) {
  const CliRun ok = Cli({"health"});
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_THAT(ok.out, HasSubstr("SERVING"));
  const CliRun closed = Cli({"health", "--server", "127.0.0.1:1"});
  EXPECT_EQ(closed.code, 5);
  EXPECT_THAT(closed.err, HasSubstr("dlmfd health: server unavailable"));
}

TEST_F(CliTest, SubmitWaitListShowFetchAndPlot) {
  const CliRun submit = Cli(
      {"submit", (root_ / "cavity.toml").string(), "--tag", "e2e", "--name", "cavity", "--wait"});
  ASSERT_EQ(submit.code, 0) << submit.out << submit.err;
  // JOB=$(dlmfd submit --wait ...) captures the id alone; the progress goes to stderr (issue 38).
  const std::string job = FirstLine(submit.out);
  ASSERT_FALSE(job.empty());
  EXPECT_EQ(submit.out, job + "\n");
  EXPECT_THAT(submit.err, HasSubstr(job + " completed: 10 steps"));

  const CliRun list = Cli({"list", "--tag", "e2e"});
  ASSERT_EQ(list.code, 0) << list.err;
  EXPECT_THAT(list.out, HasSubstr(job));
  EXPECT_THAT(list.out, HasSubstr("completed"));
  const CliRun show = Cli({"show", job});
  ASSERT_EQ(show.code, 0) << show.err;
  EXPECT_THAT(show.out, HasSubstr("state:       completed"));
  EXPECT_THAT(show.out, HasSubstr("tags:        e2e"));

  const fs::path out = root_ / "fetched";
  const CliRun fetch = Cli({"fetch", job, "--out", out.string()});
  ASSERT_EQ(fetch.code, 0) << fetch.err;
  ASSERT_TRUE(fs::exists(out / "summary.json"));
  EXPECT_THAT(Slurp(out / "summary.json"), HasSubstr("\"completed\""));
  const CliRun one =
      Cli({"fetch", job, "--out", (root_ / "one").string(), "--path", "summary.json"});
  ASSERT_EQ(one.code, 0) << one.err;
  EXPECT_EQ(Slurp(root_ / "one" / "summary.json"), Slurp(out / "summary.json"));
  // Issue 38: a path with a trailing slash made a directory named after the file.
  const CliRun slash =
      Cli({"fetch", job, "--out", (root_ / "slash").string(), "--path", "summary.json/"});
  EXPECT_EQ(slash.code, 2) << slash.err;
  EXPECT_THAT(slash.err, HasSubstr("expected the path of a file"));
  EXPECT_FALSE(fs::exists(root_ / "slash" / "summary.json"));

  const fs::path png = root_ / "cavity.png";
  const CliRun plot =
      Cli({"plot", out.string(), "--out", png.string(), "--width", "500", "--height", "400"});
  ASSERT_EQ(plot.code, 0) << plot.err;
  EXPECT_EQ(FirstLine(plot.out), png.string());
  const std::string bytes = Slurp(png);
  ASSERT_GT(bytes.size(), 24u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // IHDR: width and height, big-endian, within the requested box.
  auto be32 = [&](std::size_t at) {
    return (unsigned(uint8_t(bytes[at])) << 24) | (unsigned(uint8_t(bytes[at + 1])) << 16) |
           (unsigned(uint8_t(bytes[at + 2])) << 8) | unsigned(uint8_t(bytes[at + 3]));
  };
  EXPECT_LE(be32(16), 500u);
  EXPECT_LE(be32(20), 400u);
  EXPECT_GT(be32(16), 100u);

  const CliRun missing = Cli({"plot", out.string(), "--snapshot", "999999"});
  EXPECT_EQ(missing.code, 2);
  EXPECT_THAT(missing.err, HasSubstr("snapshot"));

  // A movie of the job itself: its snapshots are fetched from the daemon, one frame each.
  const fs::path movie = root_ / "cavity.mp4";
  const CliRun film = Cli({"movie", job, "--quantity", "speed", "--out", movie.string(), "--fps",
                           "2", "--keep", (root_ / "movie_frames").string()});
  ASSERT_EQ(film.code, 0) << film.err;
  EXPECT_EQ(FirstLine(film.out), movie.string());
  const std::size_t snapshots = dlmfd::SnapshotSteps(out.string()).size();
  ASSERT_GE(snapshots, 2u);
  EXPECT_THAT(film.err, HasSubstr(std::to_string(snapshots) + " frames"));
  EXPECT_EQ(dlmfd::SnapshotSteps((root_ / "movie_frames").string()).size(), snapshots);
  EXPECT_EQ(Slurp(movie).substr(4, 4), "ftyp");  // an MP4 (ISO base media) file
  // A job the daemon does not know is NOT_FOUND, exit 3, as for every command naming a job.
  const CliRun unknown = Cli({"movie", "j-0123456789abcdef", "--out", movie.string()});
  EXPECT_EQ(unknown.code, 3) << unknown.err;
  EXPECT_THAT(unknown.err, HasSubstr("dlmfd movie: not found: "));
}

TEST_F(CliTest, AFetchedDirectoryIsCaptionedWithItsJobsNameAndOverrides) {
  const CliRun submit = Cli({"submit", (root_ / "cavity.toml").string(), "--name", "lid", "--set",
                             "fluid.viscosity=0.02", "--set", "time.end=0.1", "--wait"});
  ASSERT_EQ(submit.code, 0) << submit.out << submit.err;
  const std::string job = FirstLine(submit.out);
  const fs::path out = root_ / "captioned";
  const CliRun fetch = Cli({"fetch", job, "--out", out.string()});
  ASSERT_EQ(fetch.code, 0) << fetch.err;
  // job.json: the job as `show --json` prints it, its overrides as submitted.
  const std::string record = Slurp(out / "job.json");
  EXPECT_THAT(record, HasSubstr("\"id\":\"" + job + "\""));
  EXPECT_THAT(record, HasSubstr("\"overrides\":[\"fluid.viscosity=0.02\",\"time.end=0.1\"]"));
  // A fetch of one file writes it too.
  const fs::path one = root_ / "captioned_one";
  ASSERT_EQ(Cli({"fetch", job, "--out", one.string(), "--path", "summary.json"}).code, 0);
  EXPECT_THAT(Slurp(one / "job.json"),
              HasSubstr("\"overrides\":[\"fluid.viscosity=0.02\",\"time.end=0.1\"]"));

  // The default caption is the job's (JobCaption: name, then the overrides, numbers to 4 digits),
  // then the run's settings from its scene.toml, and not the directory's caption of a solver's own
  // results (scene title and directory name). Read back from the PDF's text (poppler's pdftotext,
  // scripts/setup.sh).
  ASSERT_TRUE(fs::exists("/usr/bin/pdftotext")) << "poppler-utils is not installed";
  auto caption = [&](const std::string& stem) {
    const fs::path pdf = root_ / (stem + ".pdf");
    const CliRun run = Cli({"plot", out.string(), "--quantity", "vorticity", "--out", pdf.string(),
                            "--width", "1400", "--height", "1000"});
    EXPECT_EQ(run.code, 0) << run.err;
    const CliRun text = Execute({"/usr/bin/pdftotext", pdf.string(), "-"}, {{"PATH", "/usr/bin"}});
    EXPECT_EQ(text.code, 0) << text.err;
    return text.out;
  };
  const std::string by_default = caption("caption_default");
  EXPECT_THAT(by_default, HasSubstr("lid"));
  EXPECT_THAT(by_default, HasSubstr("fluid.viscosity = 0.02, time.end = 0.1"));
  EXPECT_THAT(by_default, HasSubstr("eta = 0.02"));
  EXPECT_EQ(by_default.find("lid-driven cavity (e2e)"), std::string::npos);

  // Without job.json (a solver's own results directory) the caption is the scene's title and the
  // directory's name, as before; a job.json that is not a job's JSON is exit 2.
  fs::rename(out / "job.json", root_ / "job.json.kept");
  const std::string plain = caption("caption_plain");
  EXPECT_THAT(plain, HasSubstr("lid-driven cavity (e2e)"));
  EXPECT_THAT(plain, HasSubstr("captioned"));
  EXPECT_THAT(plain, HasSubstr("eta = 0.02"));
  std::ofstream(out / "job.json") << "{\"overrides\": 3}";
  const CliRun broken = Cli({"plot", out.string(), "--out", (root_ / "broken.png").string()});
  EXPECT_EQ(broken.code, 2) << broken.err;
  EXPECT_THAT(broken.err, HasSubstr("job.json"));
}

TEST_F(CliTest, WatchJsonYieldsProgressAndTheFinalState) {
  // 2000 steps (a few seconds): the job is still running when the watch connects, so the watch sees
  // progress events and not only the final state.
  const CliRun submit = Cli({"submit", (root_ / "cavity.toml").string(), "--set", "time.end=20"});
  ASSERT_EQ(submit.code, 0) << submit.err;
  const std::string job = FirstLine(submit.out);
  const CliRun watch = Cli({"watch", job, "--json"});
  ASSERT_EQ(watch.code, 0) << watch.err;
  EXPECT_THAT(watch.out, HasSubstr("\"progress\":{"));
  std::istringstream lines(watch.out);
  std::string line, last;
  int count = 0;
  while (std::getline(lines, line)) {
    ASSERT_EQ(line.front(), '{') << line;
    ASSERT_EQ(line.back(), '}') << line;
    last = line;
    ++count;
  }
  EXPECT_GT(count, 2);
  EXPECT_THAT(last, HasSubstr("\"state\":\"COMPLETED\""));
}

TEST_F(CliTest, CancelStopsALongJob) {
  const CliRun submit =
      Cli({"submit", (root_ / "cavity.toml").string(), "--set", "time.end=100000"});
  ASSERT_EQ(submit.code, 0) << submit.err;
  const std::string job = FirstLine(submit.out);
  AwaitState(job, "RUNNING");
  const CliRun cancel = Cli({"cancel", job});
  ASSERT_EQ(cancel.code, 0) << cancel.err;
  EXPECT_THAT(cancel.out, HasSubstr(job));
  const CliRun watch = Cli({"watch", job});
  EXPECT_EQ(watch.code, 1) << watch.out << watch.err;
  EXPECT_THAT(watch.out, HasSubstr("cancelled"));
  const CliRun again = Cli({"cancel", job});
  EXPECT_EQ(again.code, 6) << again.err;  // already finished: FAILED_PRECONDITION
}

TEST_F(CliTest, WatchResumesAcrossADaemonRestart) {
  // 3000 steps (about 3 s on a quiet machine, longer under load): the job is still running when the
  // daemon is killed, which happens only once the watch has printed its first event, so the watch
  // is connected to the first daemon however long the client takes to start on a loaded machine.
  const CliRun submit = Cli({"submit", (root_ / "cavity.toml").string(), "--set", "time.end=30"});
  ASSERT_EQ(submit.code, 0) << submit.err;
  const std::string job = FirstLine(submit.out);
  AwaitState(job, "RUNNING");
  CliRun watch;
  std::atomic<bool> printed{false};
  std::thread watcher([&] {
    watch = Cli({"watch", job, "--json", "--reconnect-seconds", "600"}, Env(), &printed);
  });
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!printed.load() && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(printed.load()) << "the watch printed nothing within 60 s";
  daemon_->Kill(SIGKILL);
  StartDaemon(server_);  // the same port, the same store
  watcher.join();
  EXPECT_EQ(watch.code, 0) << watch.err;
  EXPECT_THAT(watch.err, HasSubstr("reconnecting"));
  EXPECT_THAT(watch.out, HasSubstr("\"state\":\"COMPLETED\""));
}

// dt = 0.05 on the 16 x 16 cavity: U dt / h = 0.8 > 0.64 (the accuracy envelope). `show` prints
// the warning with the key and a value to set, `show --json` carries it as the proto field.
TEST_F(CliTest, ShowPrintsTheAccuracyWarnings) {
  const CliRun submit = Cli({"submit", (root_ / "cavity.toml").string(), "--set", "time.dt=0.05",
                             "--set", "time.end=0.1", "--wait"});
  ASSERT_EQ(submit.code, 0) << submit.out << submit.err;
  const std::string job = FirstLine(submit.out);
  const CliRun show = Cli({"show", job});
  ASSERT_EQ(show.code, 0) << show.err;
  EXPECT_THAT(show.out, HasSubstr("warning:     U dt / h = 0.8 (allowed <= 0.64, "));
  EXPECT_THAT(show.out, HasSubstr("set time.dt = 0.025 (now 0.05)"));
  const CliRun json = Cli({"show", job, "--json"});
  ASSERT_EQ(json.code, 0) << json.err;
  EXPECT_THAT(json.out, HasSubstr("\"warnings\":[{\"setting\":\"U dt / h\",\"value\":0.8"));
  EXPECT_THAT(json.out, HasSubstr("\"key\":\"time.dt\",\"current\":\"0.05\""));
  // Inside the envelope: no warning line.
  const CliRun inside = Cli({"submit", (root_ / "cavity.toml").string(), "--wait"});
  ASSERT_EQ(inside.code, 0) << inside.err;
  EXPECT_THAT(Cli({"show", FirstLine(inside.out)}).out, Not(HasSubstr("warning:")));
}

TEST_F(CliTest, InvalidSceneExitsTwoNamingTheKey) {
  const CliRun bad =
      Cli({"submit", (root_ / "cavity.toml").string(), "--set", "fluid.viscosity=-1"});
  EXPECT_EQ(bad.code, 2);
  EXPECT_THAT(bad.err, HasSubstr("fluid.viscosity"));
  EXPECT_THAT(bad.err, HasSubstr("invalid argument"));
  const CliRun no_file = Cli({"submit", (root_ / "absent.toml").string()});
  EXPECT_EQ(no_file.code, 2);
  const CliRun no_job = Cli({"show", "no-such-job"});
  EXPECT_EQ(no_job.code, 3);
}

TEST_F(CliTest, TimeGivesTheJobsTimeLimitAndABadOneExitsTwo) {
  const std::string scene = (root_ / "cavity.toml").string();
  const CliRun submit = Cli({"submit", scene, "--time", "1:30:00", "--wait"});
  ASSERT_EQ(submit.code, 0) << submit.out << submit.err;
  const std::string job = FirstLine(submit.out);
  EXPECT_THAT(Cli({"show", job}).out, HasSubstr("time limit:  1h30m (5400 s, of one run)"));
  EXPECT_THAT(Cli({"show", job, "--json"}).out, HasSubstr("\"time_limit_seconds\":5400"));
  const CliRun study =
      Cli({"study", scene, "--grid", "fluid.viscosity=0.01,0.02", "--time", "90m", "--json"});
  ASSERT_EQ(study.code, 0) << study.err;
  EXPECT_THAT(study.out, HasSubstr("\"time_limit_seconds\":5400"));
  // Refused by the CLI: not a positive duration.
  const CliRun zero = Cli({"submit", scene, "--time", "0"});
  EXPECT_EQ(zero.code, 2);
  EXPECT_THAT(zero.err, HasSubstr("--time 0: not positive"));
  const CliRun word = Cli({"study", scene, "--grid", "fluid.viscosity=0.01", "--time", "soon"});
  EXPECT_EQ(word.code, 2);
  EXPECT_THAT(word.err, HasSubstr("expected a positive duration"));
  // Refused by the daemon: over its limit (a year without max_wall_seconds).
  const CliRun long_run = Cli({"submit", scene, "--time", "400d"});
  EXPECT_EQ(long_run.code, 2);
  EXPECT_THAT(long_run.err, HasSubstr("time_limit_seconds = 34560000 is not allowed"));
}

TEST_F(CliTest, WrongTokenExitsFourAndOtherUsersSeeNothing) {
  const CliRun wrong = Cli({"list", "--token", "not-a-token"});
  EXPECT_EQ(wrong.code, 4);
  EXPECT_THAT(wrong.err, HasSubstr("unauthenticated"));
  const CliRun none = Cli({"list"}, Env(true, false));
  EXPECT_EQ(none.code, 4);

  const CliRun submit = Cli({"submit", (root_ / "cavity.toml").string()});
  ASSERT_EQ(submit.code, 0) << submit.err;
  const std::string job = FirstLine(submit.out);
  const CliRun bob = Cli({"show", job, "--token", "bob-token-0123456789"});
  EXPECT_EQ(bob.code, 3);
}

TEST_F(CliTest, ConfigPrecedenceIsFlagThenEnvironmentThenFile) {
  const fs::path xdg = root_ / "xdg";
  fs::create_directories(xdg / "dlmfd");
  std::ofstream(xdg / "dlmfd" / "config.toml")
      << "server = \"" << server_ << "\"\ntoken = \"alice-token-0123456789\"\n";
  auto env = Env(false, false);
  env["XDG_CONFIG_HOME"] = xdg.string();
  EXPECT_EQ(Cli({"list"}, env).code, 0);  // file alone
  env["DLMFD_SERVER"] = "127.0.0.1:1";
  EXPECT_EQ(Cli({"list"}, env).code, 5);                       // environment beats file
  EXPECT_EQ(Cli({"list", "--server", server_}, env).code, 0);  // flag beats environment
  EXPECT_EQ(Cli({"--server", server_, "list"}, env).code, 0);  // also before the command
  env.erase("DLMFD_SERVER");
  env["DLMFD_TOKEN"] = "not-a-token";
  EXPECT_EQ(Cli({"list"}, env).code, 4);  // environment token beats the file's
  EXPECT_EQ(Cli({"list", "--token", "alice-token-0123456789"}, env).code, 0);

  std::ofstream(xdg / "dlmfd" / "config.toml") << "servr = \"x\"\n";
  const CliRun typo = Cli({"list"}, env);
  EXPECT_EQ(typo.code, 2);
  EXPECT_THAT(typo.err, HasSubstr("servr"));
}

// Two disks settling in a closed box, 20 steps: the table's particle columns and fall speed.
const std::string kPair = "title = \"two disks settling (cli e2e)\"\ngravity = [0.0, -981.0]\n" +
                          dlmfd::testing::WalledBoxDomain("1.0, 2.0", "0.0625") + R"toml([fluid]
density = 1.0
viscosity = 0.1
[time]
dt = 0.002
end = 0.04
[[particles]]
center = [0.5, 1.5]
diameter = 0.25
density = 1.5
[[particles]]
center = [0.5, 1.0]
diameter = 0.25
density = 1.5
[particle_mesh]
h = 0.0625
[output]
fields_every = 0
particles_every = 0
checkpoint_every = 0
)toml";

// A study end to end: study, table (CSV, JSON, chosen columns), chart against the parameter, the
// log and inputs of a point, then delete of the whole study.
TEST_F(CliTest, TableChartLogsInputsAndDeleteOfAStudy) {
  std::ofstream(root_ / "pair.toml") << kPair;
  const CliRun study = Cli({"study", (root_ / "pair.toml").string(), "--grid",
                            "fluid.viscosity=0.1,0.2", "--name", "pair"});
  ASSERT_EQ(study.code, 0) << study.err;
  const std::string first = FirstLine(study.out);  // "study s-...: 2 jobs"
  const std::string id = first.substr(6, first.find(':') - 6);
  ASSERT_EQ(id.rfind("s-", 0), 0u) << study.out;
  CliRun table;
  for (;;) {
    table = Cli({"table", "--study", id, "--columns", "status"});
    ASSERT_EQ(table.code, 0) << table.err;
    if (table.out == "status\ncompleted\ncompleted\n") break;
    ASSERT_THAT(table.out, Not(HasSubstr("failed")));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const CliRun csv = Cli({"table", "--study", id});
  ASSERT_EQ(csv.code, 0) << csv.err;
  EXPECT_THAT(
      FirstLine(csv.out),
      HasSubstr("job,name,state,fluid.viscosity,status,reason,steps,time,wall_seconds,"
                "fall_speed,min_gap,min_wall_gap,max_trA,min_eig_A,Re,De,E,M,p0.radius,p0.x,"
                "p0.y,p0.angle,p0.u,"));
  EXPECT_THAT(csv.out, HasSubstr(",completed,0.1,completed,,20,0.04,"));
  EXPECT_THAT(csv.out, HasSubstr(",completed,0.2,completed,,20,0.04,"));
  const CliRun json = Cli({"table", "--study", id, "--format", "json", "--columns",
                           "fluid.viscosity,steps,max_trA,p1.radius"});
  ASSERT_EQ(json.code, 0) << json.err;
  // Typed values: the parameter a number, steps an integer, a Newtonian max_trA null.
  EXPECT_THAT(json.out, HasSubstr("\"fluid.viscosity\": 0.1,\n    \"steps\": 20,\n"
                                  "    \"max_trA\": null,\n    \"p1.radius\": 0.125"));
  const CliRun unknown = Cli({"table", "--study", id, "--columns", "nope"});
  EXPECT_EQ(unknown.code, 2);
  EXPECT_THAT(unknown.err, HasSubstr("--columns nope: no such column"));

  const fs::path png = root_ / "study.png";
  const CliRun chart = Cli({"chart", "--study", id, "--x", "fluid.viscosity", "--y", "fall_speed",
                            "--out", png.string(), "--width", "400", "--height", "300"});
  ASSERT_EQ(chart.code, 0) << chart.err;
  EXPECT_EQ(FirstLine(chart.out), png.string());
  EXPECT_EQ(Slurp(png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // One line per value of --group, named by the value under a legend titled by the key.
  const CliRun grouped =
      Cli({"chart", "--study", id, "--x", "fluid.viscosity", "--y", "steps", "--group",
           "fluid.viscosity", "--out", png.string(), "--width", "400", "--height", "300"});
  ASSERT_EQ(grouped.code, 0) << grouped.err;
  EXPECT_THAT(grouped.err, HasSubstr("legend (fluid.viscosity): 0.1; 0.2\n"));

  const std::string job = csv.out.substr(
      csv.out.find('\n') + 1, csv.out.find(',', csv.out.find('\n')) - csv.out.find('\n') - 1);
  const CliRun logs = Cli({"logs", job});
  ASSERT_EQ(logs.code, 0) << logs.err;
  EXPECT_THAT(logs.out, HasSubstr("completed after 20 steps"));
  const CliRun follow = Cli({"logs", job, "--follow", "--level", "warn"});
  ASSERT_EQ(follow.code, 0) << follow.err;  // a finished job: follow returns at the end
  EXPECT_THAT(follow.out, Not(HasSubstr("[info]")));
  EXPECT_THAT(follow.out, HasSubstr("[warning] accuracy"));
  const CliRun inputs = Cli({"inputs", job});
  ASSERT_EQ(inputs.code, 0) << inputs.err;
  EXPECT_THAT(inputs.out, HasSubstr("#   fluid.viscosity=0.1\n"));
  EXPECT_THAT(inputs.out, HasSubstr(kPair));
  const CliRun as_run = Cli({"inputs", job, "--as-run"});
  ASSERT_EQ(as_run.code, 0) << as_run.err;
  EXPECT_THAT(as_run.out, HasSubstr("viscosity = 0.1"));
  EXPECT_THAT(as_run.out, HasSubstr("[collisions]"));  // the defaults filled in

  const CliRun late = Cli({"priority", job, "3"});
  EXPECT_EQ(late.code, 6) << late.err;  // finished: FAILED_PRECONDITION
  const CliRun remove = Cli({"delete", "--study", id});
  ASSERT_EQ(remove.code, 0) << remove.err;
  EXPECT_THAT(remove.err, HasSubstr("2 jobs deleted"));
  const CliRun gone = Cli({"table", "--study", id});
  EXPECT_EQ(gone.code, 3) << gone.err;
  EXPECT_EQ(Cli({"show", job}).code, 3);
}

// logs without --follow prints what the running job has logged and returns; hold refuses a
// running job; delete of a running job needs --force.
TEST_F(CliTest, LogsOfARunningJobReturnAndItsDeleteNeedsForce) {
  const CliRun submit =
      Cli({"submit", (root_ / "cavity.toml").string(), "--set", "time.end=100000"});
  ASSERT_EQ(submit.code, 0) << submit.err;
  const std::string job = FirstLine(submit.out);
  AwaitState(job, "RUNNING");
  for (;;) {  // the solver has written its first line
    const CliRun logs = Cli({"logs", job});
    ASSERT_EQ(logs.code, 0) << logs.err;
    if (logs.out.find("running") != std::string::npos) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const CliRun hold = Cli({"hold", job});
  EXPECT_EQ(hold.code, 6) << hold.err;  // running: only a queued job is held
  const CliRun refused = Cli({"delete", job});
  EXPECT_EQ(refused.code, 6) << refused.err;
  EXPECT_THAT(refused.err, HasSubstr("--force"));
  const CliRun forced = Cli({"delete", job, "--force"});
  ASSERT_EQ(forced.code, 0) << forced.err;
  EXPECT_THAT(forced.out, HasSubstr(job + " deleted"));
}

}  // namespace
