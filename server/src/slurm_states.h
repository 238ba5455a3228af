// The states of a Slurm job (squeue's job_state, the jobcomp file's JobState; slurm 22.05,
// src/common/slurm_protocol_defs.c job_state_string) mapped onto the daemon's.
//
// While a job is in Slurm's hands it is RUNNING in the daemon's store (it left our queue when it
// was submitted); `waiting` marks the states in which Slurm holds it before it runs (PENDING,
// REQUEUED, CONFIGURING, ...): the API shows it QUEUED then (job_store.h ShownState), with the
// reason saying what Slurm is doing with it ("Slurm: PENDING: waiting in Slurm's queue
// (JobArrayTaskLimit: the study's max_running (the array's throttle) holds it back)"). A job that
// has ended maps onto COMPLETED, FAILED or CANCELLED with a reason naming the Slurm state and what
// a user does about it. `retryable` marks the ends that a requeue from the checkpoint can cure
// (TIMEOUT, NODE_FAIL, PREEMPTED, BOOT_FAIL). A state this table does not know is kept live with a
// reason naming it, so that a newer Slurm's state is visible rather than guessed.
#pragma once

#include <string>

#include "job_store.h"

namespace dlmfd::server {

struct SlurmStateMeaning {
  bool finished = false;                // the Slurm job has ended
  JobState state = JobState::kRunning;  // ours
  std::string reason;
  bool retryable = false;
  bool waiting = false;  // Slurm holds it before it runs (or runs it again)
};

// slurm_state: "PENDING", "RUNNING", ... (a trailing "+" or a flag after a space is ignored, as
// the jobcomp file and sacct print "CANCELLED by 0"); state_reason: squeue's reason, may be empty.
SlurmStateMeaning MapSlurmState(const std::string& slurm_state, const std::string& state_reason);

}  // namespace dlmfd::server
