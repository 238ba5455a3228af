// Scheduler: runs queued jobs, highest priority first, then oldest, at most max_concurrent at once,
// and at most a study's max_running of that study's jobs (JobStore::NextQueued skips a study at its
// limit, so other jobs start meanwhile; a job's end wakes the loop). A job with dependencies waits
// until they have all COMPLETED (afterok) and is cancelled, "dependency ID failed (FAILED)", when
// one ends otherwise or is deleted; the daemon holds it under either executor (a job is handed to
// Slurm only when it may run; docs/cluster.md says why).
//
// A scheduler thread takes the next QUEUED job from the store, marks it RUNNING (one transaction,
// attempts + 1) and gives it a runner thread. The runner writes DIR/scene.in.toml, resumes from
// results/checkpoint.h5 when one exists and the job is not marked for a fresh start (a retry with
// another scene; else clears results/), takes the job directory's flock (so
// a job never runs twice at once), runs dlmfd-solve (SolverProcess; OMP_NUM_THREADS = cores /
// max_concurrent unless configured, since oversubscribed OpenMP teams crawl), turns its events into
// Watch events for the EventHub, records progress in the store at most once a second, and maps the
// exit:
//   0 COMPLETED; 1 FAILED (the reason from the finished event or results/summary.json); 2 FAILED
//   (invalid scene); 130 CANCELLED; killed by signal N: FAILED "solver killed by signal N".
// Limits: a solver start that runs longer than the job's time limit (its time_limit_seconds, else
// max_wall_seconds; job_time_limit.h) gets SIGTERM (it checkpoints) and the job ends FAILED naming
// the limit; an executor that limits time itself (Slurm's --time) is left to do so. A job's
// directory is counted (disk_bytes) when it ends. Cancel: a QUEUED job is cancelled in the store at
// once; a RUNNING one gets SIGTERM (the solver checkpoints and exits 130 at a step boundary). Stop
// (daemon shutdown) detaches each run (JobRun::Detach: a local solver gets SIGTERM, a Slurm job
// runs on and the next start adopts it) and leaves the jobs RUNNING in the store, so that the next
// start resumes or adopts them; a solver still alive after the grace period gets SIGKILL. The run
// itself is the configured executor's (executor.h: local child processes or Slurm jobs); with the
// slurm executor at most slurm_max_submitted jobs are handed to Slurm at once, the job directories
// live in slurm_shared_dir when it is set, the queued jobs of a study go to Slurm together (one job
// array with the study's max_running as its throttle, slurm_array.h), the Slurm id is stored
// (JobStore::SetSlurmSubmitted), so are Slurm's state and reason while it holds the job
// (RecordState: a job waiting in Slurm shows QUEUED), a Slurm restart of the job is a new attempt
// (RecordRestart) and a retryable end (TIMEOUT, NODE_FAIL, PREEMPTED, BOOT_FAIL) queues the job
// again to resume from its checkpoint while slurm_max_attempts allows (Requeue).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "clock.h"
#include "config.h"
#include "dlmfd/v1/events.pb.h"
#include "event_hub.h"
#include "job_store.h"
#include "solver_process.h"

namespace dlmfd::server {

class Executor;
class JobRun;
struct EventPosition;
struct ExecutorState;
struct RunOutcome;

class Scheduler {
 public:
  // clock: the times it records and the job time limits it applies (clock.h).
  Scheduler(const Config& config, Executor& executor, JobStore& store, EventHub& hub,
            Clock& clock = SystemClock());
  ~Scheduler();
  Scheduler(const Scheduler&) = delete;
  Scheduler& operator=(const Scheduler&) = delete;

  void Start();
  // Stops starting jobs, terminates the running solvers (jobs stay RUNNING for the next start) and
  // joins every thread.
  void Stop(std::chrono::seconds grace = std::chrono::seconds(30));
  // Something was queued.
  void Wake();
  // Cancels a job of the store; returns its record afterwards. Throws ServiceError NOT_FOUND, or
  // FAILED_PRECONDITION when it has already finished.
  JobRecord Cancel(const std::string& job_id);
  // As Cancel, but a job that has already finished is left as it is: returns its record, or
  // nothing when it had finished. Throws ServiceError NOT_FOUND.
  std::optional<JobRecord> CancelUnlessFinished(const std::string& job_id);

  // Blocks until no solver of the job runs (a cancelled one stops at a step boundary) and its end
  // is recorded.
  void WaitUntilStopped(const std::string& job_id);

  std::string JobDir(const std::string& job_id) const;
  const Executor& executor() const { return executor_; }
  std::string ResultsDir(const std::string& job_id) const;

 private:
  struct Running {
    std::thread thread;
    std::shared_ptr<JobRun> process;
    bool cancel = false;
    bool done = false;
  };
  void Loop();
  // Cancels the queued jobs whose dependencies can no longer all complete (JobStore::Blocked),
  // and theirs in turn (mutex_ held).
  void CancelBlocked();
  // Gives the job a runner thread with the run (mutex_ held).
  void Launch(const JobRecord& job, std::shared_ptr<JobRun> run);
  // Starts the queued jobs of first's study, at most room, as one submission (a Slurm job array)
  // with the study's throttle (mutex_ held); false when none could start.
  bool StartStudyBatch(const JobRecord& first, int room);
  // One attempt of a job, in its runner thread, stage by stage (scheduler.cc's Attempt holds what
  // they share): RunAttempt locks the job directory, PrepareLaunch decides adopt / resume /
  // fresh and writes the inputs, StartOrAdopt hands the run to the executor, OnSolverEvent
  // publishes and stores each event while the run is followed, EndOf maps its end to an outcome,
  // RecordEnd queues it again or finishes it.
  struct Attempt;
  void RunJob(JobRecord job);
  std::optional<RunOutcome> RunAttempt(Attempt& attempt);
  void PrepareLaunch(Attempt& attempt);
  void StartOrAdopt(Attempt& attempt);
  void OnSolverEvent(Attempt& attempt, const v1::SolverEvent& in, const EventPosition& position);
  void StoreSeenProgress(Attempt& attempt);
  std::optional<RunOutcome> EndOf(const Attempt& attempt, const SolverExit& exit,
                                  bool over_wall_time);
  void RecordEnd(const JobRecord& job, const RunOutcome& outcome);
  bool CancelRequested(const std::string& job_id);
  // The executor's word on the run changed (Slurm's state and reason): stored, and published
  // when it changes what the API shows (a waiting job is QUEUED).
  void RecordState(const JobRecord& job, const ExecutorState& state);
  // A solver run ended: its exit status, CPU time and peak memory go to the job's accounting.
  void RecordUsage(const std::string& job_id, const SolverExit& exit,
                   const std::optional<v1::Finished>& finished);
  // The executor ran the job again by itself (Slurm requeued it): a new attempt, still RUNNING.
  void RecordRestart(const JobRecord& job, int restarts, const std::string& reason);
  // A retryable end (Slurm TIMEOUT, NODE_FAIL, PREEMPTED, ...): the job goes back to the queue to
  // resume from its checkpoint when slurm_max_attempts allows and no cancel was asked; false
  // otherwise (the end is recorded as it is).
  bool Requeue(const JobRecord& job, const RunOutcome& outcome);
  void FinishJob(const std::string& job_id, JobState state, const std::string& reason);
  bool Stopping() const { return stopping_.load(); }

  const Config& config_;
  Executor& executor_;
  JobStore& store_;
  EventHub& hub_;
  Clock& clock_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::map<std::string, Running> running_;
  bool dirty_ = true;
  std::atomic<bool> stopping_{false};
  std::thread loop_;
};

}  // namespace dlmfd::server
