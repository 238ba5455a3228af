// SlurmArray: the queued jobs of one study handed to Slurm together as one job array (the slurm
// executor, slurm_executor.h; docs/cluster.md).
//
// The scheduler takes a study's queued jobs at once and gives each a SlurmRun of the same
// SlurmArray with its index. Each run prepares its own job directory and batch script (slurm.sh,
// as for a single job) and Joins with its BatchJob; a run that will not start Withdraws; a run
// signalled before the submission (cancelled, the daemon shutting down) is left out. When every
// member has joined or withdrawn, the last to arrive writes the array's script (ArrayScript:
// task I runs the batch script of member I's directory) into a directory of its own,
// ROOT/slurm-arrays/NAME-XXXXXX beside the job directories, with task-I.log linked to member I's
// solver.log (Slurm's own lines of the task land there), and submits it once:
//   sbatch --array=INDICES%THROTTLE --job-name=NAME --output=DIR/task-%a.log ...
// with the settings of a single job, --mem and --time the largest member's. THROTTLE is the study's
// max_running less its jobs already in Slurm (Slurm's JobArrayTaskLimit keeps at most that many
// tasks running). While sbatch fails because slurmctld cannot be reached (TransientSlurmError) it
// is tried again every few seconds, each time without the members signalled since. Each member
// then follows its task, ARRAYID_INDEX: its own state, events, cancel (scancel ARRAYID_INDEX) and
// retry.
#pragma once

#include <condition_variable>
#include <map>
#include <mutex>
#include <set>
#include <string>

#include "config.h"
#include "slurm_commands.h"

namespace dlmfd::server {

class SlurmArray {
 public:
  SlurmArray(const Config& config, std::string name, int members, int throttle)
      : config_(config),
        name_(std::move(name)),
        throttle_(throttle),
        waiting_for_(members) {}

  // Blocks until the array has been submitted (or given up); returns the member's Slurm id
  // (ARRAYID_INDEX), or empty when it was left out (signalled first). Throws std::runtime_error
  // when sbatch failed for another reason than an unreachable controller.
  std::string Join(int index, const BatchJob& job);
  // A member will not start.
  void Withdraw();
  // The member was signalled: an array not submitted yet leaves it out.
  void Signal(int index);

 private:
  // The last arrival submits (the lock is released while sbatch runs).
  void Arrive(std::unique_lock<std::mutex>& lock);
  // Writes the array's directory (its path to dir) and script for the given members; returns
  // sbatch's command line.
  std::vector<std::string> Prepare(const std::vector<int>& indices, std::string* dir);

  const Config& config_;
  const std::string name_;
  const int throttle_;
  std::mutex mutex_;
  std::condition_variable changed_;
  int waiting_for_;
  std::map<int, BatchJob> joined_;
  std::set<int> signalled_;
  bool done_ = false;
  std::string array_id_;
  std::set<int> submitted_;
  std::string error_;
};

}  // namespace dlmfd::server
