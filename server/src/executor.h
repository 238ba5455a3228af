// JobRun: one attempt of a job, as the scheduler drives it, whatever runs the solver.
//
// The scheduler's runner thread calls Start, then ReadEvents (returns when the run has ended and
// every event it wrote has been delivered), then Wait; Signal may come from any thread at any
// time (SIGTERM: cancel or daemon shutdown, the solver checkpoints and exits 130; SIGKILL: now).
// Executors, chosen by the daemon's `executor` setting (config.h, docs/api.md):
//   local  SolverProcess (solver_process.h): dlmfd-solve as a child process, events on a pipe.
//   slurm  SlurmRun (slurm_executor.h): a batch script submitted with sbatch, events through a
//          file in the shared job directory, states from squeue and the jobcomp file.
// Outcome lets an executor name an end that the solver's exit status cannot tell (a Slurm
// TIMEOUT, NODE_FAIL or OUT_OF_MEMORY); the scheduler uses it instead of the exit-status mapping.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "config.h"
#include "dlmfd/v1/events.pb.h"
#include "job_store.h"
#include "solver_process.h"

namespace dlmfd::server {

class JobRun {
 public:
  virtual ~JobRun() = default;
  // Takes over a run of this job directory that outlived the daemon (a Slurm job submitted
  // before a daemon crash, live or ended since); true when there is one: the scheduler then skips
  // Start. The local executor's children die with the daemon: false.
  virtual bool Adopt(const std::string& job_dir) {
    (void)job_dir;
    return false;
  }
  // Throws std::runtime_error when the run cannot be started (fork, sbatch).
  virtual void Start(const LaunchSpec& spec) = 0;
  virtual void ReadEvents(const std::function<void(const v1::SolverEvent&)>& on_event) = 0;
  virtual SolverExit Wait() = 0;
  virtual void Signal(int signal_number) = 0;
  // A line for the daemon's log once started: "solver pid 123", "Slurm job 45".
  virtual std::string Describe() const = 0;
  // The end as the executor knows it, when the exit status does not tell it; nothing otherwise.
  virtual std::optional<std::pair<JobState, std::string>> Outcome() const { return std::nullopt; }
};

// The run of the configured executor.
std::shared_ptr<JobRun> MakeJobRun(const Config& config);

}  // namespace dlmfd::server
