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
};

constexpr JobState kLive = JobState::kRunning;

// Every state of slurm 22.05's job_state_string (base states and the flag states squeue shows).
constexpr std::array<Row, 22> kRows{{
    {"PENDING", false, kLive, "waiting for resources or priority", false},
    {"RUNNING", false, kLive, "running", false},
    {"SUSPENDED", false, kLive, "suspended by the administrator or a preemption", false},
    {"COMPLETING", false, kLive, "running its epilogue", false},
    {"CONFIGURING", false, kLive, "waiting for its nodes to boot", false},
    {"REQUEUED", false, kLive, "requeued, pending again", false},
    {"REQUEUE_HOLD", false, kLive, "requeued and held (scontrol release it)", false},
    {"REQUEUE_FED", false, kLive, "requeued by the federation", false},
    {"RESV_DEL_HOLD", false, kLive, "held: its reservation was deleted", false},
    {"RESIZING", false, kLive, "being resized", false},
    {"SIGNALING", false, kLive, "being signalled", false},
    {"STAGE_OUT", false, kLive, "staging out", false},
    {"STOPPED", false, kLive, "stopped (SIGSTOP), keeps its nodes", false},
    {"COMPLETED", true, JobState::kCompleted, "completed", false},
    {"CANCELLED", true, JobState::kCancelled, "cancelled in Slurm (scancel)", false},
    {"FAILED", true, JobState::kFailed, "failed: the batch script exited non-zero", false},
    {"TIMEOUT", true, JobState::kFailed,
     "reached its time limit (slurm_time_limit_minutes, --time); retry resumes from the checkpoint",
     true},
    {"NODE_FAIL", true, JobState::kFailed, "its node failed; retry resumes from the checkpoint",
     true},
    {"PREEMPTED", true, JobState::kFailed,
     "preempted by a job of higher priority; retry resumes from the checkpoint", true},
    {"BOOT_FAIL", true, JobState::kFailed, "its node failed to boot; retry runs it again", true},
    {"OUT_OF_MEMORY", true, JobState::kFailed,
     "ran out of its memory (--mem from the scene's footprint estimate)", false},
    {"DEADLINE", true, JobState::kFailed, "not started or finished before its --deadline", false},
}};

}  // namespace

SlurmStateMeaning MapSlurmState(const std::string& slurm_state, const std::string& state_reason) {
  std::string base = slurm_state.substr(0, slurm_state.find_first_of(" +"));
  const std::string why =
      state_reason.empty() || state_reason == "None" ? "" : " (" + state_reason + ")";
  SlurmStateMeaning out;
  for (const Row& row : kRows) {
    if (base == row.slurm) {
      out.finished = row.finished;
      out.state = row.state;
      out.retryable = row.retryable;
      out.reason = "Slurm: " + base + ": " + row.meaning + why;
      return out;
    }
  }
  out.reason = "Slurm: " + (base.empty() ? std::string("no state") : base) +
               ": a state the daemon does not know, taken as live" + why;
  return out;
}

}  // namespace dlmfd::server
