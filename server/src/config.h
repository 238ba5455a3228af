// Config: dlmfdd's one validated configuration.
//
// Precedence, highest first: command-line flag > environment (DLMFD_*) > TOML config file (--config
// or DLMFD_CONFIG) > defaults. Each TOML key has the flag --key-with-dashes and the environment
// variable DLMFD_KEY (docs/api.md has the table). Keys and defaults:
//   listen            "127.0.0.1:7443" (loopback); HOST:PORT with a port 0-65535 (0: a free one)
//   data_dir          "$XDG_DATA_HOME/dlmfd" or "~/.local/share/dlmfd"; this and the other paths
//                     (solver, slurm_shared_dir, slurm_solver, slurm_jobcomp_file) are made
//                     absolute against the directory the daemon starts in
//   max_concurrent    2
//   solver            dlmfd-solve next to the dlmfdd executable; must be an executable file
//   tokens_file       none (lines "token user"); when set, at least one token
//   max_scene_bytes   1 MiB, the scene and its overrides together
//   max_grid_nodes    4,000,000
//   max_memory_mb     4096 (estimated per job)
//   max_queued        10000 unfinished jobs
//   max_user_disk_mb  0 (no quota): a user whose jobs' directories hold this many MiB or more
//                     can submit no job (RESOURCE_EXHAUSTED) until they delete some
//   max_steps         0 (no limit): steps of one job, round(time.end / time.dt)
//   max_snapshots     0 (no limit): field snapshots of one job, the initial one included
//   max_wall_seconds  0 (no limit): wall time of one solver start; past it the solver is stopped
//                     (it checkpoints) and the job ends FAILED naming the limit
//   watcher_buffer    256 events per watcher
//   event_ring        no longer used (every event is in the job's watch log); accepted
//   solver_threads    0: OMP_NUM_THREADS of each solver is max(1, cores / max_concurrent) unless
//                     the daemon's own environment sets it
//   log_level         "info"
//   port_file         none: write the bound port here once serving
//   executor          "local" (child processes) or "slurm" (batch jobs; the slurm_* keys below)
//   slurm_partition, slurm_account, slurm_qos   none: Slurm's defaults
//   slurm_sbatch_options  none: more sbatch options, separated by spaces ("--constraint=x86")
//   slurm_shared_dir  none: data_dir/jobs; else the job directories live here (it must be on a
//                     filesystem the nodes share with the daemon's machine)
//   slurm_solver      the solver setting: dlmfd-solve's path on the nodes
//   slurm_poll_seconds    10: how often squeue is asked (1-3600)
//   slurm_max_submitted   100: the most jobs handed to Slurm at once (1-100000)
//   slurm_time_limit_minutes  0: none; else each job's --time
//   slurm_signal_seconds  120: with a time limit, Slurm warns the solver this long before it
//                     (--signal=B:USR1@N) so that it checkpoints
//   slurm_jobcomp_file    none: Slurm's JobCompLoc (jobcomp/filetxt), read for the end of jobs
//                     that have left squeue
//   slurm_max_attempts    3 (1-100): a job that Slurm ends with TIMEOUT, NODE_FAIL, PREEMPTED or
//                     BOOT_FAIL is queued again (it resumes from its checkpoint) while it has had
//                     fewer attempts in Slurm since it was submitted or retried (each sbatch and
//                     each Slurm restart counts); 1: never
// Validation (ValidateConfig): a listen address that is not loopback requires a tokens file; a
// tokens file must hold at least one token.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace dlmfd::server {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The slurm executor's settings (slurm_* keys; slurm_executor.h).
struct SlurmSettings {
  std::string partition, account, qos, sbatch_options, shared_dir, solver, jobcomp_file;
  int poll_seconds = 10;
  int max_submitted = 100;
  int time_limit_minutes = 0;
  int signal_seconds = 120;
  int max_attempts = 3;
};

struct Config {
  std::string listen = "127.0.0.1:7443";
  std::string data_dir;
  int max_concurrent = 2;
  std::string solver;
  std::string tokens_file;
  int64_t max_scene_bytes = 1 << 20;
  int64_t max_grid_nodes = 4'000'000;
  int64_t max_memory_mb = 4096;
  int64_t max_queued = 10000;
  int64_t max_user_disk_mb = 0;  // 0: none
  int64_t max_steps = 0;         // 0: none
  int64_t max_snapshots = 0;     // 0: none
  int64_t max_wall_seconds = 0;  // 0: none
  int watcher_buffer = 256;
  int event_ring = 1024;
  int solver_threads = 0;
  std::string log_level = "info";
  std::string port_file;
  std::map<std::string, std::string> tokens;  // token -> user, loaded from tokens_file
  std::string executor = "local";
  SlurmSettings slurm;
};

using EnvLookup = std::function<const char*(const char*)>;

// Builds the configuration from argv (argv[0] locates the default solver), the environment and the
// config file; validates it and loads the tokens. Throws ConfigError with a message for the user.
// Returns false (and prints help) when --help was given.
bool LoadConfig(int argc, const char* const* argv, const EnvLookup& env, Config& config);

// Throws ConfigError when the configuration is unusable: a listen address that is not HOST:PORT
// with a port 0-65535 (0: pick a free one) or unix:PATH, a tokens_file without tokens, a solver
// that is not an executable file, a value out of its range.
void ValidateConfig(Config& config);

// What is usable but unwise, one line each for the log at start: a tokens file that its group or
// others can read.
std::vector<std::string> ConfigWarnings(const Config& config);

// True for 127.0.0.0/8, ::1, localhost and unix: addresses.
bool IsLoopbackAddress(const std::string& listen);

// Parses a tokens file: lines "token user"; blank lines and lines starting with '#' are skipped.
std::map<std::string, std::string> LoadTokens(const std::string& path);

}  // namespace dlmfd::server
