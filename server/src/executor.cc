#include "executor.h"

#include <map>
#include <memory>
#include <mutex>

#include "slurm_array.h"
#include "slurm_executor.h"

namespace dlmfd::server {
namespace {

// The local executor: dlmfd-solve as a child process of the daemon.
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

// One squeue poll for every live run of this configuration.
std::shared_ptr<SlurmQueue> SharedQueue(const Config& config) {
  static std::mutex mutex;
  static std::map<const Config*, std::weak_ptr<SlurmQueue>> shared;
  std::lock_guard lock(mutex);
  auto queue = shared[&config].lock();
  if (!queue) {
    queue = std::make_shared<SlurmQueue>(config.slurm);
    shared[&config] = queue;
  }
  return queue;
}

}  // namespace

std::shared_ptr<JobRun> MakeJobRun(const Config& config) {
  if (config.executor == "slurm") return std::make_shared<SlurmRun>(config, SharedQueue(config));
  return std::make_shared<LocalRun>();
}

bool SubmitsStudiesTogether(const Config& config) { return config.executor == "slurm"; }

std::vector<std::shared_ptr<JobRun>> MakeStudyRuns(const Config& config, const std::string& study,
                                                   int count, int throttle) {
  std::vector<std::shared_ptr<JobRun>> runs;
  if (!SubmitsStudiesTogether(config)) {
    for (int i = 0; i < count; ++i) runs.push_back(MakeJobRun(config));
    return runs;
  }
  auto array = std::make_shared<SlurmArray>(config, "dlmfd-" + study, count, throttle);
  for (int i = 0; i < count; ++i) {
    runs.push_back(std::make_shared<SlurmRun>(config, SharedQueue(config), array, i));
  }
  return runs;
}

}  // namespace dlmfd::server
