// A study under the slurm executor against a real Slurm (scripts/slurm-dev.sh start): its six
// points go to Slurm as one job array with the study's throttle (max_running = 2: sbatch
// --array=0-5%2, Slurm holds the other tasks back with JobArrayTaskLimit, and the daemon shows
// those points QUEUED with Slurm's reason, not RUNNING), each task runs its own point, and each
// point stays a job of its own: its Slurm id ARRAYID_INDEX, its time limit, its stream, its
// results, its cancel (scancel ARRAYID_INDEX) and its retry (a new array of one). Skipped, naming
// scripts/slurm-dev.sh, when no Slurm answers sinfo.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "slurm_harness.h"

namespace dlmfd::testing {
namespace {
namespace fs = std::filesystem;

class SlurmStudy : public SlurmTest {};

// "A" of "A_I"; empty when the id is not an array task's.
std::string ArrayOf(const std::string& slurm_id) {
  const size_t underscore = slurm_id.find('_');
  return underscore == std::string::npos ? std::string() : slurm_id.substr(0, underscore);
}

// A study of the scene over fluid.viscosity with at most max_running jobs at once, each with the
// time limit (0: the daemon's).
v1::SubmitStudyResponse SubmitStudy(v1::Jobs::Stub& stub, const std::string& scene,
                                    const std::string& name, int max_running,
                                    const std::vector<std::string>& viscosities,
                                    int64_t time_limit_seconds = 0) {
  v1::SubmitStudyRequest request;
  request.set_scene(scene);
  request.set_name(name);
  request.set_max_running(max_running);
  request.set_time_limit_seconds(time_limit_seconds);
  auto* axis = request.add_axes();
  axis->set_key("fluid.viscosity");
  for (const auto& value : viscosities) axis->add_values(value);
  v1::SubmitStudyResponse study;
  auto context = Context();
  const grpc::Status status = stub.SubmitStudy(context.get(), request, &study);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return study;
}

TEST_F(SlurmStudy, SixPointsAreOneJobArrayWithThrottleTwoAndEachPointIsAJob) {
  ASSERT_TRUE(StartDaemon()) << daemon().Log();
  auto* stub = this->stub();
  // 800 steps of a 16 x 16 cavity: about a second each; a time limit of 5 minutes each.
  const v1::SubmitStudyResponse study = SubmitStudy(
      *stub, CavityScene(8.0), "array", 2, {"0.01", "0.02", "0.03", "0.04", "0.05", "0.06"}, 300);
  ASSERT_EQ(study.jobs_size(), 6);
  // Every point has its task of one array, in the study's order.
  std::string array;
  ASSERT_TRUE(WaitUntil([&] {
    for (const auto& job : study.jobs()) {
      if (GetJob(*stub, job.id()).slurm_job_id().empty()) return false;
    }
    return true;
  })) << daemon().Log();
  for (int k = 0; k < 6; ++k) {
    const std::string id = GetJob(*stub, study.jobs(k).id()).slurm_job_id();
    if (k == 0) array = ArrayOf(id);
    EXPECT_EQ(id, array + "_" + std::to_string(k));
  }
  ASSERT_FALSE(array.empty());
  // Slurm holds the array to 2 tasks at once: its throttle, and while it runs, no more than 2
  // running, the others pending for JobArrayTaskLimit.
  const std::string throttle =
      Shell("scontrol show job " + array + " | grep -o 'ArrayTaskThrottle=[0-9]*' | head -1");
  EXPECT_EQ(throttle, "ArrayTaskThrottle=2\n");
  // Each task's --time: the points' time limit, in minutes.
  EXPECT_EQ(Shell("scontrol show job " + array + " | grep -o 'TimeLimit=[0-9:-]*' | sort -u"),
            "TimeLimit=00:05:00\n");
  int most_running = 0;
  bool held_by_limit = false;
  std::set<std::string> seen_running;
  // The points the daemon showed waiting for the throttle: QUEUED with Slurm's reason, never
  // RUNNING while Slurm holds them.
  std::set<std::string> shown_waiting;
  WaitUntil([&] {
    for (const auto& point : study.jobs()) {
      const v1::Job job = GetJob(*stub, point.id());
      if (job.slurm_state() == "PENDING") {
        EXPECT_EQ(job.state(), v1::QUEUED) << job.ShortDebugString();
        EXPECT_EQ(job.started_time(), 0.0) << job.ShortDebugString();
      }
      if (job.state() == v1::QUEUED && job.slurm_reason() == "JobArrayTaskLimit" &&
          job.reason().find("Slurm: PENDING") != std::string::npos &&
          job.reason().find("max_running") != std::string::npos) {
        shown_waiting.insert(job.id());
      }
    }
    std::istringstream lines(Shell("squeue -h -r -j " + array + " -o '%i %T %r' 2>/dev/null"));
    int running = 0, listed = 0;
    for (std::string id, state, reason; lines >> id >> state >> reason;) {
      ++listed;
      if (state == "RUNNING") {
        ++running;
        seen_running.insert(id);
      }
      if (state == "PENDING" && reason == "JobArrayTaskLimit") held_by_limit = true;
    }
    most_running = std::max(most_running, running);
    return listed == 0;
  });
  EXPECT_LE(most_running, 2);
  EXPECT_GE(seen_running.size(), 2u);
  EXPECT_TRUE(held_by_limit);
  // The last points wait two rounds of about a second; squeue is asked every second.
  EXPECT_GE(shown_waiting.size(), 1u) << daemon().Log();
  // Each point is a job of its own that ran its own scene.
  for (int k = 0; k < 6; ++k) {
    const v1::Job done = WaitFinished(*stub, study.jobs(k).id());
    EXPECT_EQ(done.state(), v1::COMPLETED) << done.reason() << "\n" << daemon().Log();
    EXPECT_EQ(done.step(), 800);
    EXPECT_TRUE(fs::exists(done.results_dir() + "/summary.json"));
  }
  // Slurm ran six tasks of the one array, each once.
  EXPECT_TRUE(WaitUntil([&] { return SlurmEndsOfName("dlmfd-" + study.study_id()) >= 6; }));
  EXPECT_EQ(SlurmEndsOfName("dlmfd-" + study.study_id()), 6);
}

TEST_F(SlurmStudy, APointIsCancelledAsItsTaskAndRetriedAsAnArrayOfOne) {
  ASSERT_TRUE(StartDaemon()) << daemon().Log();
  auto* stub = this->stub();
  // Each runs until cancelled.
  const v1::SubmitStudyResponse study =
      SubmitStudy(*stub, CavityScene(1.0e4), "cancel", 1, {"0.01", "0.02"});
  ASSERT_EQ(study.jobs_size(), 2);
  const std::string first = study.jobs(0).id(), second = study.jobs(1).id();
  // The first point runs (its stream comes as a local job's); the second waits in Slurm behind
  // the throttle of 1. Both are cancelled: each its own task.
  WaitForProgress(*stub, first);
  const std::string second_task = GetJob(*stub, second).slurm_job_id();
  ASSERT_FALSE(second_task.empty());
  EXPECT_EQ(Shell("squeue -h -j " + second_task + " -o %T"), "PENDING\n");
  // The daemon shows the waiting point QUEUED with Slurm's reason, the running one RUNNING, and
  // the study counts them so.
  ASSERT_TRUE(WaitUntil([&] {
    const v1::Job job = GetJob(*stub, second);
    return job.state() == v1::QUEUED && job.slurm_reason() == "JobArrayTaskLimit";
  })) << GetJob(*stub, second).ShortDebugString();
  const v1::Job waiting = GetJob(*stub, second);
  EXPECT_EQ(waiting.slurm_state(), "PENDING");
  EXPECT_NE(waiting.reason().find("JobArrayTaskLimit"), std::string::npos) << waiting.reason();
  EXPECT_EQ(waiting.started_time(), 0.0);
  ASSERT_TRUE(WaitUntil([&] { return GetJob(*stub, first).state() == v1::RUNNING; }));
  EXPECT_EQ(GetJob(*stub, first).slurm_state(), "RUNNING");
  v1::GetStudyRequest get_study;
  get_study.set_study_id(study.study_id());
  v1::Study counts;
  ASSERT_TRUE(stub->GetStudy(Context().get(), get_study, &counts).ok());
  EXPECT_EQ(counts.queued(), 1);
  EXPECT_EQ(counts.running(), 1);
  for (const std::string& id : {second, first}) {
    v1::CancelRequest cancel;
    cancel.set_job_id(id);
    v1::Job cancelled;
    ASSERT_TRUE(stub->Cancel(Context().get(), cancel, &cancelled).ok());
  }
  const v1::Job one = WaitFinished(*stub, first);
  const v1::Job two = WaitFinished(*stub, second);
  EXPECT_EQ(one.state(), v1::CANCELLED) << one.reason() << "\n" << daemon().Log();
  EXPECT_GT(one.step(), 0);
  EXPECT_TRUE(fs::exists(one.results_dir() + "/checkpoint.h5"));
  EXPECT_EQ(two.state(), v1::CANCELLED) << two.reason() << "\n" << daemon().Log();
  EXPECT_EQ(two.step(), 0);
  EXPECT_EQ(Shell("squeue -h -j " + second_task + " -t PD,R -o %T 2>/dev/null"), "");
  // A retry with a short end: the point goes to Slurm again, as an array of its own.
  v1::RetryRequest retry;
  retry.add_job_ids(second);
  retry.add_overrides("time.end=0.5");
  v1::RetryResponse retried;
  ASSERT_TRUE(stub->Retry(Context().get(), retry, &retried).ok());
  const v1::Job again = WaitFinished(*stub, second);
  EXPECT_EQ(again.state(), v1::COMPLETED) << again.reason() << "\n" << daemon().Log();
  EXPECT_EQ(again.attempt(), 2);
  EXPECT_EQ(again.step(), 50);
  EXPECT_NE(ArrayOf(again.slurm_job_id()), ArrayOf(second_task));
  EXPECT_FALSE(ArrayOf(again.slurm_job_id()).empty());
}

}  // namespace
}  // namespace dlmfd::testing
