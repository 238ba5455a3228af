// The local executor (executor.h): each run is dlmfd-solve as a child process of the daemon
// (SolverProcess, solver_process.h), its events on a pipe; at most max_concurrent at once; the
// daemon's time limit is max_wall_seconds, which the scheduler enforces (WallTimeLimit); job
// directories are DATA/jobs/ID. A child dies with the daemon: nothing to adopt.
#pragma once

#include <memory>
#include <string>

#include "config.h"
#include "executor.h"

namespace dlmfd::server {

class LocalExecutor : public Executor {
 public:
  explicit LocalExecutor(const Config& config)
      : config_(config) {}
  int Capacity() const override { return config_.max_concurrent; }
  DaemonTimeLimit TimeLimit() const override;
  std::string JobDirectory(const std::string& job_id) const override;
  std::shared_ptr<JobRun> NewRun() override;

 private:
  const Config& config_;
};

// DATA/jobs/ID: where a job's directory is unless the executor keeps it elsewhere.
std::string DataJobDirectory(const Config& config, const std::string& job_id);
// The daemon's own limit of a run: max_wall_seconds (0: none).
DaemonTimeLimit WallSecondsLimit(const Config& config);

}  // namespace dlmfd::server
