// The slurm executor's parts without a Slurm: the state map (every state of slurm 22.05), the
// batch script and sbatch's arguments, the parsing of sbatch --parsable, of squeue --json (a real
// output of slurm 22.05, OpenAPI v0.0.38, captured from scripts/slurm-dev.sh's Slurm) and of the
// jobcomp file (real lines of jobcomp/filetxt), of a throttled job array and of a slurmctld that
// does not answer, the job array's script and arguments, the tail of a growing event file, the
// executor's configuration and the cluster config example of deploy/.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include "config.h"
#include "dlmfd/solver/event_file.h"
#include "event_file_tail.h"
#include "executor.h"
#include "job_time_limit.h"
#include "service_error.h"
#include "slurm_commands.h"
#include "slurm_states.h"

namespace dlmfd::server {
namespace {
namespace fs = std::filesystem;

std::string ReadFixture(const std::string& name) {
  std::ifstream in(std::string(DLMFD_SOURCE_DIR) + "/tests/server/data/" + name);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(SlurmStates, EveryStateMapsOntoOursWithItsReason) {
  struct Case {
    const char* slurm;
    bool finished;
    JobState state;
    bool retryable;
    bool waiting;  // not started: the API shows the job QUEUED
  };
  const Case cases[] = {
      {"PENDING", false, JobState::kRunning, false, true},
      {"RUNNING", false, JobState::kRunning, false, false},
      {"SUSPENDED", false, JobState::kRunning, false, false},
      {"COMPLETING", false, JobState::kRunning, false, false},
      {"CONFIGURING", false, JobState::kRunning, false, true},
      {"REQUEUED", false, JobState::kRunning, false, true},
      {"REQUEUE_HOLD", false, JobState::kRunning, false, true},
      {"REQUEUE_FED", false, JobState::kRunning, false, true},
      {"RESV_DEL_HOLD", false, JobState::kRunning, false, true},
      {"RESIZING", false, JobState::kRunning, false, false},
      {"SIGNALING", false, JobState::kRunning, false, false},
      {"STAGE_OUT", false, JobState::kRunning, false, false},
      {"STOPPED", false, JobState::kRunning, false, false},
      {"COMPLETED", true, JobState::kCompleted, false, false},
      {"CANCELLED", true, JobState::kCancelled, false, false},
      {"FAILED", true, JobState::kFailed, false, false},
      {"TIMEOUT", true, JobState::kFailed, true, false},
      {"NODE_FAIL", true, JobState::kFailed, true, false},
      {"PREEMPTED", true, JobState::kFailed, true, false},
      {"BOOT_FAIL", true, JobState::kFailed, true, false},
      {"OUT_OF_MEMORY", true, JobState::kFailed, false, false},
      {"DEADLINE", true, JobState::kFailed, false, false},
  };
  std::set<std::string> reasons;
  for (const Case& c : cases) {
    const SlurmStateMeaning m = MapSlurmState(c.slurm, "");
    EXPECT_EQ(m.finished, c.finished) << c.slurm;
    EXPECT_EQ(m.state, c.state) << c.slurm;
    EXPECT_EQ(m.retryable, c.retryable) << c.slurm;
    EXPECT_EQ(m.waiting, c.waiting) << c.slurm;
    EXPECT_EQ(m.reason.rfind(std::string("Slurm: ") + c.slurm + ": ", 0), 0u) << m.reason;
    EXPECT_EQ(m.reason.find("does not know"), std::string::npos) << m.reason;
    reasons.insert(m.reason);
  }
  EXPECT_EQ(reasons.size(), std::size(cases));  // each state says something of its own
}

TEST(SlurmStates, ReasonsFlagsAndUnknownStates) {
  EXPECT_EQ(
      MapSlurmState("PENDING", "Priority").reason,
      "Slurm: PENDING: waiting in Slurm's queue (Priority: jobs of higher priority go first)");
  EXPECT_EQ(MapSlurmState("PENDING", "JobArrayTaskLimit").reason,
            "Slurm: PENDING: waiting in Slurm's queue (JobArrayTaskLimit: the study's max_running "
            "(the array's throttle) holds it back)");
  // A reason without a meaning here is shown as Slurm gives it.
  EXPECT_EQ(MapSlurmState("PENDING", "AssocGrpCpuLimit").reason,
            "Slurm: PENDING: waiting in Slurm's queue (AssocGrpCpuLimit)");
  EXPECT_EQ(MapSlurmState("RUNNING", "None").reason, "Slurm: RUNNING: running");
  // sacct and the jobcomp file write "CANCELLED by 0"; squeue may append '+'.
  EXPECT_EQ(MapSlurmState("CANCELLED by 0", "").state, JobState::kCancelled);
  EXPECT_TRUE(MapSlurmState("CANCELLED+", "").finished);
  const SlurmStateMeaning unknown = MapSlurmState("POWER_UP_NODE", "");
  EXPECT_FALSE(unknown.finished);
  EXPECT_NE(unknown.reason.find("POWER_UP_NODE"), std::string::npos);
}

BatchJob Job() {
  BatchJob job;
  job.name = "dlmfd-j1";
  job.job_dir = "/shared/jobs/j1";
  job.solver = "/opt/dlmfd/bin/dlmfd-solve";
  job.scene_path = "/shared/jobs/j1/scene.in.toml";
  job.results_dir = "/shared/jobs/j1/results";
  job.log_path = "/shared/jobs/j1/solver.log";
  job.overrides = {"fluid.relaxation_time=2", "title=it's"};
  job.resume = true;
  job.threads = 4;
  job.memory_mb = 300;
  return job;
}

TEST(SlurmCommands, SbatchArgumentsCarryTheJobAndTheSettings) {
  SlurmSettings settings;
  auto args = SbatchArguments(Job(), settings, "/shared/jobs/j1/slurm.sh");
  const std::vector<std::string> plain = {"--parsable",
                                          "--job-name=dlmfd-j1",
                                          "--cpus-per-task=4",
                                          "--ntasks=1",
                                          "--mem=300M",
                                          "--output=/shared/jobs/j1/solver.log",
                                          "--open-mode=append",
                                          "--chdir=/shared/jobs/j1",
                                          "/shared/jobs/j1/slurm.sh"};
  EXPECT_EQ(args, plain);
  BatchJob limited = Job();
  limited.time_limit_seconds = 90 * 60;
  settings.signal_seconds = 120;
  settings.partition = "short";
  settings.account = "lab";
  settings.qos = "normal";
  settings.sbatch_options = " --constraint=avx2  --exclusive ";
  args = SbatchArguments(limited, settings, "S");
  const std::vector<std::string> tail = {
      "--time=90",    "--signal=B:USR1@120", "--partition=short", "--account=lab",
      "--qos=normal", "--constraint=avx2",   "--exclusive",       "S"};
  ASSERT_GE(args.size(), tail.size());
  EXPECT_EQ(std::vector<std::string>(args.end() - static_cast<long>(tail.size()), args.end()),
            tail);
  // Slurm counts whole minutes: 90 s is --time=2; the warning comes at most half the limit early.
  limited.time_limit_seconds = 90;
  args = SbatchArguments(limited, settings, "S");
  EXPECT_NE(std::find(args.begin(), args.end(), "--time=2"), args.end());
  EXPECT_NE(std::find(args.begin(), args.end(), "--signal=B:USR1@60"), args.end());
}

TEST(JobTimeLimitUnits, TheJobsOwnElseTheDaemonsAndNeverMore) {
  Config config;
  const auto daemon_limit = [&config] { return MakeExecutor(config)->TimeLimit(); };
  EXPECT_EQ(daemon_limit().seconds, 0);
  EXPECT_EQ(EffectiveTimeLimit(0, daemon_limit()), 0);
  EXPECT_EQ(EffectiveTimeLimit(600, daemon_limit()), 600);
  EXPECT_NO_THROW(CheckTimeLimit(kMostTimeLimitSeconds, daemon_limit()));
  EXPECT_THROW(CheckTimeLimit(kMostTimeLimitSeconds + 1, daemon_limit()), ServiceError);
  EXPECT_THROW(CheckTimeLimit(-1, daemon_limit()), ServiceError);
  config.max_wall_seconds = 7200;
  EXPECT_EQ(daemon_limit().seconds, 7200);
  // slurm_time_limit_minutes counts under the slurm executor only; the smaller limit wins.
  config.slurm.time_limit_minutes = 90;
  EXPECT_EQ(daemon_limit().seconds, 7200);
  EXPECT_FALSE(MakeExecutor(config)->LimitsTimeItself());
  config.executor = "slurm";
  EXPECT_TRUE(MakeExecutor(config)->LimitsTimeItself());
  EXPECT_EQ(daemon_limit().seconds, 5400);
  EXPECT_EQ(EffectiveTimeLimit(0, daemon_limit()), 5400);
  EXPECT_EQ(EffectiveTimeLimit(60, daemon_limit()), 60);
  EXPECT_NO_THROW(CheckTimeLimit(5400, daemon_limit()));
  try {
    CheckTimeLimit(5401, daemon_limit());
    ADD_FAILURE() << "5401 s accepted over slurm_time_limit_minutes = 90";
  } catch (const ServiceError& e) {
    EXPECT_EQ(e.code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_EQ(std::string(e.what()),
              "time_limit_seconds = 5401 is not allowed: expected 0 (the daemon's limit) or 1 to "
              "5400 (max_wall_seconds, slurm_time_limit_minutes)");
  }
  config.max_wall_seconds = 0;
  EXPECT_EQ(daemon_limit().seconds, 5400);
  EXPECT_EQ(daemon_limit().settings, "slurm_time_limit_minutes");
  EXPECT_EQ(SlurmTimeMinutes(1), 1);
  EXPECT_EQ(SlurmTimeMinutes(60), 1);
  EXPECT_EQ(SlurmTimeMinutes(61), 2);
  EXPECT_EQ(SlurmSignalLead(90, 120), 120);
  EXPECT_EQ(SlurmSignalLead(1, 120), 30);
}

TEST(SlurmCommands, BatchScriptRunsTheSolverWithItsEventFileAndRecordsItsExit) {
  const std::string script = BatchScript(Job());
  EXPECT_EQ(script.rfind("#!/bin/bash\n", 0), 0u);
  EXPECT_NE(script.find("exec 3>>events.bin\n"), std::string::npos);
  EXPECT_NE(script.find("'/opt/dlmfd/bin/dlmfd-solve' '/shared/jobs/j1/scene.in.toml' --out "
                        "'/shared/jobs/j1/results' --set 'fluid.relaxation_time=2' --set "
                        "'title=it'\\''s' --events 3 $resume &\n"),
            std::string::npos)
      << script;
  EXPECT_NE(script.find("resume=--resume\n"), std::string::npos) << script;
  // Slurm ran it again (scontrol requeue): it resumes from the checkpoint of the run before.
  EXPECT_NE(script.find("if [ \"${SLURM_RESTART_COUNT:-0}\" -gt 0 ] && [ -f "
                        "'/shared/jobs/j1/results/checkpoint.h5' ]; then resume=--resume; fi"),
            std::string::npos)
      << script;
  BatchJob fresh = Job();
  fresh.resume = false;
  EXPECT_NE(BatchScript(fresh).find("resume=\n"), std::string::npos);
  EXPECT_NE(script.find("trap 'touch slurm.warned; kill -TERM $solver 2>/dev/null' USR1"),
            std::string::npos);
  EXPECT_NE(script.find("echo \"$status ${SLURM_RESTART_COUNT:-0}\" > solver.exit.tmp && mv "
                        "solver.exit.tmp solver.exit"),
            std::string::npos)
      << script;
  EXPECT_EQ(ShellQuote("a'b"), "'a'\\''b'");
}

TEST(SlurmCommands, AStudyIsOneJobArrayWhoseTasksRunTheirJobsScripts) {
  EXPECT_EQ(ArraySpec({0, 1, 2, 3, 4, 5}, 2), "0-5%2");
  EXPECT_EQ(ArraySpec({0, 2, 3, 4, 7}, 0), "0,2-4,7");
  EXPECT_EQ(ArraySpec({3}, 1), "3%1");
  EXPECT_EQ(ArrayTaskId("120", 4), "120_4");
  BatchJob array = Job();
  array.name = "dlmfd-s-1";
  array.job_dir = "/shared/jobs/slurm-arrays/dlmfd-s-1-AbC123";
  array.log_path = array.job_dir + "/task-%a.log";
  array.array = ArraySpec({0, 1, 2}, 2);
  const auto args = SbatchArguments(array, SlurmSettings(), array.job_dir + "/slurm.sh");
  EXPECT_NE(std::find(args.begin(), args.end(), "--array=0-2%2"), args.end());
  EXPECT_NE(std::find(args.begin(), args.end(), "--output=" + array.log_path), args.end());
  EXPECT_NE(std::find(args.begin(), args.end(), "--job-name=dlmfd-s-1"), args.end());
  // A single job has no --array.
  for (const auto& a : SbatchArguments(Job(), SlurmSettings(), "S")) {
    EXPECT_NE(a.rfind("--array", 0), 0u) << a;
  }
  const std::string script =
      ArrayScript("dlmfd-s-1", {{0, "/shared/jobs/j-a"}, {2, "/shared/jobs/j-c d"}});
  EXPECT_EQ(script.rfind("#!/bin/bash\n", 0), 0u);
  EXPECT_NE(script.find("case \"$SLURM_ARRAY_TASK_ID\" in\n  0) dir='/shared/jobs/j-a' ;;\n  2) "
                        "dir='/shared/jobs/j-c d' ;;\n"),
            std::string::npos)
      << script;
  EXPECT_NE(script.find("exec /bin/bash \"$dir/slurm.sh\"\n"), std::string::npos) << script;
}

// The script itself, run by bash as Slurm would: each task runs its own job's script.
TEST(SlurmCommands, TheArrayScriptRunsTheTasksJobScript) {
  const fs::path dir = fs::temp_directory_path() / ("array_test_" + std::to_string(getpid()));
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  for (const char* name : {"a", "b"}) {
    std::ofstream(dir / name / "slurm.sh")
        << "echo " << name << " > " << (dir / "ran").string() << "\n";
  }
  const fs::path script = dir / "array.sh";
  std::ofstream(script) << ArrayScript("t", {{0, (dir / "a").string()}, {1, (dir / "b").string()}});
  const CommandResult one =
      RunCommand({"env", "SLURM_ARRAY_TASK_ID=1", "/bin/bash", script.string()});
  EXPECT_EQ(one.status, 0) << one.err;
  std::ifstream ran(dir / "ran");
  std::string which;
  ran >> which;
  EXPECT_EQ(which, "b");
  const CommandResult none =
      RunCommand({"env", "SLURM_ARRAY_TASK_ID=7", "/bin/bash", script.string()});
  EXPECT_EQ(none.status, 2);
  EXPECT_NE(none.err.find("no job for array task 7"), std::string::npos) << none.err;
  fs::remove_all(dir);
}

TEST(SlurmCommands, ParsesSbatchParsable) {
  EXPECT_EQ(ParseSbatchId("12345\n"), "12345");
  EXPECT_EQ(ParseSbatchId("678;cluster2\n"), "678");
  EXPECT_THROW(ParseSbatchId(""), std::runtime_error);
  EXPECT_THROW(ParseSbatchId("sbatch: error: Batch job submission failed\n"), std::runtime_error);
}

// squeue -h --name=N --states=... -o "%i %Z": the job of this name in this directory, not one of
// the same name elsewhere (another daemon's job directory).
TEST(SlurmCommands, FindsTheLiveJobOfANameInItsDirectory) {
  const std::vector<std::string> args = SqueueOfNameArguments("dlmfd-j7");
  EXPECT_NE(std::find(args.begin(), args.end(), "--name=dlmfd-j7"), args.end());
  EXPECT_NE(std::find(args.begin(), args.end(), "--format=%i %Z"), args.end());
  const std::string out = "41 /scratch/other/jobs/j7\n42 /shared/jobs/j7\n";
  EXPECT_EQ(ParseLiveJobIn(out, "/shared/jobs/j7"), "42");
  EXPECT_EQ(ParseLiveJobIn(out, "/shared/jobs/./j7/"), "42");
  EXPECT_EQ(ParseLiveJobIn(out, "/shared/jobs/j8"), "");
  EXPECT_EQ(ParseLiveJobIn("", "/shared/jobs/j7"), "");
}

TEST(SlurmCommands, ParsesARealSqueueJson) {
  const std::string json = ReadFixture("squeue_v0.0.38.json");
  ASSERT_FALSE(json.empty());
  const auto running = FindInSqueueJson(json, "3");
  ASSERT_TRUE(running);
  EXPECT_EQ(running->state, "RUNNING");
  EXPECT_EQ(running->reason, "None");
  const auto pending = FindInSqueueJson(json, "4");
  ASSERT_TRUE(pending);
  EXPECT_EQ(pending->state, "PENDING");
  EXPECT_EQ(pending->reason, "Dependency");
  EXPECT_EQ(FindInSqueueJson(json, "1")->reason, "BadConstraints");
  EXPECT_FALSE(FindInSqueueJson(json, "5"));
  EXPECT_FALSE(FindInSqueueJson(json, "33"));
  // Newer releases write job_state as an array.
  const auto array = FindInSqueueJson(
      R"({"jobs": [{"job_id": 9, "job_state": ["TIMEOUT"], "restart_cnt": 2}]})", "9");
  ASSERT_TRUE(array);
  EXPECT_EQ(array->state, "TIMEOUT");
  EXPECT_EQ(array->restarts, 2);
  EXPECT_THROW(FindInSqueueJson("squeue: error: slurm_load_jobs", "1"), std::runtime_error);
  EXPECT_THROW(FindInSqueueJson(R"({"errors": []})", "1"), std::runtime_error);
  // A slurmctld that does not answer: squeue --json exits 0 with no jobs and an error (captured
  // with scripts/slurm-dev.sh stop-slurmctld): not an answer that no job is there.
  try {
    ParseSqueueJson(ReadFixture("squeue_controller_down_v0.0.38.json"));
    ADD_FAILURE() << "an answer without a controller was taken for one";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("Failed while looking for jobs (slurm_load_jobs)"),
              std::string::npos)
        << e.what();
  }
}

// A job array with throttle 2 (sbatch --array=0-4%2) as squeue --json of slurm 22.05 shows it:
// tasks 0 and 1 running as jobs of their own, the array's record holding 2-4 back with the
// reason JobArrayTaskLimit (captured from scripts/slurm-dev.sh's Slurm; paths replaced).
TEST(SlurmCommands, ParsesARealSqueueJsonOfAThrottledArray) {
  const std::string json = ReadFixture("squeue_array_v0.0.38.json");
  ASSERT_FALSE(json.empty());
  const auto jobs = ParseSqueueJson(json);
  ASSERT_EQ(jobs.size(), 5u);
  EXPECT_EQ(jobs.at("14_0").state, "RUNNING");
  EXPECT_EQ(jobs.at("14_1").state, "RUNNING");
  for (const char* id : {"14_2", "14_3", "14_4"}) {
    EXPECT_EQ(jobs.at(id).state, "PENDING");
    EXPECT_EQ(jobs.at(id).reason, "JobArrayTaskLimit");
  }
  // The array's own job id and the tasks' job ids are not the daemon's ids.
  EXPECT_FALSE(FindInSqueueJson(json, "14"));
  EXPECT_FALSE(FindInSqueueJson(json, "15"));
  EXPECT_TRUE(FindInSqueueJson(json, "14_3"));
}

TEST(SlurmCommands, ParsesARealJobCompFile) {
  const std::string text = ReadFixture("jobcomp_filetxt.txt");
  const auto completed = FindInJobComp(text, "2");
  ASSERT_TRUE(completed);
  EXPECT_EQ(completed->state, "COMPLETED");
  EXPECT_EQ(completed->exit_code, "0:0");
  EXPECT_EQ(FindInJobComp(text, "1")->state, "FAILED");
  EXPECT_EQ(FindInJobComp(text, "3")->state, "CANCELLED");
  EXPECT_FALSE(FindInJobComp(text, "22"));  // "JobId=2" must not match "JobId=22"
  // A requeued job has one line per end: the last one counts.
  const auto last = FindInJobComp(
      "JobId=7 JobState=NODE_FAIL ExitCode=0:0\nJobId=7 JobState=COMPLETED "
      "ExitCode=0:0\n",
      "7");
  EXPECT_EQ(last->state, "COMPLETED");
  // Array tasks (real lines of jobcomp/filetxt, trimmed): by ArrayJobId_ArrayTaskId; the last
  // task keeps the array's job id.
  const std::string array =
      "JobId=5 UserId=root(0) GroupId=root(0) Name=i15x JobState=COMPLETED Partition=debug "
      "ArrayJobId=4 ArrayTaskId=0 DerivedExitCode=0:0 ExitCode=0:0 \n"
      "JobId=4 UserId=root(0) GroupId=root(0) Name=i15x JobState=TIMEOUT Partition=debug "
      "ArrayJobId=4 ArrayTaskId=5 DerivedExitCode=0:0 ExitCode=0:0 \n";
  EXPECT_EQ(FindInJobComp(array, "4_0")->state, "COMPLETED");
  EXPECT_EQ(FindInJobComp(array, "4_5")->state, "TIMEOUT");
  EXPECT_FALSE(FindInJobComp(array, "4"));
  EXPECT_FALSE(FindInJobComp(array, "5"));
}

TEST(SlurmCommands, TransientErrorsAreThoseOfAnUnreachableController) {
  EXPECT_TRUE(TransientSlurmError(
      "sbatch: error: Batch job submission failed: Unable to contact slurm controller (connect "
      "failure)\n"));
  EXPECT_TRUE(TransientSlurmError("sbatch: error: Socket timed out on send/recv operation\n"));
  EXPECT_FALSE(TransientSlurmError(
      "sbatch: error: Batch job submission failed: Invalid account or account/partition "
      "combination specified\n"));
  EXPECT_FALSE(TransientSlurmError(""));
}

TEST(SlurmCommands, RunCommandCollectsOutputAndStatus) {
  const CommandResult ok = RunCommand({"sh", "-c", "echo out; echo err >&2; exit 3"});
  EXPECT_EQ(ok.status, 3);
  EXPECT_EQ(ok.out, "out\n");
  EXPECT_EQ(ok.err, "err\n");
  EXPECT_EQ(RunCommand({"/nonexistent/sbatch"}).status, 127);
}

TEST(EventFileTail, DeliversEachCompleteEventOnceWhileTheFileGrows) {
  const fs::path path = fs::temp_directory_path() / ("tail_test_" + std::to_string(getpid()));
  fs::remove(path);
  EventFileTail tail(path.string());
  std::vector<int64_t> steps;
  auto collect = [&](const v1::SolverEvent& e) {
    steps.push_back(e.has_log() ? -1 : e.progress().step());
  };
  EXPECT_EQ(tail.ReadNew(collect), 0);  // no file yet
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  {
    solver::EventFileWriter writer(fd);
    for (int step = 1; step <= 3; ++step) {
      v1::SolverEvent e;
      e.mutable_progress()->set_step(step);
      ASSERT_TRUE(writer.Write(e));
    }
  }
  EXPECT_EQ(tail.ReadNew(collect), 3);
  EXPECT_EQ(tail.ReadNew(collect), 0);
  // Half of an event: nothing yet; its other half: the event, once.
  v1::SolverEvent big;  // over 127 bytes: a two-byte length
  big.mutable_log()->set_text(std::string(300, 'x'));
  const std::string body = big.SerializeAsString();
  ASSERT_GT(body.size(), 127u);
  ASSERT_LT(body.size(), 16384u);
  std::string framed(1, static_cast<char>(0x80 | (body.size() & 0x7f)));
  framed += static_cast<char>(body.size() >> 7);
  framed += body;
  ASSERT_EQ(write(fd, framed.data(), 100), 100);
  EXPECT_EQ(tail.ReadNew(collect), 0);
  ASSERT_EQ(write(fd, framed.data() + 100, framed.size() - 100),
            static_cast<ssize_t>(framed.size() - 100));
  EXPECT_EQ(tail.ReadNew(collect), 1);
  close(fd);
  fs::remove(path);
  ASSERT_EQ(steps.size(), 4u);
  EXPECT_EQ(steps, (std::vector<int64_t>{1, 2, 3, -1}));
}

Config Load(const std::vector<std::string>& args) {
  std::vector<const char*> argv = {"dlmfdd", "--solver", "/bin/true"};
  for (const auto& a : args) argv.push_back(a.c_str());
  Config config;
  LoadConfig(
      static_cast<int>(argv.size()), argv.data(), [](const char*) { return nullptr; }, config);
  return config;
}

// What the scheduler asks of an executor (executor.h), by configuration alone.
TEST(SlurmConfig, EachExecutorsCapacityLimitsAndJobDirectories) {
  Config local = Load({"--data-dir", "/tmp/d", "--max-concurrent", "3", "--slurm-shared-dir",
                       "/shared", "--slurm-max-submitted", "20"});
  const auto runs_locally = MakeExecutor(local);
  EXPECT_EQ(runs_locally->Capacity(), 3);
  EXPECT_EQ(runs_locally->JobDirectory("j-1"), "/tmp/d/jobs/j-1");
  EXPECT_FALSE(runs_locally->SubmitsStudiesTogether());
  EXPECT_EQ(runs_locally->NewStudyRuns("s-1", 2, 1).size(), 2u);
  Config slurm = local;
  slurm.executor = "slurm";
  const auto runs_in_slurm = MakeExecutor(slurm);
  EXPECT_EQ(runs_in_slurm->Capacity(), 20);
  EXPECT_EQ(runs_in_slurm->JobDirectory("j-1"), "/shared/j-1");
  EXPECT_TRUE(runs_in_slurm->SubmitsStudiesTogether());
  slurm.slurm.shared_dir.clear();
  EXPECT_EQ(MakeExecutor(slurm)->JobDirectory("j-1"), "/tmp/d/jobs/j-1");
  slurm.executor = "pbs";
  EXPECT_THROW(MakeExecutor(slurm), ConfigError);
}

TEST(SlurmConfig, ExecutorAndItsSettings) {
  EXPECT_EQ(Load({"--data-dir", "/tmp/d"}).executor, "local");
  const Config slurm = Load({"--data-dir", "/tmp/d", "--executor", "slurm", "--slurm-partition",
                             "short", "--slurm-poll-seconds", "5", "--slurm-max-submitted", "20"});
  EXPECT_EQ(slurm.executor, "slurm");
  EXPECT_EQ(slurm.slurm.partition, "short");
  EXPECT_EQ(slurm.slurm.poll_seconds, 5);
  EXPECT_EQ(slurm.slurm.max_submitted, 20);
  EXPECT_EQ(slurm.slurm.solver, "/bin/true");  // the daemon's solver unless slurm_solver is set
  EXPECT_EQ(slurm.slurm.max_attempts, 3);
  EXPECT_EQ(Load({"--data-dir", "/tmp/d", "--slurm-max-attempts", "1"}).slurm.max_attempts, 1);
  try {
    Load({"--data-dir", "/tmp/d", "--slurm-max-attempts", "0"});
    ADD_FAILURE() << "slurm_max_attempts 0 accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("slurm_max_attempts = 0 is not allowed: expected 1 to "
                                         "100"),
              std::string::npos);
  }
  try {
    Load({"--data-dir", "/tmp/d", "--executor", "pbs"});
    ADD_FAILURE() << "executor pbs accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("expected local or slurm"), std::string::npos);
  }
  try {
    Load({"--data-dir", "/tmp/d", "--slurm-poll-seconds", "0"});
    ADD_FAILURE() << "slurm_poll_seconds 0 accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("slurm_poll_seconds = 0 is not allowed: expected 1 to "
                                         "3600"),
              std::string::npos);
  }
}

// deploy/dlmfdd-slurm.toml.example loads (with a tokens file of this machine, since it listens
// beyond loopback) and sets every slurm_* key of docs/api.md's table.
// Issue 38: with --data-dir data (relative) every Slurm job failed: the batch script, which runs in
// the job directory, and sbatch's --output named paths relative to the daemon's directory.
TEST(SlurmConfig, RelativePathsAreMadeAbsoluteAgainstTheDaemonsDirectory) {
  const fs::path here = fs::current_path();
  const Config config = Load({"--data-dir", "data/", "--executor", "slurm", "--slurm-shared-dir",
                              "./shared/jobs", "--slurm-jobcomp-file", "slurm/../jobcomp.txt"});
  EXPECT_EQ(config.data_dir, (here / "data").string());
  EXPECT_EQ(config.slurm.shared_dir, (here / "shared" / "jobs").string());
  EXPECT_EQ(config.slurm.jobcomp_file, (here / "jobcomp.txt").string());
  EXPECT_EQ(config.solver, "/bin/true");
  EXPECT_EQ(Load({"--data-dir", "/tmp/d/"}).data_dir, "/tmp/d");
}

TEST(SlurmConfig, TheClusterExampleLoadsAndSetsEverySlurmKey) {
  const std::string example = std::string(DLMFD_SOURCE_DIR) + "/deploy/dlmfdd-slurm.toml.example";
  const fs::path tokens = fs::temp_directory_path() / ("tokens_" + std::to_string(getpid()));
  std::ofstream(tokens) << "0123456789abcdef0123 alice\n";
  fs::permissions(tokens, fs::perms::owner_read | fs::perms::owner_write);
  const Config config =
      Load({"--config", example, "--data-dir", "/tmp/d", "--tokens-file", tokens.string()});
  fs::remove(tokens);
  EXPECT_EQ(config.executor, "slurm");
  EXPECT_EQ(config.slurm.shared_dir, "/shared/dlmfd/jobs");
  EXPECT_EQ(config.slurm.solver, "/shared/dlmfd/bin/dlmfd-solve");
  EXPECT_EQ(config.slurm.max_attempts, 3);
  EXPECT_EQ(config.slurm.time_limit_minutes, 1440);
  std::ifstream api(std::string(DLMFD_SOURCE_DIR) + "/docs/api.md");
  std::ifstream in(example);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  int keys = 0;
  for (std::string line; std::getline(api, line);) {
    if (line.rfind("| slurm_", 0) != 0) continue;
    const std::string key = line.substr(2, line.find(' ', 2) - 2);
    ++keys;
    EXPECT_NE(text.find("\n" + key + " = "), std::string::npos) << key << " is not in " << example;
  }
  EXPECT_EQ(keys, 12);
}

}  // namespace
}  // namespace dlmfd::server
