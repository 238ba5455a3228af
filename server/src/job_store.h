// JobStore: the durable record of every job, an SQLite file (DATA/jobs.db).
//
// One connection in serialized use (a mutex), WAL journal, a busy timeout, a schema_version table
// and ordered migrations applied at open. Every statement is prepared and parameterised; every
// state change is one transaction. An accepted job is committed before Submit returns; a job id is
// never reused. Watch sequence numbers are handed out in blocks: last_seq is the reserved
// high-water mark, so after a crash the next daemon starts above any number it may have issued. Not
// supported: several daemons on one data directory (the daemon holds an flock on it).
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dlmfd/scene/accuracy_envelope.h"

struct sqlite3;

namespace dlmfd::server {

class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Values equal dlmfd.v1.JobState.
enum class JobState { kQueued = 1, kRunning = 2, kCompleted = 3, kFailed = 4, kCancelled = 5 };
bool IsFinished(JobState state);
const char* JobStateName(JobState state);

struct JobRecord {
  std::string id;
  std::string name;
  std::string owner;
  JobState state = JobState::kQueued;
  std::string reason;
  int priority = 0;
  std::vector<std::string> tags;
  std::string sweep_id;
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
  bool cancel_requested = false;
  bool held = false;       // a queued job kept from starting
  int64_t disk_bytes = 0;  // bytes of the job directory, counted when the job finished
  int64_t ordinal = 0;     // insertion order, set by the store
};

struct ListFilter {
  std::string owner;
  std::vector<JobState> states;  // empty: any
  std::string tag;               // empty: any
  std::string sweep_id;          // empty: any
  int64_t before_ordinal = 0;    // 0: from the newest
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
  InsertResult InsertJobs(std::vector<JobRecord> jobs, const std::string& owner,
                          const std::string& request_key);

  // The jobs created by an earlier request with this key, or empty.
  std::vector<JobRecord> FindRequest(const std::string& owner, const std::string& request_key);
  std::optional<JobRecord> Get(const std::string& id);
  std::vector<JobRecord> List(const ListFilter& filter);
  int64_t CountUnfinished();
  std::vector<JobRecord> SweepJobs(const std::string& owner, const std::string& sweep_id);

  // Every job of the owner, oldest first.
  std::vector<JobRecord> OwnerJobs(const std::string& owner);

  // Highest priority, then oldest, among QUEUED jobs that are not held.
  std::optional<JobRecord> NextQueued();
  void MarkRunning(const std::string& id, double started_time);
  // Sets a finished state; returns false when the job had already finished (nothing changed).
  bool MarkFinished(const std::string& id, JobState state, const std::string& reason, double when);
  // QUEUED -> CANCELLED atomically; false if the job was not QUEUED.
  bool CancelQueued(const std::string& id, const std::string& reason, double when);
  void SetCancelRequested(const std::string& id);
  void UpdateProgress(const std::string& id, int64_t step, double time, double end_time);
  void SetLastSeq(const std::string& id, int64_t last_seq);
  // Daemon start after a crash: every RUNNING job becomes QUEUED (returned), except those whose
  // cancel was requested, which become CANCELLED.
  std::vector<std::string> RequeueRunning(double now);
  int CountRunning();
  // Holds or releases a QUEUED job; false when the job is not QUEUED.
  bool SetHeld(const std::string& id, bool held);
  // Sets the priority of a QUEUED or RUNNING job; false when it has finished (or does not exist).
  bool SetPriority(const std::string& id, int priority);
  void SetDiskBytes(const std::string& id, int64_t bytes);
  // Removes the jobs, their tags and their ids from the requests that made them (a request left
  // with no job is forgotten).
  void Delete(const std::vector<std::string>& ids);

 private:
  class Statement;
  void Exec(const char* sql);
  void Migrate();
  std::vector<JobRecord> Query(Statement& statement);
  void LoadTags(JobRecord& job);

  std::mutex mutex_;
  sqlite3* db_ = nullptr;
};

}  // namespace dlmfd::server
