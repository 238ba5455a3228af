// SolverProcess: one run of dlmfd-solve as a child process, with its event pipe.
//
// The child is started with fork/exec as
//   SOLVER DIR/scene.in.toml --out DIR/results --set k=v ... --events 3 [--resume]
// with the write end of a pipe on fd 3, stdout and stderr appended to DIR/solver.log, the job
// directory's flock on fd 4 (so the lock lives as long as any run of the job, even one orphaned by
// a killed daemon), PR_SET_PDEATHSIG = SIGKILL (a daemon that dies takes its solvers with it) and
// every other descriptor closed. The child does only async-signal-safe work between fork and exec.
// The thread that calls Start must stay alive until Wait returns: PR_SET_PDEATHSIG follows the
// thread that forked. Events are read with the solver's own reader (dlmfd/solver/event_file.h).
// Not supported: running the solver under a batch system (Slurm); that would be another executor.
#pragma once

#include <sys/types.h>

#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "dlmfd/v1/events.pb.h"

namespace dlmfd::server {

struct LaunchSpec {
  std::string solver;
  std::string scene_path;
  std::string results_dir;
  std::string log_path;
  std::vector<std::string> overrides;
  bool resume = false;
  int lock_fd = -1;  // the held flock of the job directory, passed to the child as fd 4
  std::vector<std::string> environment;  // "NAME=value" set in the child over the daemon's
  // The wall-time limit of this run in seconds (job_time_limit.h); 0: none. The scheduler enforces
  // it for the local executor; the slurm executor hands it to Slurm (--time).
  int64_t time_limit_seconds = 0;
};

struct SolverExit {
  bool signalled = false;
  int code = 0;  // exit status, or the signal number when signalled
  // What the run used, when the executor measured it (wait4's rusage of the child): CPU seconds
  // (user + system) and the peak resident set in bytes; negative: not measured.
  double cpu_seconds = -1;
  int64_t peak_memory_bytes = -1;
};

class SolverProcess {
 public:
  SolverProcess() = default;
  ~SolverProcess();
  SolverProcess(const SolverProcess&) = delete;
  SolverProcess& operator=(const SolverProcess&) = delete;

  // Forks and execs; throws std::runtime_error when the process cannot be created.
  void Start(const LaunchSpec& spec);
  // Reads events until the child closes its end; calls on_event for each.
  void ReadEvents(const std::function<void(const v1::SolverEvent&)>& on_event);
  // Waits for the child to exit and reaps it (wait4: its CPU time and peak memory too).
  SolverExit Wait();
  // Sends a signal if the child has not been reaped yet (never to a recycled pid).
  void Signal(int signal_number);
  pid_t pid() const { return pid_; }

 private:
  std::mutex mutex_;  // guards pid_ against reaping while Signal runs
  pid_t pid_ = -1;
  int events_fd_ = -1;
};

// Takes an exclusive flock on path (a directory), waiting while another process holds it. Returns
// the descriptor, or -1 when should_stop() became true first. Throws when the path cannot be
// opened.
int LockDirectory(const std::string& path, const std::function<bool()>& should_stop);

}  // namespace dlmfd::server
