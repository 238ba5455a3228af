// A job's wall-time limit: the time one run of it may take (SubmitRequest.time_limit_seconds, or
// the daemon's limit when the job gives none), checked at submission and applied by the executor.
//
// The daemon's limit is its executor's (Executor::TimeLimit, executor.h): max_wall_seconds and,
// with the slurm executor, also slurm_time_limit_minutes (the smaller when both are set); a job
// may ask for less, never more (else kMostTimeLimitSeconds, Slurm's largest --time). The local
// executor stops a solver start past the job's limit (WallTimeLimit: it checkpoints, the job ends
// FAILED naming the limit); the slurm executor gives it to sbatch as --time in whole minutes,
// rounded up (Slurm counts minutes), with --signal=B:USR1@N so that the solver checkpoints N s
// before it (slurm_signal_seconds, at most half the limit: a short limit leaves the solver time
// to run). Slurm counts the time a job runs, not the time it waits in Slurm's queue; a TIMEOUT
// queues the job again to resume from its checkpoint while slurm_max_attempts allows
// (docs/cluster.md).
#pragma once

#include <cstdint>

#include "executor.h"

namespace dlmfd::server {

// 365 days: Slurm's largest --time (525600 minutes), and the most any job may ask for.
inline constexpr int64_t kMostTimeLimitSeconds = 525600LL * 60;

// The smaller of two limits (0: none); its settings name every limit that is set.
DaemonTimeLimit Tighter(const DaemonTimeLimit& a, const DaemonTimeLimit& b);
// Throws INVALID_ARGUMENT naming time_limit_seconds when seconds < 0 or over the daemon's limit
// (or kMostTimeLimitSeconds); 0 (the daemon's limit) is allowed.
void CheckTimeLimit(int64_t seconds, const DaemonTimeLimit& daemon);
// The limit that applies to a job that asked for `seconds` (0: none asked): its own, else the
// daemon's; 0: none.
int64_t EffectiveTimeLimit(int64_t seconds, const DaemonTimeLimit& daemon);

// sbatch --time in minutes for a limit in seconds (> 0): rounded up.
int64_t SlurmTimeMinutes(int64_t seconds);
// --signal's lead time for a limit of `minutes`: signal_seconds, at most half the limit (>= 1).
int64_t SlurmSignalLead(int64_t minutes, int signal_seconds);

}  // namespace dlmfd::server
