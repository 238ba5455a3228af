#include "executor.h"

#include <map>
#include <memory>
#include <mutex>

#include "slurm_executor.h"

namespace dlmfd::server {
namespace {

// The local executor: dlmfd-solve as a child process of the daemon.
class LocalRun : public JobRun {
 public:
  void Start(const LaunchSpec& spec) override { process_.Start(spec); }
  void ReadEvents(const std::function<void(const v1::SolverEvent&)>& on_event) override {
    process_.ReadEvents(on_event);
  }
  SolverExit Wait() override { return process_.Wait(); }
  void Signal(int signal_number) override { process_.Signal(signal_number); }
  std::string Describe() const override { return "solver pid " + std::to_string(process_.pid()); }

 private:
  SolverProcess process_;
};

}  // namespace

std::shared_ptr<JobRun> MakeJobRun(const Config& config) {
  if (config.executor == "slurm") {
    // One squeue poll for every live run of this configuration.
    static std::mutex mutex;
    static std::map<const Config*, std::weak_ptr<SlurmQueue>> shared;
    std::lock_guard lock(mutex);
    auto queue = shared[&config].lock();
    if (!queue) {
      queue = std::make_shared<SlurmQueue>(config.slurm);
      shared[&config] = queue;
    }
    return std::make_shared<SlurmRun>(config, queue);
  }
  return std::make_shared<LocalRun>();
}

}  // namespace dlmfd::server
