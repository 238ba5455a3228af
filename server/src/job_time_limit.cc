#include "job_time_limit.h"

#include <algorithm>
#include <string>

#include "service_error.h"

namespace dlmfd::server {

DaemonTimeLimit Tighter(const DaemonTimeLimit& a, const DaemonTimeLimit& b) {
  if (a.seconds <= 0) return b;
  if (b.seconds <= 0) return a;
  return {std::min(a.seconds, b.seconds), a.settings + ", " + b.settings};
}

void CheckTimeLimit(int64_t seconds, const DaemonTimeLimit& daemon) {
  const bool limited = daemon.seconds > 0;
  const int64_t most =
      limited ? std::min(daemon.seconds, kMostTimeLimitSeconds) : kMostTimeLimitSeconds;
  Require(seconds >= 0 && seconds <= most,
          "time_limit_seconds = " + std::to_string(seconds) +
              " is not allowed: expected 0 (the daemon's limit) or 1 to " + std::to_string(most) +
              " (" + (limited ? daemon.settings : std::string("365 days")) + ")");
}

int64_t EffectiveTimeLimit(int64_t seconds, const DaemonTimeLimit& daemon) {
  return seconds > 0 ? seconds : daemon.seconds;
}

int64_t SlurmTimeMinutes(int64_t seconds) { return (seconds + 59) / 60; }

int64_t SlurmSignalLead(int64_t minutes, int signal_seconds) {
  return std::max<int64_t>(1, std::min<int64_t>(signal_seconds, minutes * 60 / 2));
}

}  // namespace dlmfd::server
