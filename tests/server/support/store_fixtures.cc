#include "store_fixtures.h"

#include <sqlite3.h>

#include <functional>
#include <map>
#include <stdexcept>

namespace dlmfd::testing {

server::JobRecord StoreJob(const std::string& id, const std::string& study, int priority,
                           const std::string& owner) {
  server::JobRecord job;
  job.id = id;
  job.name = id;
  job.owner = owner;
  job.study_id = study;
  job.priority = priority;
  job.results_dir = "/tmp/" + id;
  job.scene = "scene";
  return job;
}

server::StudyRecord StoreStudy(const std::string& id, int max_running) {
  server::StudyRecord study;
  study.id = id;
  study.owner = "local";
  study.max_running = max_running;
  return study;
}

namespace {

// What each schema added (job_store.cc kMigrations), undone.
const std::map<int, const char*, std::greater<>> kUndo = {
    {11,
     "ALTER TABLE studies RENAME TO sweeps; ALTER TABLE jobs RENAME COLUMN study_id TO sweep_id; "
     "DROP INDEX studies_owner; CREATE INDEX sweeps_owner ON sweeps (owner, ordinal DESC); "
     "DROP INDEX jobs_study; CREATE INDEX jobs_sweep ON jobs (owner, sweep_id);"},
    {10,
     "ALTER TABLE jobs ADD COLUMN slurm_job_id TEXT NOT NULL DEFAULT ''; "
     "ALTER TABLE jobs ADD COLUMN slurm_live INTEGER NOT NULL DEFAULT 0; "
     "ALTER TABLE jobs ADD COLUMN slurm_attempts INTEGER NOT NULL DEFAULT 0; "
     "ALTER TABLE jobs ADD COLUMN slurm_restarts INTEGER NOT NULL DEFAULT 0; "
     "ALTER TABLE jobs ADD COLUMN slurm_state TEXT NOT NULL DEFAULT ''; "
     "ALTER TABLE jobs ADD COLUMN slurm_reason TEXT NOT NULL DEFAULT ''; "
     "ALTER TABLE jobs ADD COLUMN slurm_waiting INTEGER NOT NULL DEFAULT 0; "
     "UPDATE jobs SET slurm_job_id = s.slurm_job_id, slurm_live = s.live, "
     "slurm_attempts = s.attempts, slurm_restarts = s.restarts, slurm_state = s.state, "
     "slurm_reason = s.reason, slurm_waiting = s.waiting FROM slurm_jobs s "
     "WHERE s.job_id = jobs.id; DROP TABLE slurm_jobs;"},
    {9,
     "ALTER TABLE jobs DROP COLUMN exit_code; ALTER TABLE jobs DROP COLUMN exit_signal; "
     "ALTER TABLE jobs DROP COLUMN cpu_seconds; ALTER TABLE jobs DROP COLUMN peak_memory_bytes;"},
    {8, "DROP TABLE job_dependencies;"},
    {7, "ALTER TABLE jobs DROP COLUMN numerics;"},
    {6,
     "ALTER TABLE jobs DROP COLUMN slurm_state; ALTER TABLE jobs DROP COLUMN slurm_reason; "
     "ALTER TABLE jobs DROP COLUMN slurm_waiting; ALTER TABLE jobs DROP COLUMN "
     "time_limit_seconds;"},
    {5,
     "ALTER TABLE jobs DROP COLUMN slurm_job_id; ALTER TABLE jobs DROP COLUMN slurm_live; "
     "ALTER TABLE jobs DROP COLUMN slurm_attempts; ALTER TABLE jobs DROP COLUMN slurm_restarts;"},
    {4, "ALTER TABLE jobs DROP COLUMN held; ALTER TABLE jobs DROP COLUMN disk_bytes;"},
    {3,
     "DROP TABLE sweeps; DROP TABLE job_labels; DROP TABLE job_values; ALTER TABLE jobs DROP "
     "COLUMN parameters; ALTER TABLE jobs DROP COLUMN attempt; ALTER TABLE jobs DROP COLUMN "
     "previous_attempts; ALTER TABLE jobs DROP COLUMN fresh_start;"},
    {2, "ALTER TABLE jobs DROP COLUMN warnings;"},
};

}  // namespace

void RollBackSchema(const std::string& path, int version) {
  if (kUndo.begin()->first != server::JobStore::SchemaVersion()) {
    throw std::runtime_error("RollBackSchema knows schema " + std::to_string(kUndo.begin()->first) +
                             ", the store has " +
                             std::to_string(server::JobStore::SchemaVersion()) +
                             ": add the new schema's undo to store_fixtures.cc");
  }
  std::string sql;
  for (const auto& [added, undo] : kUndo) {
    if (added > version) sql += undo;
  }
  sql += "UPDATE schema_version SET version = " + std::to_string(version) + ";";
  ExecuteOnStore(path, sql, "rolling " + path + " back to schema " + std::to_string(version));
}

void ExecuteOnStore(const std::string& path, const std::string& sql, const std::string& what) {
  sqlite3* db = nullptr;
  if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) {
    const std::string message = db ? sqlite3_errmsg(db) : "cannot open";
    sqlite3_close(db);
    throw std::runtime_error(path + ": " + message);
  }
  char* error = nullptr;
  if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string message = error ? error : "unknown";
    sqlite3_free(error);
    sqlite3_close(db);
    throw std::runtime_error(what + ": " + message);
  }
  sqlite3_close(db);
}

}  // namespace dlmfd::testing
