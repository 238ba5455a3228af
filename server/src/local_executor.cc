#include "local_executor.h"

#include <filesystem>

#include "solver_process.h"

namespace dlmfd::server {
namespace {

class LocalRun : public JobRun {
 public:
  void Start(const LaunchSpec& spec) override { process_.Start(spec); }
  void ReadEvents(const EventHandler& on_event) override {
    process_.ReadEvents([&](const v1::SolverEvent& event) { on_event(event, EventPosition{}); });
  }
  SolverExit Wait() override { return process_.Wait(); }
  void Signal(int signal_number) override { process_.Signal(signal_number); }
  std::string Describe() const override { return "solver pid " + std::to_string(process_.pid()); }

 private:
  SolverProcess process_;
};

}  // namespace

std::string DataJobDirectory(const Config& config, const std::string& job_id) {
  return (std::filesystem::path(config.data_dir) / "jobs" / job_id).string();
}

DaemonTimeLimit WallSecondsLimit(const Config& config) {
  if (config.max_wall_seconds <= 0) return {};
  return {config.max_wall_seconds, "max_wall_seconds"};
}

DaemonTimeLimit LocalExecutor::TimeLimit() const { return WallSecondsLimit(config_); }

std::string LocalExecutor::JobDirectory(const std::string& job_id) const {
  return DataJobDirectory(config_, job_id);
}

std::shared_ptr<JobRun> LocalExecutor::NewRun() { return std::make_shared<LocalRun>(); }

}  // namespace dlmfd::server
