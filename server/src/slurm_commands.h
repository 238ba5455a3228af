// The Slurm commands the daemon runs and the parsing of their output (slurm 22.05's CLI; the
// commands are the stable interface there, slurmrestd needs slurmdbd: ../shared/ops).
//
//   sbatch --parsable --job-name --cpus-per-task --mem [--time --signal] --output [--partition
//          --account --qos] [extra options] SCRIPT      prints "ID" or "ID;CLUSTER"
//   squeue --json --jobs ID,...                       OpenAPI v0.0.38: jobs[].job_id, job_state
//                                                     (a string; an array in newer releases),
//                                                     state_reason, restart_cnt
//   scancel [--signal=KILL] ID
// The jobcomp file (JobCompType=jobcomp/filetxt) has one line per ended job, "JobId=ID ...
// JobState=STATE ... ExitCode=A:B": it tells the end of a job that has left squeue (MinJobAge).
// The batch script runs dlmfd-solve with its event stream appended to a file of the job directory
// (fd 3, the framing of dlmfd/solver/event_file.h), forwards SIGTERM and Slurm's time-limit
// warning (--signal=B:USR1@N) to the solver as SIGTERM (it checkpoints and exits 130), and writes
// the solver's exit status to a file of the job directory when the solver has ended.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "config.h"

namespace dlmfd::server {

// File names in the job directory.
inline constexpr char kSlurmScript[] = "slurm.sh";
inline constexpr char kSlurmIdFile[] = "slurm.id";          // the Slurm job id, once submitted
inline constexpr char kSlurmEventsFile[] = "events.bin";    // the solver's event stream
inline constexpr char kSlurmExitFile[] = "solver.exit";     // the solver's exit status
inline constexpr char kSlurmWarnedFile[] = "slurm.warned";  // Slurm's time-limit warning came
inline constexpr char kSlurmLiveFile[] = "slurm.live";      // submitted, its end not yet recorded

struct BatchJob {
  std::string name;
  std::string job_dir;
  std::string solver;  // on the nodes
  std::string scene_path;
  std::string results_dir;
  std::string log_path;
  std::vector<std::string> overrides;
  bool resume = false;
  int threads = 1;
  int64_t memory_mb = 0;
};

// The batch script's text (bash).
std::string BatchScript(const BatchJob& job);
// sbatch's arguments, without "sbatch" and with the script path last.
std::vector<std::string> SbatchArguments(const BatchJob& job, const SlurmSettings& settings,
                                         const std::string& script_path);
// The id sbatch --parsable printed; throws std::runtime_error when there is none.
std::string ParseSbatchId(const std::string& output);

struct SlurmJobStatus {
  std::string id;
  std::string state;   // "PENDING", ...
  std::string reason;  // squeue's state_reason; empty from the jobcomp file
  int restarts = 0;
  std::string exit_code;  // the jobcomp file's "A:B"; empty from squeue
};

// The job's entry in squeue --json's output; nothing when it is not listed. Throws
// std::runtime_error when the text is not squeue's JSON.
std::optional<SlurmJobStatus> FindInSqueueJson(const std::string& json, const std::string& id);
// The last line of the jobcomp file's text for the job; nothing when it has none.
std::optional<SlurmJobStatus> FindInJobComp(const std::string& text, const std::string& id);

struct CommandResult {
  int status = -1;  // exit status; 128 + signal when killed; -1 when it could not start
  std::string out, err;
};
// Runs argv[0] (found on PATH) with the arguments, without a shell; collects stdout and stderr.
CommandResult RunCommand(const std::vector<std::string>& argv);

// A single-quoted word for bash.
std::string ShellQuote(const std::string& word);

}  // namespace dlmfd::server
