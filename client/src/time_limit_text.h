// The text of a job's wall-time limit on the command line (`dlmfd submit/study --time`): a
// duration in seconds for SubmitRequest.time_limit_seconds.
//
// Accepted, as a researcher who uses Slurm writes it:
//   units       "90m", "2h", "45s", "1d", and sums of them: "1h30m", "1d12h"
//   sbatch's    "90" (minutes), "90:30" (minutes:seconds), "1:30:00" (hours:minutes:seconds),
//               "2-12" (days-hours), "2-12:30" (days-hours:minutes), "2-12:30:00"
// The duration must be positive: to take the daemon's limit, give no --time.
#pragma once

#include <cstdint>
#include <string>

namespace dlmfd::cli {

// Seconds of the text; throws std::invalid_argument whose message says what is expected.
int64_t ParseTimeLimit(const std::string& text);

}  // namespace dlmfd::cli
