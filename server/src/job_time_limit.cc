#include "job_time_limit.h"

#include <algorithm>
#include <string>

#include "service_error.h"

namespace dlmfd::server {

int64_t DaemonTimeLimit(const Config& config) {
  int64_t limit = config.max_wall_seconds;
  if (config.executor == "slurm" && config.slurm.time_limit_minutes > 0) {
    const int64_t slurm = int64_t{config.slurm.time_limit_minutes} * 60;
    limit = limit > 0 ? std::min(limit, slurm) : slurm;
  }
  return limit;
}

void CheckTimeLimit(int64_t seconds, const Config& config) {
  const int64_t daemon = DaemonTimeLimit(config);
  const int64_t most = daemon > 0 ? std::min(daemon, kMostTimeLimitSeconds) : kMostTimeLimitSeconds;
  std::string where = "365 days";
  if (daemon > 0) {
    where = config.executor == "slurm" && config.slurm.time_limit_minutes > 0
                ? (config.max_wall_seconds > 0 ? "max_wall_seconds, slurm_time_limit_minutes"
                                               : "slurm_time_limit_minutes")
                : "max_wall_seconds";
  }
  Require(seconds >= 0 && seconds <= most,
          "time_limit_seconds = " + std::to_string(seconds) +
              " is not allowed: expected 0 (the daemon's limit) or 1 to " + std::to_string(most) +
              " (" + where + ")");
}

int64_t EffectiveTimeLimit(int64_t seconds, const Config& config) {
  return seconds > 0 ? seconds : DaemonTimeLimit(config);
}

int64_t SlurmTimeMinutes(int64_t seconds) { return (seconds + 59) / 60; }

int64_t SlurmSignalLead(int64_t minutes, int signal_seconds) {
  return std::max<int64_t>(1, std::min<int64_t>(signal_seconds, minutes * 60 / 2));
}

}  // namespace dlmfd::server
