// SlurmRun: one attempt of a job as a Slurm batch job (the `slurm` executor, executor.h).
//
// Start writes the batch script (slurm_commands.h) into the job directory, which lives on the
// filesystem the nodes share (slurm_shared_dir), and submits it with sbatch --parsable:
// --job-name dlmfd-ID, --cpus-per-task the solver's threads (solver_threads, else 1), --mem the
// scene's memory estimate (scene_admission.h, scene/scene_footprint.h) plus kProcessHeadroomMb,
// --output the job's solver.log, --time and --signal=B:USR1@N when slurm_time_limit_minutes is
// set, partition, account, qos and the extra options. The Slurm id is written to DIR/slurm.id
// (Job.slurm_job_id in the API).
// ReadEvents follows DIR/events.bin (EventFileTail) twice a second and asks the shared SlurmQueue
// for the job's state every slurm_poll_seconds: squeue --json while Slurm lists the job, else
// the jobcomp file. The run has ended when the batch script has written the solver's exit status
// (DIR/solver.exit: the scheduler maps it as for a local run) or when Slurm says the job ended
// without it (killed by its time limit, node failure, out of memory, cancelled while pending):
// Outcome then gives the Slurm state's meaning (slurm_states.h). While squeue does not answer
// (slurmctld restarting) the run carries on with the last state it knew.
// Signal: SIGTERM is scancel (the solver checkpoints and exits 130), SIGKILL scancel --signal=KILL.
// Adoption: DIR/slurm.live marks a submitted job whose end the daemon has not seen; a daemon that
// starts after a crash finds it (the job is RUNNING in the store, requeued at start) and follows
// that Slurm job instead of submitting another: no duplicate run, and a job that ended meanwhile
// is recorded from its exit file or Slurm's state, with its results.
// Not supported yet: studies as job arrays, requeue on TIMEOUT/NODE_FAIL/PREEMPTED; a daemon's
// graceful shutdown cancels its Slurm jobs (each checkpoints) as the local executor stops its
// solvers, and the next start resubmits them with --resume.
#pragma once

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "executor.h"
#include "slurm_commands.h"

namespace dlmfd::server {

// The memory a dlmfd-solve process needs beyond the scene's estimate, given to --mem on top of it:
// the process itself measured 21 MiB at most (max RSS, /usr/bin/time -v, a 16x16 cavity, one
// thread); 256 MiB is a margin over that for HDF5 and FFTW buffers, not a measurement.
inline constexpr int64_t kProcessHeadroomMb = 256;

// squeue --json, run at most once per poll interval for all the runs of the daemon.
class SlurmQueue {
 public:
  explicit SlurmQueue(const SlurmSettings& settings)
      : settings_(settings) {}
  // The job's status from the latest squeue, else from the jobcomp file; nothing when neither
  // knows it. answered is false when squeue has not answered since the last poll.
  std::optional<SlurmJobStatus> Status(const std::string& id, bool* answered);

 private:
  const SlurmSettings settings_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point polled_{};
  std::string json_;
  bool answered_ = false;
};

class SlurmRun : public JobRun {
 public:
  SlurmRun(const Config& config, std::shared_ptr<SlurmQueue> queue)
      : config_(config),
        queue_(std::move(queue)) {}
  bool Adopt(const std::string& job_dir) override;
  void Start(const LaunchSpec& spec) override;
  void ReadEvents(const std::function<void(const v1::SolverEvent&)>& on_event) override;
  SolverExit Wait() override { return exit_; }
  void Signal(int signal_number) override;
  std::string Describe() const override { return "Slurm job " + slurm_id_; }
  std::optional<std::pair<JobState, std::string>> Outcome() const override { return outcome_; }

 private:
  void FollowUntilEnd(const std::function<void(const v1::SolverEvent&)>& on_event);
  // Reads DIR/solver.exit into exit_; false when it is not there yet.
  bool ReadExitFile();

  const Config& config_;
  std::shared_ptr<SlurmQueue> queue_;
  std::string job_dir_;
  std::string slurm_id_;
  std::mutex mutex_;
  std::condition_variable signalled_;
  bool woken_ = false;
  SolverExit exit_;
  std::optional<std::pair<JobState, std::string>> outcome_;
};

}  // namespace dlmfd::server
