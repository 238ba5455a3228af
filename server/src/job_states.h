// The states of a job and the transitions between them: one table each, which the store's
// updates are built from (job_store.cc: every UPDATE of a job's state takes its "state IN (...)"
// from JobStatesBefore and checks its target with CheckTransition) and which docs/api.md states.
//
//   QUEUED ---start---> RUNNING ---finish---> COMPLETED | FAILED | CANCELLED
//     |                  |  ^  \--end attempt (requeued to resume, TIMEOUT ...)--> QUEUED
//     |                  |  '--end attempt (Slurm restarted the job itself)
//     |                  '--daemon start: QUEUED to resume or adopt; CANCELLED if asked before
//     '--cancel queued (or a dependency that cannot complete)--> CANCELLED
//   COMPLETED | FAILED | CANCELLED ---retry---> QUEUED
// A job in the executor's hands that Slurm holds waiting is stored RUNNING and shown QUEUED
// (ShownState, job_store.h). The numbers are dlmfd.v1.JobState's (proto/).
#pragma once

#include <string>

namespace dlmfd::server {

// Values equal dlmfd.v1.JobState.
enum class JobState { kQueued = 1, kRunning = 2, kCompleted = 3, kFailed = 4, kCancelled = 5 };

struct JobStateRow {
  JobState state;
  const char* name;  // as the API and the CLI show it
  bool finished;     // no run will follow unless the job is retried
};

inline constexpr JobStateRow kJobStates[] = {
    {JobState::kQueued, "QUEUED", false},      {JobState::kRunning, "RUNNING", false},
    {JobState::kCompleted, "COMPLETED", true}, {JobState::kFailed, "FAILED", true},
    {JobState::kCancelled, "CANCELLED", true},
};

// A set of states, as bits.
using JobStates = unsigned;
constexpr JobStates Of(JobState state) { return 1u << static_cast<int>(state); }
inline constexpr JobStates kUnfinishedStates = Of(JobState::kQueued) | Of(JobState::kRunning);
inline constexpr JobStates kFinishedStates =
    Of(JobState::kCompleted) | Of(JobState::kFailed) | Of(JobState::kCancelled);

// What moves a job from one state to another.
enum class JobTransition { kStart, kCancelQueued, kFinish, kEndAttempt, kDaemonStart, kRetry };

struct JobTransitionRow {
  JobTransition transition;
  JobStates from, to;
  const char* when;
};

inline constexpr JobTransitionRow kJobTransitions[] = {
    {JobTransition::kStart, Of(JobState::kQueued), Of(JobState::kRunning),
     "the scheduler runs it, hands it to its executor or adopts its live run (MarkRunning)"},
    {JobTransition::kCancelQueued, Of(JobState::kQueued), Of(JobState::kCancelled),
     "cancelled while queued, or a dependency can no longer complete (CancelQueued)"},
    {JobTransition::kFinish, kUnfinishedStates, kFinishedStates,
     "its run's end is recorded (MarkFinished)"},
    {JobTransition::kEndAttempt, Of(JobState::kRunning), kUnfinishedStates,
     "an attempt ended, the job did not: queued again to resume from its checkpoint, or still "
     "running when Slurm restarted it (EndAttempt)"},
    {JobTransition::kDaemonStart, Of(JobState::kRunning),
     Of(JobState::kQueued) | Of(JobState::kCancelled),
     "the daemon starts: a run of its previous life is queued to resume or be adopted, or "
     "cancelled when a cancel was asked before (RequeueRunning)"},
    {JobTransition::kRetry, kFinishedStates, Of(JobState::kQueued),
     "a finished job is retried (Requeue)"},
};

bool IsFinished(JobState state);
const char* JobStateName(JobState state);
// True when some transition of the table moves a job from `from` to `to`.
bool TransitionAllowed(JobState from, JobState to);
// True when the transition may take a job in state `from`.
bool TransitionFrom(JobTransition transition, JobState from);
// The states a job may be in for the transition: "(1, 2)", for an SQL "state IN".
std::string JobStatesBefore(JobTransition transition);
// Throws std::logic_error when the transition cannot end in `to` (a defect of the caller).
void CheckTransition(JobTransition transition, JobState to);

}  // namespace dlmfd::server
