// Test support for the store's tests (real SQLite): a job and a study to insert, and a store file
// brought back to an older schema, as an older daemon left it, so that a test can open it with
// this daemon's JobStore and check the migrations that follow.
#pragma once

#include <string>

#include "job_store.h"

namespace dlmfd::testing {

// A queued job of `owner` with a placeholder scene, its results under /tmp/ID.
server::JobRecord StoreJob(const std::string& id, const std::string& study = "", int priority = 0,
                           const std::string& owner = "local");

// A study of "local" with at most max_running jobs at once (0: no limit), nothing else set.
server::StudyRecord StoreStudy(const std::string& id, int max_running);

// Undoes, newest first, every migration of job_store.cc above `version` (its columns and tables
// dropped) in the store file at `path`, and sets its schema_version; the rows stay. Throws
// std::runtime_error with SQLite's message when a statement fails. A new schema adds its undo
// here.
void RollBackSchema(const std::string& path, int version);

// Runs the SQL statements on the store file at `path` (a test that edits what a daemon left);
// throws std::runtime_error with SQLite's message, prefixed by `what`, when one fails.
void ExecuteOnStore(const std::string& path, const std::string& sql, const std::string& what);

}  // namespace dlmfd::testing
