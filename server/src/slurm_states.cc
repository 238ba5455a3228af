#include "slurm_states.h"

#include <array>

namespace dlmfd::server {
namespace {

struct Row {
  const char* slurm;
  bool finished;
  JobState state;
  const char* meaning;
  bool retryable;
  bool waiting;
};

constexpr JobState kLive = JobState::kRunning;

// Every state of slurm 22.05's job_state_string (base states and the flag states squeue shows).
constexpr std::array<Row, 22> kRows{{
    {"PENDING", false, kLive, "waiting in Slurm's queue", false, true},
    {"RUNNING", false, kLive, "running", false, false},
    {"SUSPENDED", false, kLive, "suspended by the administrator or a preemption", false, false},
    {"COMPLETING", false, kLive, "running its epilogue", false, false},
    {"CONFIGURING", false, kLive, "waiting for its nodes to boot", false, true},
    {"REQUEUED", false, kLive, "requeued, pending again", false, true},
    {"REQUEUE_HOLD", false, kLive, "requeued and held (scontrol release it)", false, true},
    {"REQUEUE_FED", false, kLive, "requeued by the federation", false, true},
    {"RESV_DEL_HOLD", false, kLive, "held: its reservation was deleted", false, true},
    {"RESIZING", false, kLive, "being resized", false, false},
    {"SIGNALING", false, kLive, "being signalled", false, false},
    {"STAGE_OUT", false, kLive, "staging out", false, false},
    {"STOPPED", false, kLive, "stopped (SIGSTOP), keeps its nodes", false, false},
    {"COMPLETED", true, JobState::kCompleted, "completed", false, false},
    {"CANCELLED", true, JobState::kCancelled, "cancelled in Slurm (scancel)", false, false},
    {"FAILED", true, JobState::kFailed, "failed: the batch script exited non-zero", false, false},
    {"TIMEOUT", true, JobState::kFailed,
     "reached its time limit (--time: the job's time_limit_seconds, else the daemon's); retry "
     "resumes from the checkpoint",
     true, false},
    {"NODE_FAIL", true, JobState::kFailed, "its node failed; retry resumes from the checkpoint",
     true, false},
    {"PREEMPTED", true, JobState::kFailed,
     "preempted by a job of higher priority; retry resumes from the checkpoint", true, false},
    {"BOOT_FAIL", true, JobState::kFailed, "its node failed to boot; retry runs it again", true,
     false},
    {"OUT_OF_MEMORY", true, JobState::kFailed,
     "ran out of its memory (--mem from the scene's footprint estimate)", false, false},
    {"DEADLINE", true, JobState::kFailed, "not started or finished before its --deadline", false,
     false},
}};

// What the commonest reasons of a waiting job mean (squeue's state_reason; slurm 22.05's
// job_reason_string); another reason is shown as Slurm gives it.
struct Reason {
  const char* slurm;
  const char* meaning;
};
constexpr std::array<Reason, 10> kReasons{{
    {"Priority", "jobs of higher priority go first"},
    {"Resources", "waiting for free resources"},
    {"JobArrayTaskLimit", "the study's max_running (the array's throttle) holds it back"},
    {"JobHeldUser", "held by its user (scontrol release)"},
    {"JobHeldAdmin", "held by an administrator"},
    {"BeginTime", "waiting for its begin time"},
    {"Dependency", "waiting for a job it depends on"},
    {"ReqNodeNotAvail", "its nodes are not available"},
    {"PartitionTimeLimit", "its time limit is above the partition's"},
    {"QOSMaxJobsPerUserLimit", "the QOS's limit of jobs per user holds it back"},
}};

}  // namespace

SlurmStateMeaning MapSlurmState(const std::string& slurm_state, const std::string& state_reason) {
  std::string base = slurm_state.substr(0, slurm_state.find_first_of(" +"));
  std::string why;
  if (!state_reason.empty() && state_reason != "None") {
    why = " (" + state_reason;
    for (const Reason& reason : kReasons) {
      if (state_reason == reason.slurm) why += std::string(": ") + reason.meaning;
    }
    why += ")";
  }
  SlurmStateMeaning out;
  for (const Row& row : kRows) {
    if (base == row.slurm) {
      out.finished = row.finished;
      out.state = row.state;
      out.retryable = row.retryable;
      out.waiting = row.waiting;
      out.reason = "Slurm: " + base + ": " + row.meaning + why;
      return out;
    }
  }
  out.reason = "Slurm: " + (base.empty() ? std::string("no state") : base) +
               ": a state the daemon does not know, taken as live" + why;
  return out;
}

}  // namespace dlmfd::server
