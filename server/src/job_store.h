// JobStore: the durable record of every job, an SQLite file (DATA/jobs.db).
//
// One connection in serialized use (a mutex), WAL journal, a busy timeout, a schema_version table
// and ordered migrations applied at open. Every statement is prepared and parameterised; every
// state change is one transaction. An accepted job is committed before Submit returns; a job id is
// never reused. last_seq is the last watch number issued, except while a job has a channel in the
// EventHub (which then knows it; the watch log holds it, and EventHub::Recover takes it from there
// after a crash). Not
// supported: several daemons on one data directory (the daemon holds an flock on it).
//
// Studies (schema 3; the table and the jobs' column named `study` since schema 11, `sweep`
// before): a studies table holds each study (name, tags, labels, axes, base overrides,
// max_running); job_labels the key=value labels of each job; job_values the effective scene of
// each job flattened to dotted keys with normalised value texts (scene_values.h), which List's
// `where` filter matches in SQL; jobs gain the point's typed parameters, the attempt number, the
// earlier attempts and a fresh-start flag (a retry with a changed scene must not resume).
//
// Slurm (schema 5): the Slurm id of a job's latest attempt and whether its end is still to be
// recorded (slurm_live): a daemon that starts adopts such a job (NextQueued gives it first) and
// neither cancels it while queued (CancelQueued) nor holds it; attempts that end without ending
// the job (a Slurm requeue, a TIMEOUT requeued by the daemon) are recorded by EndAttempt.
// Schema 6: Slurm's state and reason of the live Slurm job and whether Slurm holds it waiting
// (SetSlurmState). The stored state stays RUNNING (the job is in the executor's hands: the
// scheduler's count); the API shows a waiting one QUEUED (ShownState; List's states filter and
// StatsOfStudy's counts go by the shown state). And the job's own wall-time limit.
// Schema 8: job dependencies (job_dependencies: job_id runs after after_id has COMPLETED, Slurm's
// afterok). NextQueued and QueuedOfStudy skip a job until all of its dependencies COMPLETED;
// Blocked names the queued jobs that never can (a dependency FAILED, CANCELLED or deleted), which
// the scheduler cancels. A queued job that waits shows the reason "dependency: waiting for ...".
// Schema 9: accounting of the current attempt (sacct's ExitCode, TotalCPU, MaxRSS; RecordUsage).
// Schema 10: the Slurm record of schemas 5 and 6 in a table of its own (slurm_jobs, a row for each
// job handed to Slurm since its submission or retry); JobRecord reads it as before.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dlmfd/scene/accuracy_envelope.h"
#include "job_states.h"

struct sqlite3;

namespace dlmfd::server {

class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One coordinate of a job's point in its study (dlmfd.v1.ParameterValue).
struct ParameterValue {
  std::string key;
  std::string text;  // TOML value text
  std::string type;  // integer, float, boolean, string, array
  double number = 0;
};

// How an earlier attempt of a job ended (dlmfd.v1.AttemptRecord).
struct AttemptRecord {
  int attempt = 0;
  JobState state = JobState::kFailed;
  std::string reason;
  double started_time = 0, finished_time = 0;
  int64_t step = 0;
  double time = 0;
  std::vector<std::string> overrides;
};

struct JobRecord {
  std::string id;
  std::string name;
  std::string owner;
  JobState state = JobState::kQueued;
  std::string reason;
  int priority = 0;
  std::vector<std::string> tags;
  std::string study_id;
  double created_time = 0, started_time = 0, finished_time = 0;
  int64_t step = 0;
  double time = 0, end_time = 0;
  int attempts = 0;
  std::string results_dir;
  std::string scene;
  std::vector<std::string> overrides;
  std::string client_request_id;
  int64_t last_seq = 0;
  std::vector<AccuracyWarning> warnings;  // found at admission (scene/accuracy_envelope.h)
  std::vector<ResolvedChoice> numerics;   // what each "auto" of the scene became (admission)
  bool cancel_requested = false;
  bool held = false;       // a queued job kept from starting
  int64_t disk_bytes = 0;  // bytes of the job directory, counted when the job finished
  int64_t ordinal = 0;     // insertion order, set by the store
  std::map<std::string, std::string> labels;
  std::vector<ParameterValue> parameters;  // the point of its study
  int attempt = 1;                         // 1 + the number of retries
  std::vector<AttemptRecord> previous_attempts;
  bool fresh_start = false;  // set by a retry with another scene: the next run must not resume
  // The effective scene as (dotted key, normalised value) pairs: written at insert and retry, not
  // read back into records (List's `where` matches it in SQL).
  std::vector<std::pair<std::string, std::string>> scene_values;
  // The slurm executor's (schema 5).
  std::string slurm_job_id;  // the latest attempt's: "123", an array task "120_4"
  bool slurm_live = false;   // submitted, its end not recorded yet: the next start adopts it
  int slurm_attempts = 0;    // sbatch submissions and Slurm restarts since submit or retry
  int slurm_restarts = 0;    // Slurm's restart count of slurm_job_id already recorded
  // Schema 6: Slurm's word on the live Slurm job (squeue's job_state and state_reason) and
  // whether Slurm holds it waiting: the API shows such a RUNNING job QUEUED (ShownState).
  std::string slurm_state, slurm_reason;
  bool slurm_waiting = false;
  int64_t time_limit_seconds = 0;  // the job's own wall-time limit of one run; 0: the daemon's
  // Schema 8: the jobs that must COMPLETE before this one runs (afterok), in the order given.
  std::vector<std::string> after;
  // Schema 9: accounting of the current attempt (RecordUsage; a retry clears it).
  int exit_code = -1;             // the latest solver run's exit status; -1: none yet, or killed
  int exit_signal = 0;            // the signal that ended it; 0: none
  double cpu_seconds = 0;         // CPU seconds (user + system) of its runs, added up
  int64_t peak_memory_bytes = 0;  // the largest peak resident set of one run
};

// How one solver run of a job ended and what it used (JobStore::RecordUsage).
struct RunUsage {
  int exit_code = -1;  // -1 when a signal ended it
  int exit_signal = 0;
  double cpu_seconds = -1;         // negative: not measured (adds nothing)
  int64_t peak_memory_bytes = -1;  // negative: not measured
};

// The state the API shows: a job in the executor's hands that Slurm holds waiting (PENDING and
// the like) is QUEUED; else the stored state.
inline JobState ShownState(const JobRecord& job) {
  return job.state == JobState::kRunning && job.slurm_waiting ? JobState::kQueued : job.state;
}

// How one attempt of a RUNNING job ended without ending the job (JobStore::EndAttempt).
struct AttemptEnd {
  JobState state = JobState::kFailed;  // recorded in previous_attempts
  std::string reason;
  double when = 0;
  // 0: the daemon queues the job again (a requeue after a Slurm TIMEOUT, NODE_FAIL, ...); else
  // Slurm ran the same Slurm job again by itself (scontrol requeue) and this is its restart
  // count: the job stays RUNNING.
  int slurm_restarts = 0;
};

// A study axis as stored: its values (a range already expanded) and how it was given.
struct StoredAxis {
  std::string key;
  std::string zip;  // axes with the same non-empty name step together
  std::vector<std::string> values;
  bool is_range = false;
  double start = 0, stop = 0;
  int count = 0;
  bool logarithmic = false;
};

struct StudyRecord {
  std::string id;
  std::string owner;
  std::string name;
  std::vector<std::string> tags;
  std::map<std::string, std::string> labels;
  std::vector<StoredAxis> axes;
  std::vector<std::string> overrides;
  int max_running = 0;
  double created_time = 0;
  int64_t ordinal = 0;
};

// Where a study's jobs stand, from one aggregate query.
struct StudyStats {
  std::array<int, 6> count{};  // indexed by the shown JobState (ShownState; 0 unused)
  int jobs = 0;
  double progress_sum = 0;  // sum over jobs of min(1, time / end_time), finished jobs 1
  double first_started_time = 0, last_finished_time = 0;
};

// A retry of one finished job: what changes (JobStore::Requeue).
struct RequeueChange {
  std::string id;
  std::vector<std::string> overrides;
  std::vector<ParameterValue> parameters;
  std::vector<std::pair<std::string, std::string>> scene_values;
  std::vector<AccuracyWarning> warnings;
  double end_time = 0;
  bool fresh_start = false;
  std::string name;  // empty: unchanged
  std::vector<ResolvedChoice> numerics;
};

// One `where` filter of List on the effective scene: a key pattern ('*' matches any index), an
// operator, and its operand: the normalised value for = and != (scene_values.h), a number for the
// ranges <, <=, >, >= (which only a value that reads as a number can meet).
struct SceneValueFilter {
  std::string pattern;
  std::string op;     // "=", "!=", "<", "<=", ">", ">="
  std::string value;  // = and !=
  double bound = 0;   // <, <=, >, >=
};

struct ListFilter {
  std::string owner;
  std::vector<JobState> states;               // empty: any
  std::string tag;                            // empty: any
  std::string study_id;                       // empty: any
  std::vector<std::string> tags;              // every one of them
  std::map<std::string, std::string> labels;  // every one of them
  // Filters on the effective scene's values, every one of them.
  std::vector<SceneValueFilter> values;
  int64_t before_ordinal = 0;  // 0: from the newest
  int limit = 100;
};

class JobStore {
 public:
  explicit JobStore(const std::string& path);
  ~JobStore();
  JobStore(const JobStore&) = delete;
  JobStore& operator=(const JobStore&) = delete;

  static int SchemaVersion();

  // Inserts the jobs in one transaction. If request_key is non-empty and (owner, request_key) was
  // used before, nothing is inserted and the earlier jobs are returned with `existed` set.
  struct InsertResult {
    std::vector<JobRecord> jobs;
    bool existed = false;
  };
  // With `study`, the study's row is inserted in the same transaction.
  InsertResult InsertJobs(std::vector<JobRecord> jobs, const std::string& owner,
                          const std::string& request_key, const StudyRecord* study = nullptr);

  // The jobs created by an earlier request with this key, or empty.
  std::vector<JobRecord> FindRequest(const std::string& owner, const std::string& request_key);
  std::optional<JobRecord> Get(const std::string& id);
  std::vector<JobRecord> List(const ListFilter& filter);
  // Whether some job of the owner has a scene key that the pattern ('*': any index) matches;
  // true when the owner has no job at all (a filter on nothing refuses nothing).
  bool SceneKeyKnown(const std::string& owner, const std::string& pattern);
  int64_t CountUnfinished();
  std::vector<std::string> UnfinishedJobIds();
  std::vector<JobRecord> StudyJobs(const std::string& owner, const std::string& study_id);
  std::optional<StudyRecord> GetStudy(const std::string& owner, const std::string& study_id);
  // The owner's studies, newest first; tag empty: any.
  std::vector<StudyRecord> ListStudies(const std::string& owner, const std::string& tag,
                                       int64_t before_ordinal, int limit);
  StudyStats StatsOfStudy(const std::string& owner, const std::string& study_id);
  // Finished jobs back to QUEUED in one transaction, each with attempt + 1 and its ending recorded
  // in previous_attempts; returns them as written (QUEUED: the scheduler may take them the moment
  // the transaction ends, so a later Get can already read RUNNING). Throws StoreError (nothing
  // changed) when one is no longer finished.
  std::vector<JobRecord> Requeue(const std::vector<RequeueChange>& changes);
  void ClearFreshStart(const std::string& id);

  // Every job of the owner, oldest first.
  std::vector<JobRecord> OwnerJobs(const std::string& owner);

  // Highest priority, then oldest, among QUEUED jobs that are not held and whose study is below
  // its max_running.
  std::optional<JobRecord> NextQueued();
  // The QUEUED jobs of a study that are neither held nor in Slurm's hands, in NextQueued's order,
  // at most limit: the slurm executor hands them to Slurm together (one job array).
  std::vector<JobRecord> QueuedOfStudy(const std::string& study_id, int limit);
  int CountRunningOfStudy(const std::string& study_id);
  // The QUEUED jobs (not in Slurm's hands) with a dependency that ended FAILED or CANCELLED or was
  // deleted, oldest first, each with the reason to cancel it: "dependency ID failed (FAILED)",
  // "dependency ID was deleted".
  std::vector<std::pair<std::string, std::string>> Blocked();
  // QUEUED -> RUNNING. kRun: a solver starts now (attempts + 1, started_time); kWaiting: a run
  // handed to an executor that holds it first (a Slurm submission: attempts + 1, shown QUEUED
  // until SetSlurmState says it runs); kAdopt: a run that outlived the daemon is followed again
  // (no new start). Throws StoreError when the job is not QUEUED.
  enum class RunStart { kRun, kWaiting, kAdopt };
  void MarkRunning(const std::string& id, double started_time, RunStart start = RunStart::kRun);
  // Sets a finished state; returns false when the job had already finished (nothing changed).
  bool MarkFinished(const std::string& id, JobState state, const std::string& reason, double when);
  // QUEUED -> CANCELLED atomically; false if the job was not QUEUED or is a Slurm job to adopt.
  bool CancelQueued(const std::string& id, const std::string& reason, double when);
  void SetCancelRequested(const std::string& id);
  void UpdateProgress(const std::string& id, int64_t step, double time, double end_time);
  void SetLastSeq(const std::string& id, int64_t last_seq);
  std::optional<int64_t> LastSeq(const std::string& id);  // none when the job does not exist
  // The slurm executor submitted the job's attempt as slurm_job_id: recorded, live (adopted by
  // the next start until its end is recorded: MarkFinished and EndAttempt clear it), one more
  // Slurm attempt.
  void SetSlurmSubmitted(const std::string& id, const std::string& slurm_job_id);
  // Slurm's word on the RUNNING job's live Slurm job: its state, reason and whether Slurm holds it
  // waiting; started_time becomes `now` when a waiting job starts. Submission sets PENDING and
  // waiting; an end (MarkFinished, EndAttempt, Requeue) clears them. False when nothing changed.
  bool SetSlurmState(const std::string& id, const std::string& slurm_state,
                     const std::string& slurm_reason, bool waiting, double now);
  // Ends the current attempt of a RUNNING job: records it in previous_attempts, attempt + 1.
  // Throws StoreError when the job is not RUNNING.
  void EndAttempt(const std::string& id, const AttemptEnd& end);
  // Daemon start after a crash: every RUNNING job becomes QUEUED (returned), except those whose
  // cancel was requested, which become CANCELLED.
  std::vector<std::string> RequeueRunning(double now);
  int CountRunning();
  // Holds or releases a QUEUED job; false when the job is not QUEUED or is a Slurm job to adopt.
  bool SetHeld(const std::string& id, bool held);
  // Sets the priority of a QUEUED or RUNNING job; false when it has finished (or does not exist).
  bool SetPriority(const std::string& id, int priority);
  void SetDiskBytes(const std::string& id, int64_t bytes);
  // A solver run of the job ended: its exit status replaces the job's, its CPU time is added, its
  // peak memory kept when it is the largest.
  void RecordUsage(const std::string& id, const RunUsage& usage);
  // Removes the jobs, their tags and their ids from the requests that made them (a request left
  // with no job is forgotten), and each study left with no job.
  void Delete(const std::vector<std::string>& ids);

 private:
  class Statement;
  void Exec(const char* sql);
  void Migrate();
  std::vector<JobRecord> Query(Statement& statement);
  void LoadTags(JobRecord& job);
  void LoadLabels(JobRecord& job);
  void LoadDependencies(JobRecord& job);
  void WriteSceneValues(const std::string& id,
                        const std::vector<std::pair<std::string, std::string>>& values);
  std::vector<StudyRecord> QueryStudies(Statement& statement);

  std::mutex mutex_;
  sqlite3* db_ = nullptr;
};

}  // namespace dlmfd::server
