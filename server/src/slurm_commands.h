// The Slurm commands the daemon runs and the parsing of their output (slurm 22.05's CLI; the
// commands are the stable interface there, slurmrestd needs slurmdbd:
// docs/sources/slurm_single_node.md).
//
//   sbatch --parsable --job-name --cpus-per-task --mem --output [--array --time --signal
//          --partition --account --qos] [extra options] SCRIPT   prints "ID" or "ID;CLUSTER"
//   squeue --json                                     OpenAPI v0.0.38: jobs[].job_id, job_state
//                                                     (a string; an array in newer releases),
//                                                     state_reason, restart_cnt, array_job_id,
//                                                     array_task_id, array_task_string
//   squeue -h --name --states -o "%i %Z"              the live jobs of a name and their
//                                                     working directories
//   scancel [--signal=KILL] ID                        ID or ARRAYID_INDEX
// The jobcomp file (JobCompType=jobcomp/filetxt) has one line per ended job, "JobId=ID ...
// JobState=STATE ... [ArrayJobId=A ArrayTaskId=I] ExitCode=A:B": it tells the end of a job that
// has left squeue (MinJobAge).
// The batch script runs dlmfd-solve with its event stream appended to a file of the job directory
// (fd 3, the framing of dlmfd/solver/event_file.h), forwards SIGTERM and Slurm's time-limit
// warning (--signal=B:USR1@N) to the solver as SIGTERM (it checkpoints and exits 130), resumes
// from the checkpoint when Slurm runs it again (SLURM_RESTART_COUNT > 0), and writes the solver's
// exit status and that restart count to a file of the job directory when the solver has ended.
// A study's jobs go to Slurm as one job array whose script runs, for task I, the batch script of
// the I-th job's directory.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "config.h"

namespace dlmfd::server {

// File names in the job directory.
inline constexpr char kSlurmScript[] = "slurm.sh";
inline constexpr char kSlurmIdFile[] = "slurm.id";          // the Slurm job id, once submitted
inline constexpr char kSlurmEventsFile[] = "events.bin";    // the solver's event stream
inline constexpr char kSlurmExitFile[] = "solver.exit";     // "STATUS RESTARTS" of the solver
inline constexpr char kSlurmWarnedFile[] = "slurm.warned";  // Slurm's time-limit warning came

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
  // The job's wall-time limit (job_time_limit.h: its own, else the daemon's); 0: none. sbatch gets
  // --time in whole minutes, rounded up, and --signal=B:USR1@N (slurm_signal_seconds, at most half
  // the limit).
  int64_t time_limit_seconds = 0;
  std::string array;  // sbatch --array (ArraySpec) for a job array; empty for one job
};

// The batch script's text (bash).
std::string BatchScript(const BatchJob& job);
// The script of a job array (a study's jobs handed over together): task I runs the batch script
// of its job's directory, given as (I, directory) pairs; log lines of Slurm go to the array's
// --output (the array's job_dir/task-%a.log, each a link to its job's solver.log).
std::string ArrayScript(const std::string& name,
                        const std::vector<std::pair<int, std::string>>& task_dirs);
// sbatch's --array value: the indices as ranges ("0-3,5"), then "%throttle" when throttle > 0.
std::string ArraySpec(const std::vector<int>& indices, int throttle);
// The id of an array task as the daemon stores it and scancel takes it: "ARRAYID_INDEX".
std::string ArrayTaskId(const std::string& array_id, int index);
// sbatch's arguments, without "sbatch" and with the script path last.
std::vector<std::string> SbatchArguments(const BatchJob& job, const SlurmSettings& settings,
                                         const std::string& script_path);
// The id sbatch --parsable printed; throws std::runtime_error when there is none.
std::string ParseSbatchId(const std::string& output);
// squeue's arguments (without "squeue") that list the live jobs of a name, one "ID WORKDIR" line
// each: waiting or running, not ending or ended.
std::vector<std::string> SqueueOfNameArguments(const std::string& name);
// The id in that output of the job whose working directory is job_dir; empty when none is.
std::string ParseLiveJobIn(const std::string& output, const std::string& job_dir);

struct SlurmJobStatus {
  std::string id;
  std::string state;   // "PENDING", ...
  std::string reason;  // squeue's state_reason; empty from the jobcomp file
  int restarts = 0;
  std::string exit_code;  // the jobcomp file's "A:B"; empty from squeue
};

// squeue --json's jobs by the daemon's ids: "ID" for a job, "ARRAYID_INDEX" for an array task
// (a task that has started has an entry of its own; the array's pending record stands for each
// index of its array_task_string, "2-5%2"). Throws std::runtime_error when the text is not
// squeue's JSON or reports an error (a slurmctld that does not answer: squeue --json then exits 0
// with no jobs and the error in "errors").
std::map<std::string, SlurmJobStatus> ParseSqueueJson(const std::string& json);
// The job's entry in squeue --json's output; nothing when it is not listed.
std::optional<SlurmJobStatus> FindInSqueueJson(const std::string& json, const std::string& id);
// The jobcomp file's jobs by the same ids (ArrayJobId and ArrayTaskId name an array task's); a
// job with several lines (requeued) has its last.
std::map<std::string, SlurmJobStatus> ParseJobComp(const std::string& text);
// The last line of the jobcomp file's text for the job; nothing when it has none.
std::optional<SlurmJobStatus> FindInJobComp(const std::string& text, const std::string& id);

struct CommandResult {
  int status = -1;  // exit status; 128 + signal when killed; -1 when it could not start
  std::string out, err;
};
// Runs argv[0] (found on PATH) with the arguments, without a shell; collects stdout and stderr.
CommandResult RunCommand(const std::vector<std::string>& argv);

// True when a Slurm command's error output says that slurmctld could not be reached or was busy
// (a controller restarting or failing over): the command is worth running again.
bool TransientSlurmError(const std::string& err);
// How long the daemon waits before it runs sbatch again after a transient error.
inline constexpr std::chrono::seconds kSbatchRetryInterval{5};

// A single-quoted word for bash.
std::string ShellQuote(const std::string& word);

}  // namespace dlmfd::server
