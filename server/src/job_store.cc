#include "job_store.h"

#include <sqlite3.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace dlmfd::server {
namespace {

// Ordered migrations: each brings the schema to its version from the one before (a version that a
// branch does not have is skipped: "if version < N apply it, set N"). Append, never edit.
struct Migration {
  int version;
  const char* sql;
};
const Migration kMigrations[] = {
    {1, R"sql(
    CREATE TABLE jobs (
      ordinal INTEGER PRIMARY KEY AUTOINCREMENT,
      id TEXT NOT NULL UNIQUE,
      name TEXT NOT NULL,
      owner TEXT NOT NULL,
      state INTEGER NOT NULL,
      reason TEXT NOT NULL DEFAULT '',
      priority INTEGER NOT NULL DEFAULT 0,
      sweep_id TEXT NOT NULL DEFAULT '',
      created_time REAL NOT NULL DEFAULT 0,
      started_time REAL NOT NULL DEFAULT 0,
      finished_time REAL NOT NULL DEFAULT 0,
      step INTEGER NOT NULL DEFAULT 0,
      time REAL NOT NULL DEFAULT 0,
      end_time REAL NOT NULL DEFAULT 0,
      attempts INTEGER NOT NULL DEFAULT 0,
      results_dir TEXT NOT NULL,
      scene TEXT NOT NULL,
      overrides TEXT NOT NULL DEFAULT '',
      client_request_id TEXT NOT NULL DEFAULT '',
      last_seq INTEGER NOT NULL DEFAULT 0,
      cancel_requested INTEGER NOT NULL DEFAULT 0);
    CREATE INDEX jobs_queue ON jobs (state, priority DESC, ordinal);
    CREATE INDEX jobs_owner ON jobs (owner, ordinal DESC);
    CREATE INDEX jobs_sweep ON jobs (owner, sweep_id);
    CREATE TABLE job_tags (
      job_id TEXT NOT NULL,
      tag TEXT NOT NULL,
      PRIMARY KEY (job_id, tag));
    CREATE INDEX job_tags_tag ON job_tags (tag);
    CREATE TABLE requests (
      owner TEXT NOT NULL,
      request_key TEXT NOT NULL,
      job_ids TEXT NOT NULL,
      PRIMARY KEY (owner, request_key));
    )sql"},
    // Schema 2: the accuracy warnings of a job's scene, one per line (EncodeWarnings).
    {2, R"sql(
    ALTER TABLE jobs ADD COLUMN warnings TEXT NOT NULL DEFAULT '';
    )sql"},
    // Schema 4: a queued job held from starting, and the bytes of a finished job's directory
    // (the disk quota).
    {4, R"sql(
    ALTER TABLE jobs ADD COLUMN held INTEGER NOT NULL DEFAULT 0;
    ALTER TABLE jobs ADD COLUMN disk_bytes INTEGER NOT NULL DEFAULT 0;
    )sql"},
};

const char kColumns[] =
    "ordinal, id, name, owner, state, reason, priority, sweep_id, created_time, started_time, "
    "finished_time, step, time, end_time, attempts, results_dir, scene, overrides, "
    "client_request_id, last_seq, cancel_requested, warnings, held, disk_bytes";

std::string Join(const std::vector<std::string>& parts, char sep) {
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) {
    if (i) out += sep;
    out += parts[i];
  }
  return out;
}

std::vector<std::string> Split(const std::string& text, char sep) {
  std::vector<std::string> out;
  if (text.empty()) return out;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, sep)) out.push_back(part);
  return out;
}

// One warning per line, its fields separated by tabs (the engine writes neither into a field); the
// value with 17 digits, so it reads back as the same double.
std::string EncodeWarnings(const std::vector<AccuracyWarning>& warnings) {
  std::vector<std::string> lines;
  for (const AccuracyWarning& w : warnings) {
    char value[40];
    std::snprintf(value, sizeof value, "%.17g", w.value);
    lines.push_back(
        Join({w.setting, value, w.allowed, w.key, w.current, w.suggested, w.source}, '\t'));
  }
  return Join(lines, '\n');
}

std::vector<AccuracyWarning> DecodeWarnings(const std::string& text) {
  std::vector<AccuracyWarning> out;
  for (const std::string& line : Split(text, '\n')) {
    std::vector<std::string> f = Split(line, '\t');
    if (f.size() != 7) {
      throw StoreError("jobs.warnings: a line with " + std::to_string(f.size()) +
                       " fields instead of 7");
    }
    AccuracyWarning w;
    w.setting = f[0];
    w.value = std::strtod(f[1].c_str(), nullptr);
    w.allowed = f[2];
    w.key = f[3];
    w.current = f[4];
    w.suggested = f[5];
    w.source = f[6];
    out.push_back(std::move(w));
  }
  return out;
}

}  // namespace

bool IsFinished(JobState state) {
  return state == JobState::kCompleted || state == JobState::kFailed ||
         state == JobState::kCancelled;
}

const char* JobStateName(JobState state) {
  switch (state) {
    case JobState::kQueued:
      return "QUEUED";
    case JobState::kRunning:
      return "RUNNING";
    case JobState::kCompleted:
      return "COMPLETED";
    case JobState::kFailed:
      return "FAILED";
    case JobState::kCancelled:
      return "CANCELLED";
  }
  return "UNKNOWN";
}

// A prepared statement with positional binding; finalised on destruction.
class JobStore::Statement {
 public:
  Statement(sqlite3* db, const std::string& sql)
      : db_(db) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK) {
      throw StoreError(std::string("prepare: ") + sqlite3_errmsg(db));
    }
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& Bind(const std::string& value) {
    Check(sqlite3_bind_text(stmt_, ++index_, value.data(), static_cast<int>(value.size()),
                            SQLITE_TRANSIENT));
    return *this;
  }
  Statement& Bind(int64_t value) {
    Check(sqlite3_bind_int64(stmt_, ++index_, value));
    return *this;
  }
  Statement& Bind(int value) { return Bind(static_cast<int64_t>(value)); }
  Statement& Bind(double value) {
    Check(sqlite3_bind_double(stmt_, ++index_, value));
    return *this;
  }
  // True while a row is available.
  bool Step() {
    int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw StoreError(std::string("step: ") + sqlite3_errmsg(db_));
  }
  void Run() {
    while (Step()) {}
  }
  int64_t Int(int col) const { return sqlite3_column_int64(stmt_, col); }
  double Real(int col) const { return sqlite3_column_double(stmt_, col); }
  std::string Text(int col) const {
    const unsigned char* text = sqlite3_column_text(stmt_, col);
    return text ? std::string(reinterpret_cast<const char*>(text),
                              static_cast<size_t>(sqlite3_column_bytes(stmt_, col)))
                : std::string();
  }
  int Changes() const { return sqlite3_changes(db_); }

 private:
  void Check(int rc) {
    if (rc != SQLITE_OK) throw StoreError(std::string("bind: ") + sqlite3_errmsg(db_));
  }
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
  int index_ = 0;
};

namespace {

// BEGIN IMMEDIATE ... COMMIT, rolled back if not committed.
class Transaction {
 public:
  explicit Transaction(sqlite3* db)
      : db_(db) {
    Exec("BEGIN IMMEDIATE");
  }
  ~Transaction() {
    if (!done_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  void Commit() {
    Exec("COMMIT");
    done_ = true;
  }

 private:
  void Exec(const char* sql) {
    char* message = nullptr;
    if (sqlite3_exec(db_, sql, nullptr, nullptr, &message) != SQLITE_OK) {
      std::string text = message ? message : "unknown";
      sqlite3_free(message);
      throw StoreError(std::string(sql) + ": " + text);
    }
  }
  sqlite3* db_;
  bool done_ = false;
};

}  // namespace

JobStore::JobStore(const std::string& path) {
  if (sqlite3_open_v2(path.c_str(), &db_,
                      SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX,
                      nullptr) != SQLITE_OK) {
    std::string message = db_ ? sqlite3_errmsg(db_) : "cannot allocate";
    sqlite3_close(db_);
    db_ = nullptr;
    throw StoreError("cannot open " + path + ": " + message);
  }
  try {
    sqlite3_busy_timeout(db_, 5000);
    Exec("PRAGMA journal_mode=WAL");
    Exec("PRAGMA synchronous=NORMAL");
    Exec("PRAGMA foreign_keys=ON");
    Migrate();
  } catch (...) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw;
  }
}

JobStore::~JobStore() { sqlite3_close(db_); }

int JobStore::SchemaVersion() { return std::end(kMigrations)[-1].version; }

void JobStore::Exec(const char* sql) {
  char* message = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &message) != SQLITE_OK) {
    std::string text = message ? message : "unknown";
    sqlite3_free(message);
    throw StoreError(text);
  }
}

void JobStore::Migrate() {
  Exec("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)");
  Transaction transaction(db_);
  int64_t version = 0;
  {
    Statement select(db_, "SELECT version FROM schema_version");
    if (select.Step()) {
      version = select.Int(0);
    } else {
      Statement(db_, "INSERT INTO schema_version (version) VALUES (0)").Run();
    }
  }
  if (version > SchemaVersion()) {
    throw StoreError("jobs.db has schema version " + std::to_string(version) +
                     ", newer than this daemon's " + std::to_string(SchemaVersion()));
  }
  for (const Migration& migration : kMigrations) {
    if (version >= migration.version) continue;
    Exec(migration.sql);
    version = migration.version;
    Statement(db_, "UPDATE schema_version SET version = ?").Bind(version).Run();
  }
  transaction.Commit();
}

std::vector<JobRecord> JobStore::Query(Statement& statement) {
  std::vector<JobRecord> jobs;
  while (statement.Step()) {
    JobRecord job;
    int c = 0;
    job.ordinal = statement.Int(c++);
    job.id = statement.Text(c++);
    job.name = statement.Text(c++);
    job.owner = statement.Text(c++);
    job.state = static_cast<JobState>(statement.Int(c++));
    job.reason = statement.Text(c++);
    job.priority = static_cast<int>(statement.Int(c++));
    job.sweep_id = statement.Text(c++);
    job.created_time = statement.Real(c++);
    job.started_time = statement.Real(c++);
    job.finished_time = statement.Real(c++);
    job.step = statement.Int(c++);
    job.time = statement.Real(c++);
    job.end_time = statement.Real(c++);
    job.attempts = static_cast<int>(statement.Int(c++));
    job.results_dir = statement.Text(c++);
    job.scene = statement.Text(c++);
    job.overrides = Split(statement.Text(c++), '\n');
    job.client_request_id = statement.Text(c++);
    job.last_seq = statement.Int(c++);
    job.cancel_requested = statement.Int(c++) != 0;
    job.warnings = DecodeWarnings(statement.Text(c++));
    job.held = statement.Int(c++) != 0;
    job.disk_bytes = statement.Int(c++);
    jobs.push_back(std::move(job));
  }
  for (auto& job : jobs) LoadTags(job);
  return jobs;
}

void JobStore::LoadTags(JobRecord& job) {
  Statement select(db_, "SELECT tag FROM job_tags WHERE job_id = ? ORDER BY rowid");
  select.Bind(job.id);
  job.tags.clear();
  while (select.Step()) job.tags.push_back(select.Text(0));
}

JobStore::InsertResult JobStore::InsertJobs(std::vector<JobRecord> jobs, const std::string& owner,
                                            const std::string& request_key) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  InsertResult result;
  if (!request_key.empty()) {
    Statement select(db_, "SELECT job_ids FROM requests WHERE owner = ? AND request_key = ?");
    select.Bind(owner).Bind(request_key);
    if (select.Step()) {
      for (const auto& id : Split(select.Text(0), ',')) {
        Statement get(db_, std::string("SELECT ") + kColumns + " FROM jobs WHERE id = ?");
        get.Bind(id);
        for (auto& job : Query(get)) result.jobs.push_back(std::move(job));
      }
      result.existed = true;
      return result;
    }
  }
  std::vector<std::string> ids;
  for (auto& job : jobs) {
    Statement insert(db_,
                     "INSERT INTO jobs (id, name, owner, state, reason, priority, sweep_id, "
                     "created_time, end_time, results_dir, scene, overrides, client_request_id, "
                     "warnings) VALUES (?, ?, ?, ?, '', ?, ?, ?, ?, ?, ?, ?, ?, ?)");
    insert.Bind(job.id)
        .Bind(job.name)
        .Bind(job.owner)
        .Bind(static_cast<int>(job.state))
        .Bind(job.priority)
        .Bind(job.sweep_id)
        .Bind(job.created_time)
        .Bind(job.end_time)
        .Bind(job.results_dir)
        .Bind(job.scene)
        .Bind(Join(job.overrides, '\n'))
        .Bind(job.client_request_id)
        .Bind(EncodeWarnings(job.warnings));
    insert.Run();
    job.ordinal = sqlite3_last_insert_rowid(db_);
    for (const auto& tag : job.tags) {
      Statement tag_insert(db_, "INSERT OR IGNORE INTO job_tags (job_id, tag) VALUES (?, ?)");
      tag_insert.Bind(job.id).Bind(tag).Run();
    }
    ids.push_back(job.id);
  }
  if (!request_key.empty()) {
    Statement insert(db_, "INSERT INTO requests (owner, request_key, job_ids) VALUES (?, ?, ?)");
    insert.Bind(owner).Bind(request_key).Bind(Join(ids, ',')).Run();
  }
  transaction.Commit();
  result.jobs = std::move(jobs);
  return result;
}

std::vector<JobRecord> JobStore::FindRequest(const std::string& owner,
                                             const std::string& request_key) {
  std::lock_guard lock(mutex_);
  std::vector<JobRecord> jobs;
  Statement select(db_, "SELECT job_ids FROM requests WHERE owner = ? AND request_key = ?");
  select.Bind(owner).Bind(request_key);
  if (!select.Step()) return jobs;
  for (const auto& id : Split(select.Text(0), ',')) {
    Statement get(db_, std::string("SELECT ") + kColumns + " FROM jobs WHERE id = ?");
    get.Bind(id);
    for (auto& job : Query(get)) jobs.push_back(std::move(job));
  }
  return jobs;
}

std::optional<JobRecord> JobStore::Get(const std::string& id) {
  std::lock_guard lock(mutex_);
  Statement select(db_, std::string("SELECT ") + kColumns + " FROM jobs WHERE id = ?");
  select.Bind(id);
  auto jobs = Query(select);
  if (jobs.empty()) return std::nullopt;
  return std::move(jobs.front());
}

std::vector<JobRecord> JobStore::List(const ListFilter& filter) {
  std::lock_guard lock(mutex_);
  std::string sql = std::string("SELECT ") + kColumns + " FROM jobs WHERE owner = ?";
  if (!filter.states.empty()) {
    sql += " AND state IN (";
    for (size_t i = 0; i < filter.states.size(); ++i) sql += i ? ", ?" : "?";
    sql += ")";
  }
  if (!filter.tag.empty()) sql += " AND id IN (SELECT job_id FROM job_tags WHERE tag = ?)";
  if (!filter.sweep_id.empty()) sql += " AND sweep_id = ?";
  if (filter.before_ordinal > 0) sql += " AND ordinal < ?";
  sql += " ORDER BY ordinal DESC LIMIT ?";
  Statement select(db_, sql);
  select.Bind(filter.owner);
  for (JobState state : filter.states) select.Bind(static_cast<int>(state));
  if (!filter.tag.empty()) select.Bind(filter.tag);
  if (!filter.sweep_id.empty()) select.Bind(filter.sweep_id);
  if (filter.before_ordinal > 0) select.Bind(filter.before_ordinal);
  select.Bind(filter.limit);
  return Query(select);
}

int64_t JobStore::CountUnfinished() {
  std::lock_guard lock(mutex_);
  Statement select(db_, "SELECT COUNT(*) FROM jobs WHERE state IN (?, ?)");
  select.Bind(static_cast<int>(JobState::kQueued)).Bind(static_cast<int>(JobState::kRunning));
  select.Step();
  return select.Int(0);
}

int JobStore::CountRunning() {
  std::lock_guard lock(mutex_);
  Statement select(db_, "SELECT COUNT(*) FROM jobs WHERE state = ?");
  select.Bind(static_cast<int>(JobState::kRunning));
  select.Step();
  return static_cast<int>(select.Int(0));
}

std::vector<JobRecord> JobStore::SweepJobs(const std::string& owner, const std::string& sweep_id) {
  std::lock_guard lock(mutex_);
  Statement select(db_, std::string("SELECT ") + kColumns +
                            " FROM jobs WHERE owner = ? AND sweep_id = ? ORDER BY ordinal");
  select.Bind(owner).Bind(sweep_id);
  return Query(select);
}

std::optional<JobRecord> JobStore::NextQueued() {
  std::lock_guard lock(mutex_);
  Statement select(
      db_, std::string("SELECT ") + kColumns +
               " FROM jobs WHERE state = ? AND held = 0 ORDER BY priority DESC, ordinal LIMIT 1");
  select.Bind(static_cast<int>(JobState::kQueued));
  auto jobs = Query(select);
  if (jobs.empty()) return std::nullopt;
  return std::move(jobs.front());
}

void JobStore::MarkRunning(const std::string& id, double started_time) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  Statement update(db_,
                   "UPDATE jobs SET state = ?, started_time = ?, attempts = attempts + 1, "
                   "reason = '' WHERE id = ? AND state = ?");
  update.Bind(static_cast<int>(JobState::kRunning))
      .Bind(started_time)
      .Bind(id)
      .Bind(static_cast<int>(JobState::kQueued));
  update.Run();
  if (update.Changes() != 1) throw StoreError("job " + id + " is not queued");
  transaction.Commit();
}

bool JobStore::MarkFinished(const std::string& id, JobState state, const std::string& reason,
                            double when) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  Statement update(db_,
                   "UPDATE jobs SET state = ?, reason = ?, finished_time = ? "
                   "WHERE id = ? AND state IN (?, ?)");
  update.Bind(static_cast<int>(state))
      .Bind(reason)
      .Bind(when)
      .Bind(id)
      .Bind(static_cast<int>(JobState::kQueued))
      .Bind(static_cast<int>(JobState::kRunning));
  update.Run();
  bool changed = update.Changes() == 1;
  transaction.Commit();
  return changed;
}

bool JobStore::CancelQueued(const std::string& id, const std::string& reason, double when) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  Statement update(db_,
                   "UPDATE jobs SET state = ?, reason = ?, finished_time = ?, cancel_requested = 1 "
                   "WHERE id = ? AND state = ?");
  update.Bind(static_cast<int>(JobState::kCancelled))
      .Bind(reason)
      .Bind(when)
      .Bind(id)
      .Bind(static_cast<int>(JobState::kQueued));
  update.Run();
  bool changed = update.Changes() == 1;
  transaction.Commit();
  return changed;
}

void JobStore::SetCancelRequested(const std::string& id) {
  std::lock_guard lock(mutex_);
  Statement(db_, "UPDATE jobs SET cancel_requested = 1 WHERE id = ?").Bind(id).Run();
}

void JobStore::UpdateProgress(const std::string& id, int64_t step, double time, double end_time) {
  std::lock_guard lock(mutex_);
  Statement update(db_, "UPDATE jobs SET step = ?, time = ?, end_time = ? WHERE id = ?");
  update.Bind(step).Bind(time).Bind(end_time).Bind(id).Run();
}

void JobStore::SetLastSeq(const std::string& id, int64_t last_seq) {
  std::lock_guard lock(mutex_);
  Statement(db_, "UPDATE jobs SET last_seq = ? WHERE id = ?").Bind(last_seq).Bind(id).Run();
}

std::vector<std::string> JobStore::RequeueRunning(double now) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  std::vector<std::string> ids;
  {
    Statement select(
        db_, "SELECT id FROM jobs WHERE state = ? AND cancel_requested = 0 ORDER BY ordinal");
    select.Bind(static_cast<int>(JobState::kRunning));
    while (select.Step()) ids.push_back(select.Text(0));
  }
  {
    // A cancel that was requested before the crash is honoured: the job does not run again.
    Statement cancel(db_,
                     "UPDATE jobs SET state = ?, reason = 'cancelled', finished_time = ? "
                     "WHERE state = ? AND cancel_requested = 1");
    cancel.Bind(static_cast<int>(JobState::kCancelled))
        .Bind(now)
        .Bind(static_cast<int>(JobState::kRunning))
        .Run();
  }
  Statement update(db_, "UPDATE jobs SET state = ?, reason = 'daemon restarted' WHERE state = ?");
  update.Bind(static_cast<int>(JobState::kQueued)).Bind(static_cast<int>(JobState::kRunning)).Run();
  transaction.Commit();
  return ids;
}

bool JobStore::SetHeld(const std::string& id, bool held) {
  std::lock_guard lock(mutex_);
  Statement update(db_, "UPDATE jobs SET held = ? WHERE id = ? AND state = ?");
  update.Bind(held ? 1 : 0).Bind(id).Bind(static_cast<int>(JobState::kQueued)).Run();
  return update.Changes() == 1;
}

bool JobStore::SetPriority(const std::string& id, int priority) {
  std::lock_guard lock(mutex_);
  Statement update(db_, "UPDATE jobs SET priority = ? WHERE id = ? AND state IN (?, ?)");
  update.Bind(priority)
      .Bind(id)
      .Bind(static_cast<int>(JobState::kQueued))
      .Bind(static_cast<int>(JobState::kRunning))
      .Run();
  return update.Changes() == 1;
}

void JobStore::SetDiskBytes(const std::string& id, int64_t bytes) {
  std::lock_guard lock(mutex_);
  Statement(db_, "UPDATE jobs SET disk_bytes = ? WHERE id = ?").Bind(bytes).Bind(id).Run();
}

void JobStore::Delete(const std::vector<std::string>& ids) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  for (const std::string& id : ids) {
    Statement(db_, "DELETE FROM job_tags WHERE job_id = ?").Bind(id).Run();
    Statement(db_, "DELETE FROM jobs WHERE id = ?").Bind(id).Run();
  }
  // A request keeps the jobs it made that still exist; one with none left is forgotten, so that
  // its client_request_id makes new jobs rather than answer with deleted ones.
  std::vector<std::pair<int64_t, std::string>> requests;
  {
    Statement select(db_, "SELECT rowid, job_ids FROM requests");
    while (select.Step()) requests.emplace_back(select.Int(0), select.Text(1));
  }
  for (const auto& [rowid, job_ids] : requests) {
    std::vector<std::string> kept;
    for (const std::string& id : Split(job_ids, ',')) {
      if (std::find(ids.begin(), ids.end(), id) == ids.end()) kept.push_back(id);
    }
    if (kept.size() == Split(job_ids, ',').size()) continue;
    if (kept.empty()) {
      Statement(db_, "DELETE FROM requests WHERE rowid = ?").Bind(rowid).Run();
    } else {
      Statement(db_, "UPDATE requests SET job_ids = ? WHERE rowid = ?")
          .Bind(Join(kept, ','))
          .Bind(rowid)
          .Run();
    }
  }
  transaction.Commit();
}

std::vector<JobRecord> JobStore::OwnerJobs(const std::string& owner) {
  std::lock_guard lock(mutex_);
  Statement select(
      db_, std::string("SELECT ") + kColumns + " FROM jobs WHERE owner = ? ORDER BY ordinal");
  select.Bind(owner);
  return Query(select);
}

}  // namespace dlmfd::server
