// The slurm executor (executor.h; docs/cluster.md): SlurmExecutor hands at most
// slurm_max_submitted jobs to Slurm at once, a study's queued jobs together as one job array
// (slurm_array.h); the daemon's time limit is the smaller of max_wall_seconds and
// slurm_time_limit_minutes, and Slurm enforces it (--time); job directories live in
// slurm_shared_dir when it is set (else DATA/jobs). One SlurmQueue answers every run's polls.
//
// SlurmRun: one attempt of a job as a Slurm batch job or array task.
//
// Start writes the batch script (slurm_commands.h) into the job directory, which lives on the
// filesystem the nodes share (slurm_shared_dir), and submits it with sbatch --parsable:
// --job-name dlmfd-ID, --cpus-per-task the solver's threads (solver_threads, else 1), --mem the
// scene's memory estimate (scene_admission.h, scene/scene_footprint.h) plus kProcessHeadroomMb,
// --output the job's solver.log, --time and --signal=B:USR1@N from the run's time limit
// (LaunchSpec::time_limit_seconds: the job's, else the daemon's; job_time_limit.h), partition,
// account, qos and the extra options. A run of a study's batch (NewStudyRuns)
// joins its SlurmArray instead (slurm_array.h: one sbatch --array for the study's queued jobs).
// While sbatch cannot reach slurmctld (TransientSlurmError) it is run again every
// kSbatchRetryInterval until it answers or the run is signalled. The Slurm id ("123", an array
// task "120_4") is written to DIR/slurm.id; the scheduler stores it (JobStore::SetSlurmSubmitted).
// ReadEvents follows DIR/events.bin (EventFileTail) twice a second and asks the shared SlurmQueue
// for the job's state every slurm_poll_seconds: squeue --json while Slurm lists the job, else
// the jobcomp file; a change of Slurm's state or reason goes to OnStateChange's handler (PENDING
// and the other states before a run are `waiting`: the API shows the job QUEUED); the solver's
// first events show it running before squeue may: RUNNING then, and an older squeue answer that
// says PENDING is ignored. The end:
//   - DIR/solver.exit ("STATUS RESTARTS", written by the batch script) of the current Slurm
//     restart with status 0, 1 or 2, or after the daemon's own signal: the scheduler maps the
//     status as for a local run; each round reads it before events.bin, so every event the solver
//     wrote is delivered before its end;
//   - status 130 after Slurm's time-limit warning (DIR/slurm.warned): the solver checkpointed
//     before the limit: a retryable end (the scheduler queues the job again up to
//     slurm_max_attempts);
//   - any other status (130 or a signal that the daemon did not send) waits for Slurm's word: a
//     restart count above the known one is Slurm running the job again (scontrol requeue, a node
//     failure with --requeue): OnRestart's handler records a new attempt and the run goes on
//     following the same Slurm job; an ended state gives the end (TIMEOUT, NODE_FAIL, PREEMPTED:
//     retryable; CANCELLED: cancelled in Slurm);
//   - Slurm says the job ended without an exit file (killed by its time limit, node failure, out
//     of memory, cancelled while pending): Outcome gives the Slurm state's meaning
//     (slurm_states.h).
// While squeue does not answer (slurmctld restarting) the run carries on with the last state it
// knew. Signal: SIGTERM is scancel (the solver checkpoints and exits 130), SIGKILL scancel
// --signal=KILL; a run not submitted yet is not submitted. Detach (the daemon shuts down) stops
// following and leaves the Slurm job running (signals after it are not sent on). Adopt: a job whose
// Slurm job the store marks live (slurm_live: submitted, its end not recorded, after a crash or a
// shutdown) is followed again instead of submitted: no duplicate run, and a job that ended
// meanwhile is recorded from its exit file or Slurm's state, with its results; its events are
// replayed from the start of events.bin.
#pragma once

#include <sys/types.h>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "executor.h"
#include "slurm_commands.h"

namespace dlmfd::server {

class SlurmArray;

// The memory a dlmfd-solve process needs beyond the scene's estimate, given to --mem on top of it:
// the process itself measured 21 MiB at most (max RSS, /usr/bin/time -v, a 16x16 cavity, one
// thread); 256 MiB is a margin over that for HDF5 and FFTW buffers, not a measurement.
inline constexpr int64_t kProcessHeadroomMb = 256;

// squeue --json, run at most once per poll interval for all the runs of the daemon and parsed
// once; the jobcomp file, parsed again only when it has changed.
class SlurmQueue {
 public:
  explicit SlurmQueue(const SlurmSettings& settings)
      : settings_(settings) {}
  using Clock = std::chrono::steady_clock;
  // The job's status from the latest squeue that answered, else from the jobcomp file; nothing
  // when neither knows it. answered_at: when that squeue was run (its answer is at least as new),
  // the epoch while none has answered. Runs squeue first when the last one is older than the poll
  // interval and no other run is running it (squeue takes seconds to give up on a slurmctld that
  // does not answer; the others go on with the last answer meanwhile).
  std::optional<SlurmJobStatus> Status(const std::string& id, Clock::time_point* answered_at);

 private:
  std::optional<SlurmJobStatus> FromJobComp(const std::string& id);

  const SlurmSettings settings_;
  std::mutex mutex_;
  Clock::time_point polled_{};
  bool polling_ = false;
  std::map<std::string, SlurmJobStatus> squeue_;
  Clock::time_point answered_at_{};
  std::map<std::string, SlurmJobStatus> jobcomp_;
  off_t jobcomp_size_ = -1;
  std::chrono::system_clock::time_point jobcomp_changed_{};
};

class SlurmRun : public JobRun {
 public:
  // array and index: a member of a study's job array (slurm_array.h); else a job of its own.
  SlurmRun(const Config& config, std::shared_ptr<SlurmQueue> queue,
           std::shared_ptr<SlurmArray> array = nullptr, int index = -1)
      : config_(config),
        queue_(std::move(queue)),
        array_(std::move(array)),
        index_(index) {}
  bool Adopt(const std::string& job_dir, const JobRecord& job, const ReadFrom& read_from) override;
  bool WaitsBeforeRunning() const override { return true; }
  void Start(const LaunchSpec& spec) override;
  void Abandon() override;
  void ReadEvents(const EventHandler& on_event) override;
  SolverExit Wait() override { return exit_; }
  void Signal(int signal_number) override;
  void Detach() override;
  std::string Describe() const override;
  std::string ExecutorId() const override;
  std::optional<RunOutcome> Outcome() const override { return outcome_; }
  void OnRestart(RestartHandler handler) override { on_restart_ = std::move(handler); }
  void OnStateChange(StateHandler handler) override { on_state_ = std::move(handler); }

 private:
  struct ExitFile {
    int status = 0;
    int restarts = 0;
  };
  // A daemon killed between sbatch's answer and the store's commit of the id leaves a Slurm job
  // the store does not know: when one of this job's name and directory waits or runs (squeue),
  // it is followed as if just submitted; true then.
  bool FollowUnrecordedJob(const std::filesystem::path& dir);
  // Follows Slurm job `id` from now on (submitted, or found): records it, writes the id file of
  // `dir`, and passes on a signal that came before the id.
  void Follow(const std::filesystem::path& dir, const std::string& id);
  // sbatch for a job of its own; empty when the run was signalled while sbatch could not reach
  // slurmctld.
  std::string Submit(const BatchJob& job, const std::string& script);
  void FollowUntilEnd(const EventHandler& on_event);
  std::optional<ExitFile> ReadExitFile() const;
  // Gives OnStateChange's handler the state when it differs from the one reported last.
  void Report(const ExecutorState& state);
  void SetExit(const ExitFile& file);
  // Waits up to the tail interval or until signalled; true when Detach was called.
  bool Sleep();

  const Config& config_;
  std::shared_ptr<SlurmQueue> queue_;
  std::shared_ptr<SlurmArray> array_;
  const int index_;
  std::string job_dir_;
  RestartHandler on_restart_;
  StateHandler on_state_;
  int restarts_ = 0;                                // Slurm's restart count of the attempt followed
  ExecutorState reported_;                          // Slurm's word last reported (as stored)
  SlurmQueue::Clock::time_point followed_since_{};  // submitted or adopted
  bool submitted_ = false;
  int64_t read_from_ = 0;  // the offset of events.bin to read on from (an adopted run)
  SolverExit exit_;
  std::optional<RunOutcome> outcome_;
  mutable std::mutex mutex_;  // guards the members below (Signal and Detach come from others)
  std::condition_variable signalled_;
  std::string slurm_id_;
  bool woken_ = false;
  bool asked_ = false;  // the daemon signalled the Slurm job (cancel, wall time)
  bool detached_ = false;
  int pending_signal_ = 0;  // a signal that came before the Slurm id
};

class SlurmExecutor : public Executor {
 public:
  explicit SlurmExecutor(const Config& config)
      : config_(config),
        queue_(std::make_shared<SlurmQueue>(config.slurm)) {}
  int Capacity() const override { return config_.slurm.max_submitted; }
  DaemonTimeLimit TimeLimit() const override;
  bool LimitsTimeItself() const override { return true; }
  std::string JobDirectory(const std::string& job_id) const override;
  std::shared_ptr<JobRun> NewRun() override;
  bool SubmitsStudiesTogether() const override { return true; }
  std::vector<std::shared_ptr<JobRun>> NewStudyRuns(const std::string& study, int count,
                                                    int throttle) override;

 private:
  const Config& config_;
  const std::shared_ptr<SlurmQueue> queue_;
};

}  // namespace dlmfd::server
