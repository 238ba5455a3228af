// The executors: what runs the solver for the scheduler. Two levels, one interface each:
//   Executor  the daemon's one executor (MakeExecutor, from the `executor` setting; config.h,
//             docs/api.md): its capacity (runs in its hands at once), its limits (the daemon's
//             time limit of one run, and whether it enforces it itself), where a job's directory
//             lives, and the runs it launches, one job at a time or a study's jobs together.
//   JobRun    one attempt of a job: launch (Start), adopt (a run that outlived the daemon), poll
//             (ReadEvents: returns when the run has ended and every event it wrote has been
//             delivered, then Wait), cancel (Signal; Detach at the daemon's shutdown).
// Implementations: local (local_executor.h: dlmfd-solve as a child process, events on a pipe) and
// slurm (slurm_executor.h: a batch script submitted with sbatch, events through a file in the
// shared job directory, states from squeue and the jobcomp file). No other code names them.
//
// The scheduler's runner thread calls Start, then ReadEvents, then Wait; Signal may come from any
// thread at any time (SIGTERM: cancel or daemon shutdown, the solver checkpoints and exits 130;
// SIGKILL: now). OnStateChange reports the executor's word on the run (a Slurm job PENDING for a
// reason, then RUNNING): the scheduler stores it, and the API shows a run that has not started
// QUEUED. Outcome lets an executor name an end that the solver's exit status cannot tell (a Slurm
// TIMEOUT, NODE_FAIL or OUT_OF_MEMORY); the scheduler uses it instead of the exit-status mapping,
// and queues the job again when it is retryable and the executor's attempts allow.
// A study's queued jobs may be handed over together (SubmitsStudiesTogether: a Slurm job array):
// the scheduler starts a runner for each with a run of NewStudyRuns; a runner that will not call
// Start calls Abandon, so that the others do not wait for it.
#pragma once

#include <signal.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "config.h"
#include "dlmfd/v1/events.pb.h"
#include "job_store.h"
#include "solver_process.h"

namespace dlmfd::server {

// What the executor says of a run in its hands (a Slurm job's squeue state and reason).
struct ExecutorState {
  std::string state;   // "PENDING", "RUNNING", ...
  std::string reason;  // "JobArrayTaskLimit", ...; empty for none
  bool waiting = false;
};

// How a run ended when the exit status does not tell it.
struct RunOutcome {
  JobState state = JobState::kFailed;
  std::string reason;
  bool retryable = false;  // an end that a new attempt from the checkpoint may cure
};

// Where a solver event was read: the run's event file ("slurm:ID") and the offset just past the
// event in it; an empty source for a pipe, which cannot be read again.
struct EventPosition {
  std::string source;
  int64_t offset = 0;
};

class JobRun {
 public:
  virtual ~JobRun() = default;
  using EventHandler = std::function<void(const v1::SolverEvent&, const EventPosition&)>;
  // Where the daemon before stopped reading an event source, if it read any of it.
  using ReadFrom = std::function<std::optional<int64_t>(const std::string& source)>;
  // Takes over a run of the job that outlived the daemon (a Slurm job submitted before a daemon
  // crash or shutdown, live or ended since: job.slurm_live); true when there is one: the
  // scheduler then skips Start, and its events are read on from read_from's offset. The local
  // executor's children die with the daemon: false.
  virtual bool Adopt(const std::string& job_dir, const JobRecord& job, const ReadFrom& read_from) {
    (void)job_dir;
    (void)job;
    (void)read_from;
    return false;
  }
  // True when a started run waits before it runs (a Slurm job pends in Slurm's queue): the job is
  // shown QUEUED until the executor says it runs (OnStateChange).
  virtual bool WaitsBeforeRunning() const { return false; }
  // Throws std::runtime_error when the run cannot be started (fork, sbatch).
  virtual void Start(const LaunchSpec& spec) = 0;
  // Start will not be called (the job was cancelled or failed before it).
  virtual void Abandon() {}
  virtual void ReadEvents(const EventHandler& on_event) = 0;
  virtual SolverExit Wait() = 0;
  virtual void Signal(int signal_number) = 0;
  // The daemon shuts down: a run that can outlive it (a Slurm job) is left running and ReadEvents
  // returns (Wait then gives SIGTERM); the local executor's solver gets SIGTERM and checkpoints.
  virtual void Detach() { Signal(SIGTERM); }
  // A line for the daemon's log once started: "solver pid 123", "Slurm job 45".
  virtual std::string Describe() const = 0;
  // The executor's id of the run once started or adopted (the Slurm job id); empty otherwise.
  virtual std::string ExecutorId() const { return {}; }
  // The end as the executor knows it, when the exit status does not tell it; nothing otherwise.
  virtual std::optional<RunOutcome> Outcome() const { return std::nullopt; }
  // Called on ReadEvents' thread when the executor ran the job again by itself (Slurm requeued
  // it): restarts is the executor's count of such runs, reason says why.
  using RestartHandler = std::function<void(int restarts, const std::string& reason)>;
  virtual void OnRestart(RestartHandler handler) { (void)handler; }
  // Called on ReadEvents' thread when the executor's word on the run changes (a Slurm job's state
  // or reason): waiting tells that the run has not started (Slurm holds it PENDING, ...).
  using StateHandler = std::function<void(const ExecutorState& state)>;
  virtual void OnStateChange(StateHandler handler) { (void)handler; }
};

// The daemon's time limit of one run of a job under an executor (job_time_limit.h).
struct DaemonTimeLimit {
  int64_t seconds = 0;   // 0: none
  std::string settings;  // the settings that set it, for messages ("max_wall_seconds")
};

class Executor {
 public:
  virtual ~Executor() = default;
  // The most runs in its hands at once (local: max_concurrent solvers; slurm: slurm_max_submitted
  // jobs, running or waiting in Slurm's queue).
  virtual int Capacity() const = 0;
  // The daemon's limit of one run; a job may ask for less (job_time_limit.h).
  virtual DaemonTimeLimit TimeLimit() const = 0;
  // True when the executor enforces a run's time limit itself (Slurm's --time, which counts the
  // time the job runs, not the time it waits); else the scheduler stops the run past it.
  virtual bool LimitsTimeItself() const { return false; }
  // The directory of a job: its results, solver log, inputs and watch log.
  virtual std::string JobDirectory(const std::string& job_id) const = 0;
  // A run for one job.
  virtual std::shared_ptr<JobRun> NewRun() = 0;
  // True when a study's queued jobs are handed over together (slurm: one job array).
  virtual bool SubmitsStudiesTogether() const { return false; }
  // The runs of `count` jobs of the study `study` (its id) handed over together, at most
  // `throttle` of them running at once (0: no limit); the scheduler gives the i-th to the i-th
  // job. By default, a run of its own for each.
  virtual std::vector<std::shared_ptr<JobRun>> NewStudyRuns(const std::string& study, int count,
                                                            int throttle);
};

// The configured executor (config.executor); throws ConfigError for an unknown name.
std::unique_ptr<Executor> MakeExecutor(const Config& config);
// True when `name` is an executor's (the `executor` setting's allowed values).
bool IsExecutorName(const std::string& name);
// The allowed values for messages: "local or slurm".
std::string ExecutorNamesText();

}  // namespace dlmfd::server
