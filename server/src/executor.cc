#include "executor.h"

#include <functional>
#include <map>

#include "local_executor.h"
#include "slurm_executor.h"

namespace dlmfd::server {
namespace {

using Factory = std::function<std::unique_ptr<Executor>(const Config&)>;

// The one place that maps the `executor` setting to an implementation.
const std::map<std::string, Factory>& Executors() {
  static const std::map<std::string, Factory> executors = {
      {"local", [](const Config& c) { return std::make_unique<LocalExecutor>(c); }},
      {"slurm", [](const Config& c) { return std::make_unique<SlurmExecutor>(c); }},
  };
  return executors;
}

}  // namespace

std::vector<std::shared_ptr<JobRun>> Executor::NewStudyRuns(const std::string& study, int count,
                                                            int throttle) {
  (void)study;
  (void)throttle;
  std::vector<std::shared_ptr<JobRun>> runs;
  for (int i = 0; i < count; ++i) runs.push_back(NewRun());
  return runs;
}

std::unique_ptr<Executor> MakeExecutor(const Config& config) {
  const auto found = Executors().find(config.executor);
  if (found == Executors().end()) {
    throw ConfigError("executor = \"" + config.executor + "\" is not allowed: expected " +
                      ExecutorNamesText());
  }
  return found->second(config);
}

bool IsExecutorName(const std::string& name) { return Executors().count(name) > 0; }

std::string ExecutorNamesText() {
  std::string text;
  size_t left = Executors().size();
  for (const auto& [name, factory] : Executors()) {
    text += name;
    --left;
    text += left > 1 ? ", " : left == 1 ? " or " : "";
  }
  return text;
}

}  // namespace dlmfd::server
