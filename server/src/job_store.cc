#include "job_store.h"

#include <sqlite3.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <set>
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
    // Schema 3: studies as objects, labels, the effective scene's values, retries. Sweeps of
    // schema 2 become rows of their own (no axes recorded).
    {3, R"sql(
    CREATE TABLE sweeps (
      ordinal INTEGER PRIMARY KEY AUTOINCREMENT,
      id TEXT NOT NULL UNIQUE,
      owner TEXT NOT NULL,
      name TEXT NOT NULL DEFAULT '',
      tags TEXT NOT NULL DEFAULT '',
      labels TEXT NOT NULL DEFAULT '',
      axes TEXT NOT NULL DEFAULT '',
      overrides TEXT NOT NULL DEFAULT '',
      max_running INTEGER NOT NULL DEFAULT 0,
      created_time REAL NOT NULL DEFAULT 0);
    CREATE INDEX sweeps_owner ON sweeps (owner, ordinal DESC);
    INSERT INTO sweeps (id, owner, created_time)
      SELECT sweep_id, owner, MIN(created_time) FROM jobs WHERE sweep_id != ''
      GROUP BY sweep_id, owner ORDER BY MIN(ordinal);
    CREATE TABLE job_labels (
      job_id TEXT NOT NULL,
      key TEXT NOT NULL,
      value TEXT NOT NULL,
      PRIMARY KEY (job_id, key));
    CREATE INDEX job_labels_key ON job_labels (key, value);
    CREATE TABLE job_values (
      job_id TEXT NOT NULL,
      key TEXT NOT NULL,
      value TEXT NOT NULL,
      PRIMARY KEY (job_id, key));
    CREATE INDEX job_values_key ON job_values (key, value);
    ALTER TABLE jobs ADD COLUMN parameters TEXT NOT NULL DEFAULT '';
    ALTER TABLE jobs ADD COLUMN attempt INTEGER NOT NULL DEFAULT 1;
    ALTER TABLE jobs ADD COLUMN previous_attempts TEXT NOT NULL DEFAULT '';
    ALTER TABLE jobs ADD COLUMN fresh_start INTEGER NOT NULL DEFAULT 0;
    )sql"},
    // Schema 4: a queued job held from starting, and the bytes of a finished job's directory
    // (the disk quota).
    {4, R"sql(
    ALTER TABLE jobs ADD COLUMN held INTEGER NOT NULL DEFAULT 0;
    ALTER TABLE jobs ADD COLUMN disk_bytes INTEGER NOT NULL DEFAULT 0;
    )sql"},
    // Schema 5: the slurm executor's record of a job (docs/cluster.md): the Slurm id of its latest
    // attempt, whether that Slurm job's end is still to be recorded (the next start adopts it),
    // its attempts in Slurm since it was submitted or retried (slurm_max_attempts) and Slurm's
    // restart count of the current Slurm job already recorded as attempts.
    {5, R"sql(
    ALTER TABLE jobs ADD COLUMN slurm_job_id TEXT NOT NULL DEFAULT '';
    ALTER TABLE jobs ADD COLUMN slurm_live INTEGER NOT NULL DEFAULT 0;
    ALTER TABLE jobs ADD COLUMN slurm_attempts INTEGER NOT NULL DEFAULT 0;
    ALTER TABLE jobs ADD COLUMN slurm_restarts INTEGER NOT NULL DEFAULT 0;
    )sql"},
    // Schema 6: Slurm's state and reason of a job's live Slurm job as last seen and whether Slurm
    // holds it waiting (the API shows such a job QUEUED), and the job's own wall-time limit.
    {6, R"sql(
    ALTER TABLE jobs ADD COLUMN slurm_state TEXT NOT NULL DEFAULT '';
    ALTER TABLE jobs ADD COLUMN slurm_reason TEXT NOT NULL DEFAULT '';
    ALTER TABLE jobs ADD COLUMN slurm_waiting INTEGER NOT NULL DEFAULT 0;
    ALTER TABLE jobs ADD COLUMN time_limit_seconds INTEGER NOT NULL DEFAULT 0;
    )sql"},
    // Schema 7: what each "auto" of a job's scene became at admission (EncodeNumerics).
    {7, R"sql(
    ALTER TABLE jobs ADD COLUMN numerics TEXT NOT NULL DEFAULT '';
    )sql"},
    // Schema 8: job dependencies (afterok): a job runs only once every job it names has
    // COMPLETED (NextQueued); one that ends otherwise, or is deleted, cancels it (Blocked).
    {8, R"sql(
    CREATE TABLE job_dependencies (
      job_id TEXT NOT NULL,
      after_id TEXT NOT NULL,
      PRIMARY KEY (job_id, after_id));
    CREATE INDEX job_dependencies_after ON job_dependencies (after_id);
    )sql"},
    // Schema 9: accounting of the current attempt (sacct's ExitCode, TotalCPU, MaxRSS): the exit
    // status of its latest solver run (-1: none yet, or a signal ended it), that signal, the CPU
    // seconds of its runs added up and the largest peak resident set of one run (RecordUsage).
    {9, R"sql(
    ALTER TABLE jobs ADD COLUMN exit_code INTEGER NOT NULL DEFAULT -1;
    ALTER TABLE jobs ADD COLUMN exit_signal INTEGER NOT NULL DEFAULT 0;
    ALTER TABLE jobs ADD COLUMN cpu_seconds REAL NOT NULL DEFAULT 0;
    ALTER TABLE jobs ADD COLUMN peak_memory_bytes INTEGER NOT NULL DEFAULT 0;
    )sql"},
    // Schema 10: the slurm executor's record of a job (schemas 5 and 6) in a table of its own, a
    // row for each job that was handed to Slurm since it was submitted or retried; the jobs
    // table keeps what every executor shares. Rows of schema 9 move with their values.
    {10, R"sql(
    CREATE TABLE slurm_jobs (
      job_id TEXT PRIMARY KEY REFERENCES jobs (id) ON DELETE CASCADE,
      slurm_job_id TEXT NOT NULL DEFAULT '',
      live INTEGER NOT NULL DEFAULT 0,
      attempts INTEGER NOT NULL DEFAULT 0,
      restarts INTEGER NOT NULL DEFAULT 0,
      state TEXT NOT NULL DEFAULT '',
      reason TEXT NOT NULL DEFAULT '',
      waiting INTEGER NOT NULL DEFAULT 0);
    INSERT INTO slurm_jobs (job_id, slurm_job_id, live, attempts, restarts, state, reason, waiting)
      SELECT id, slurm_job_id, slurm_live, slurm_attempts, slurm_restarts, slurm_state,
             slurm_reason, slurm_waiting FROM jobs
      WHERE slurm_job_id != '' OR slurm_live != 0 OR slurm_attempts != 0 OR slurm_waiting != 0;
    ALTER TABLE jobs DROP COLUMN slurm_job_id;
    ALTER TABLE jobs DROP COLUMN slurm_live;
    ALTER TABLE jobs DROP COLUMN slurm_attempts;
    ALTER TABLE jobs DROP COLUMN slurm_restarts;
    ALTER TABLE jobs DROP COLUMN slurm_state;
    ALTER TABLE jobs DROP COLUMN slurm_reason;
    ALTER TABLE jobs DROP COLUMN slurm_waiting;
    )sql"},
    // Schema 11: one word for one concept (issue 39 point 5): the table of studies and a job's
    // study column take the name users see (`dlmfd study`); rows keep their values.
    {11, R"sql(
    ALTER TABLE sweeps RENAME TO studies;
    ALTER TABLE jobs RENAME COLUMN sweep_id TO study_id;
    DROP INDEX IF EXISTS sweeps_owner;
    CREATE INDEX studies_owner ON studies (owner, ordinal DESC);
    DROP INDEX IF EXISTS jobs_sweep;
    CREATE INDEX jobs_study ON jobs (owner, study_id);
    )sql"},
};

// A job's row as the store reads it: the jobs table with its Slurm record (schema 10), under the
// column names of schemas 5 and 6; a job never handed to Slurm reads the defaults.
const char kJobRows[] =
    "(SELECT jobs.*, COALESCE(s.slurm_job_id, '') AS slurm_job_id, "
    "COALESCE(s.live, 0) AS slurm_live, COALESCE(s.attempts, 0) AS slurm_attempts, "
    "COALESCE(s.restarts, 0) AS slurm_restarts, COALESCE(s.state, '') AS slurm_state, "
    "COALESCE(s.reason, '') AS slurm_reason, COALESCE(s.waiting, 0) AS slurm_waiting "
    "FROM jobs LEFT JOIN slurm_jobs s ON s.job_id = jobs.id)";

// SQL true for the job named `job` whose Slurm job is live (submitted, its end not recorded).
std::string SlurmLive(const std::string& job) {
  return "EXISTS (SELECT 1 FROM slurm_jobs s WHERE s.job_id = " + job + ".id AND s.live = 1)";
}

// SQL true for a job j whose dependencies have not all COMPLETED (a missing one never will).
std::string WaitsForDependency() {
  return "EXISTS (SELECT 1 FROM job_dependencies d LEFT JOIN jobs p ON p.id = d.after_id "
         "WHERE d.job_id = j.id AND (p.state IS NULL OR p.state != " +
         std::to_string(static_cast<int>(JobState::kCompleted)) + "))";
}

// The state the API shows: a RUNNING job that Slurm holds waiting is QUEUED (ShownState).
const std::string kShownState =
    "(CASE WHEN state = " + std::to_string(static_cast<int>(JobState::kRunning)) +
    " AND slurm_waiting = 1 THEN " + std::to_string(static_cast<int>(JobState::kQueued)) +
    " ELSE state END)";

const char kColumns[] =
    "ordinal, id, name, owner, state, reason, priority, study_id, created_time, started_time, "
    "finished_time, step, time, end_time, attempts, results_dir, scene, overrides, "
    "client_request_id, last_seq, cancel_requested, warnings, held, disk_bytes, parameters, "
    "attempt, previous_attempts, fresh_start, slurm_job_id, slurm_live, slurm_attempts, "
    "slurm_restarts, slurm_state, slurm_reason, slurm_waiting, time_limit_seconds, numerics, "
    "exit_code, exit_signal, cpu_seconds, peak_memory_bytes";

// SELECT of kColumns from kJobRows under the name `as`.
std::string SelectJobs(const std::string& as = "jobs") {
  return std::string("SELECT ") + kColumns + " FROM " + kJobRows + " " + as;
}

const char kStudyColumns[] =
    "ordinal, id, owner, name, tags, labels, axes, overrides, max_running, created_time";

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

// One choice per line: key, value, rule and the numbers, fields separated by tabs, the numbers as
// name=value pairs separated by semicolons (the engine writes none of these characters into them),
// each value with 17 digits.
std::string EncodeNumerics(const std::vector<ResolvedChoice>& choices) {
  std::vector<std::string> lines;
  for (const ResolvedChoice& c : choices) {
    std::vector<std::string> numbers;
    for (const auto& [name, value] : c.numbers) {
      char text[40];
      std::snprintf(text, sizeof text, "%.17g", value);
      numbers.push_back(name + "=" + text);
    }
    lines.push_back(Join({c.key, c.value, c.rule, Join(numbers, ';')}, '\t'));
  }
  return Join(lines, '\n');
}

std::vector<ResolvedChoice> DecodeNumerics(const std::string& text) {
  std::vector<ResolvedChoice> out;
  for (const std::string& line : Split(text, '\n')) {
    const std::vector<std::string> f = Split(line, '\t');
    if (f.size() != 3 && f.size() != 4) {
      throw StoreError("jobs.numerics: a line with " + std::to_string(f.size()) +
                       " fields instead of 4");
    }
    ResolvedChoice c{f[0], f[1], f[2], {}};
    if (f.size() == 4) {
      for (const std::string& pair : Split(f[3], ';')) {
        const auto eq = pair.rfind('=');
        if (eq == std::string::npos) throw StoreError("jobs.numerics: a number without '='");
        c.numbers.emplace_back(pair.substr(0, eq), std::strtod(pair.c_str() + eq + 1, nullptr));
      }
    }
    out.push_back(std::move(c));
  }
  return out;
}

// Records of fields for the columns of schema 3: fields joined by tabs, records by line breaks,
// with backslash, tab and line break escaped inside a field, so any text reads back as written.
std::string EscapeField(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\\') {
      out += "\\\\";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\n') {
      out += "\\n";
    } else {
      out += c;
    }
  }
  return out;
}

std::string UnescapeField(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\\' && i + 1 < text.size()) {
      const char c = text[++i];
      out += c == 't' ? '\t' : c == 'n' ? '\n' : c;
    } else {
      out += text[i];
    }
  }
  return out;
}

std::string EncodeRecords(const std::vector<std::vector<std::string>>& records) {
  std::vector<std::string> lines;
  for (const auto& fields : records) {
    std::vector<std::string> escaped;
    for (const auto& f : fields) escaped.push_back(EscapeField(f));
    lines.push_back(Join(escaped, '\t'));
  }
  return Join(lines, '\n');
}

std::vector<std::vector<std::string>> DecodeRecords(const std::string& text, size_t min_fields,
                                                    const char* column) {
  std::vector<std::vector<std::string>> out;
  for (const std::string& line : Split(text, '\n')) {
    std::vector<std::string> fields;
    for (const std::string& f : Split(line, '\t')) fields.push_back(UnescapeField(f));
    if (line.empty() || line.back() == '\t') fields.emplace_back();  // a trailing empty field
    if (fields.size() < min_fields) {
      throw StoreError(std::string(column) + ": a record with " + std::to_string(fields.size()) +
                       " fields, expected at least " + std::to_string(min_fields));
    }
    out.push_back(std::move(fields));
  }
  return out;
}

std::string Exact(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

double ReadDouble(const std::string& text) { return std::strtod(text.c_str(), nullptr); }

std::string EncodeParameters(const std::vector<ParameterValue>& parameters) {
  std::vector<std::vector<std::string>> records;
  for (const auto& p : parameters) records.push_back({p.key, p.text, p.type, Exact(p.number)});
  return EncodeRecords(records);
}

std::vector<ParameterValue> DecodeParameters(const std::string& text) {
  std::vector<ParameterValue> out;
  for (const auto& f : DecodeRecords(text, 4, "jobs.parameters")) {
    out.push_back({f[0], f[1], f[2], ReadDouble(f[3])});
  }
  return out;
}

std::string EncodeAttempts(const std::vector<AttemptRecord>& attempts) {
  std::vector<std::vector<std::string>> records;
  for (const auto& a : attempts) {
    std::vector<std::string> fields = {std::to_string(a.attempt),
                                       std::to_string(static_cast<int>(a.state)),
                                       a.reason,
                                       Exact(a.started_time),
                                       Exact(a.finished_time),
                                       std::to_string(a.step),
                                       Exact(a.time)};
    fields.insert(fields.end(), a.overrides.begin(), a.overrides.end());
    records.push_back(std::move(fields));
  }
  return EncodeRecords(records);
}

std::vector<AttemptRecord> DecodeAttempts(const std::string& text) {
  std::vector<AttemptRecord> out;
  for (const auto& f : DecodeRecords(text, 7, "jobs.previous_attempts")) {
    AttemptRecord a;
    a.attempt = std::atoi(f[0].c_str());
    a.state = static_cast<JobState>(std::atoi(f[1].c_str()));
    a.reason = f[2];
    a.started_time = ReadDouble(f[3]);
    a.finished_time = ReadDouble(f[4]);
    a.step = std::atoll(f[5].c_str());
    a.time = ReadDouble(f[6]);
    for (size_t k = 7; k < f.size(); ++k) {
      if (!f[k].empty()) a.overrides.push_back(f[k]);
    }
    out.push_back(std::move(a));
  }
  return out;
}

std::string EncodeLabels(const std::map<std::string, std::string>& labels) {
  std::vector<std::vector<std::string>> records;
  for (const auto& [k, v] : labels) records.push_back({k, v});
  return EncodeRecords(records);
}

std::map<std::string, std::string> DecodeLabels(const std::string& text) {
  std::map<std::string, std::string> out;
  for (const auto& f : DecodeRecords(text, 2, "studies.labels")) out[f[0]] = f[1];
  return out;
}

// One axis per record: key, zip, range ("" or "lin"/"log"), start, stop, count, then the values.
std::string EncodeAxes(const std::vector<StoredAxis>& axes) {
  std::vector<std::vector<std::string>> records;
  for (const auto& a : axes) {
    std::vector<std::string> fields = {
        a.key,          a.zip,         a.is_range ? (a.logarithmic ? "log" : "lin") : "",
        Exact(a.start), Exact(a.stop), std::to_string(a.count)};
    fields.insert(fields.end(), a.values.begin(), a.values.end());
    records.push_back(std::move(fields));
  }
  return EncodeRecords(records);
}

std::vector<StoredAxis> DecodeAxes(const std::string& text) {
  std::vector<StoredAxis> out;
  for (const auto& f : DecodeRecords(text, 6, "studies.axes")) {
    StoredAxis a;
    a.key = f[0];
    a.zip = f[1];
    a.is_range = !f[2].empty();
    a.logarithmic = f[2] == "log";
    a.start = ReadDouble(f[3]);
    a.stop = ReadDouble(f[4]);
    a.count = std::atoi(f[5].c_str());
    a.values.assign(f.begin() + 6, f.end());
    out.push_back(std::move(a));
  }
  return out;
}

}  // namespace

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
  bool IsNull(int col) const { return sqlite3_column_type(stmt_, col) == SQLITE_NULL; }
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

// A scene key pattern as a GLOB: '*' matches any index; the key's other GLOB characters ('?',
// '[') are escaped as one-character classes.
std::string KeyGlob(const std::string& pattern) {
  std::string glob;
  for (char c : pattern) {
    if (c == '?' || c == '[') {
      glob += std::string("[") + c + "]";
    } else {
      glob += c;
    }
  }
  return glob;
}

// SQL scene_number(TEXT): a normalised scene value (scene_values.h: numbers as the shortest text
// that reads back, "inf", "-inf") as a number; NULL for any other value (a string, an array, a
// boolean), which no range then matches.
void SceneNumber(sqlite3_context* context, int, sqlite3_value** argv) {
  const unsigned char* text = sqlite3_value_text(argv[0]);
  if (text == nullptr || *text == '\0') {
    sqlite3_result_null(context);
    return;
  }
  const std::string value(reinterpret_cast<const char*>(text));
  const bool numeric_characters = value == "inf" || value == "-inf" ||
                                  value.find_first_not_of("0123456789.eE+-") == std::string::npos;
  char* end = nullptr;
  const double number = numeric_characters ? std::strtod(value.c_str(), &end) : 0;
  if (!numeric_characters || end != value.c_str() + value.size()) {
    sqlite3_result_null(context);
  } else {
    sqlite3_result_double(context, number);
  }
}

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
    if (sqlite3_create_function_v2(db_, "scene_number", 1, SQLITE_UTF8 | SQLITE_DETERMINISTIC,
                                   nullptr, SceneNumber, nullptr, nullptr, nullptr) != SQLITE_OK) {
      throw StoreError(std::string("scene_number: ") + sqlite3_errmsg(db_));
    }
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
    job.study_id = statement.Text(c++);
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
    job.parameters = DecodeParameters(statement.Text(c++));
    job.attempt = static_cast<int>(statement.Int(c++));
    job.previous_attempts = DecodeAttempts(statement.Text(c++));
    job.fresh_start = statement.Int(c++) != 0;
    job.slurm_job_id = statement.Text(c++);
    job.slurm_live = statement.Int(c++) != 0;
    job.slurm_attempts = static_cast<int>(statement.Int(c++));
    job.slurm_restarts = static_cast<int>(statement.Int(c++));
    job.slurm_state = statement.Text(c++);
    job.slurm_reason = statement.Text(c++);
    job.slurm_waiting = statement.Int(c++) != 0;
    job.time_limit_seconds = statement.Int(c++);
    job.numerics = DecodeNumerics(statement.Text(c++));
    job.exit_code = static_cast<int>(statement.Int(c++));
    job.exit_signal = static_cast<int>(statement.Int(c++));
    job.cpu_seconds = statement.Real(c++);
    job.peak_memory_bytes = statement.Int(c++);
    jobs.push_back(std::move(job));
  }
  for (auto& job : jobs) {
    LoadTags(job);
    LoadLabels(job);
    LoadDependencies(job);
  }
  return jobs;
}

void JobStore::LoadDependencies(JobRecord& job) {
  Statement select(db_,
                   "SELECT d.after_id, p.state FROM job_dependencies d LEFT JOIN jobs p "
                   "ON p.id = d.after_id WHERE d.job_id = ? ORDER BY d.rowid");
  select.Bind(job.id);
  job.after.clear();
  std::string waiting_for;
  while (select.Step()) {
    job.after.push_back(select.Text(0));
    if (waiting_for.empty() && select.Int(1) != static_cast<int>(JobState::kCompleted)) {
      waiting_for = job.after.back();
    }
  }
  // Slurm's reason "Dependency", with the job that holds it back.
  if (job.state == JobState::kQueued && !waiting_for.empty()) {
    job.reason = "dependency: waiting for job " + waiting_for + " to complete";
  }
}

void JobStore::LoadLabels(JobRecord& job) {
  Statement select(db_, "SELECT key, value FROM job_labels WHERE job_id = ? ORDER BY key");
  select.Bind(job.id);
  job.labels.clear();
  while (select.Step()) job.labels[select.Text(0)] = select.Text(1);
}

void JobStore::WriteSceneValues(const std::string& id,
                                const std::vector<std::pair<std::string, std::string>>& values) {
  Statement(db_, "DELETE FROM job_values WHERE job_id = ?").Bind(id).Run();
  for (const auto& [key, value] : values) {
    Statement insert(db_,
                     "INSERT OR REPLACE INTO job_values (job_id, key, value) VALUES (?, ?, ?)");
    insert.Bind(id).Bind(key).Bind(value).Run();
  }
}

std::vector<StudyRecord> JobStore::QueryStudies(Statement& statement) {
  std::vector<StudyRecord> studies;
  while (statement.Step()) {
    StudyRecord study;
    int c = 0;
    study.ordinal = statement.Int(c++);
    study.id = statement.Text(c++);
    study.owner = statement.Text(c++);
    study.name = statement.Text(c++);
    study.tags = Split(statement.Text(c++), ',');
    study.labels = DecodeLabels(statement.Text(c++));
    study.axes = DecodeAxes(statement.Text(c++));
    study.overrides = Split(statement.Text(c++), '\n');
    study.max_running = static_cast<int>(statement.Int(c++));
    study.created_time = statement.Real(c++);
    studies.push_back(std::move(study));
  }
  return studies;
}

void JobStore::LoadTags(JobRecord& job) {
  Statement select(db_, "SELECT tag FROM job_tags WHERE job_id = ? ORDER BY rowid");
  select.Bind(job.id);
  job.tags.clear();
  while (select.Step()) job.tags.push_back(select.Text(0));
}

JobStore::InsertResult JobStore::InsertJobs(std::vector<JobRecord> jobs, const std::string& owner,
                                            const std::string& request_key,
                                            const StudyRecord* study) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  InsertResult result;
  if (!request_key.empty()) {
    Statement select(db_, "SELECT job_ids FROM requests WHERE owner = ? AND request_key = ?");
    select.Bind(owner).Bind(request_key);
    if (select.Step()) {
      for (const auto& id : Split(select.Text(0), ',')) {
        Statement get(db_, SelectJobs() + " WHERE id = ?");
        get.Bind(id);
        for (auto& job : Query(get)) result.jobs.push_back(std::move(job));
      }
      result.existed = true;
      return result;
    }
  }
  if (study != nullptr) {
    Statement insert(db_,
                     "INSERT INTO studies (id, owner, name, tags, labels, axes, overrides, "
                     "max_running, created_time) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?)");
    insert.Bind(study->id)
        .Bind(study->owner)
        .Bind(study->name)
        .Bind(Join(study->tags, ','))
        .Bind(EncodeLabels(study->labels))
        .Bind(EncodeAxes(study->axes))
        .Bind(Join(study->overrides, '\n'))
        .Bind(study->max_running)
        .Bind(study->created_time)
        .Run();
  }
  std::vector<std::string> ids;
  for (auto& job : jobs) {
    Statement insert(db_,
                     "INSERT INTO jobs (id, name, owner, state, reason, priority, study_id, "
                     "created_time, end_time, results_dir, scene, overrides, client_request_id, "
                     "warnings, parameters, attempt, time_limit_seconds, numerics) "
                     "VALUES (?, ?, ?, ?, '', ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
    insert.Bind(job.id)
        .Bind(job.name)
        .Bind(job.owner)
        .Bind(static_cast<int>(job.state))
        .Bind(job.priority)
        .Bind(job.study_id)
        .Bind(job.created_time)
        .Bind(job.end_time)
        .Bind(job.results_dir)
        .Bind(job.scene)
        .Bind(Join(job.overrides, '\n'))
        .Bind(job.client_request_id)
        .Bind(EncodeWarnings(job.warnings))
        .Bind(EncodeParameters(job.parameters))
        .Bind(job.attempt)
        .Bind(job.time_limit_seconds)
        .Bind(EncodeNumerics(job.numerics));
    insert.Run();
    job.ordinal = sqlite3_last_insert_rowid(db_);
    for (const auto& tag : job.tags) {
      Statement tag_insert(db_, "INSERT OR IGNORE INTO job_tags (job_id, tag) VALUES (?, ?)");
      tag_insert.Bind(job.id).Bind(tag).Run();
    }
    for (const auto& [key, value] : job.labels) {
      Statement label_insert(db_, "INSERT INTO job_labels (job_id, key, value) VALUES (?, ?, ?)");
      label_insert.Bind(job.id).Bind(key).Bind(value).Run();
    }
    WriteSceneValues(job.id, job.scene_values);
    for (const auto& after : job.after) {
      Statement dependency(
          db_, "INSERT OR IGNORE INTO job_dependencies (job_id, after_id) VALUES (?, ?)");
      dependency.Bind(job.id).Bind(after).Run();
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
    Statement get(db_, SelectJobs() + " WHERE id = ?");
    get.Bind(id);
    for (auto& job : Query(get)) jobs.push_back(std::move(job));
  }
  return jobs;
}

std::optional<JobRecord> JobStore::Get(const std::string& id) {
  std::lock_guard lock(mutex_);
  Statement select(db_, SelectJobs() + " WHERE id = ?");
  select.Bind(id);
  auto jobs = Query(select);
  if (jobs.empty()) return std::nullopt;
  return std::move(jobs.front());
}

std::vector<JobRecord> JobStore::List(const ListFilter& filter) {
  std::lock_guard lock(mutex_);
  std::string sql = SelectJobs() + " WHERE owner = ?";
  if (!filter.states.empty()) {
    sql += std::string(" AND ") + kShownState + " IN (";
    for (size_t i = 0; i < filter.states.size(); ++i) sql += i ? ", ?" : "?";
    sql += ")";
  }
  std::vector<std::string> tags = filter.tags;
  if (!filter.tag.empty()) tags.push_back(filter.tag);
  for (size_t i = 0; i < tags.size(); ++i) {
    sql += " AND id IN (SELECT job_id FROM job_tags WHERE tag = ?)";
  }
  for (size_t i = 0; i < filter.labels.size(); ++i) {
    sql += " AND id IN (SELECT job_id FROM job_labels WHERE key = ? AND value = ?)";
  }
  // The ranges compare scene_number(value): the value as a number, NULL for any other value.
  for (const auto& value : filter.values) {
    sql += " AND id IN (SELECT job_id FROM job_values WHERE key GLOB ? AND ";
    sql += value.op == "=" || value.op == "!=" ? "value " + value.op + " ?)"
                                               : "scene_number(value) " + value.op + " ?)";
  }
  if (!filter.study_id.empty()) sql += " AND study_id = ?";
  if (filter.before_ordinal > 0) sql += " AND ordinal < ?";
  sql += " ORDER BY ordinal DESC LIMIT ?";
  Statement select(db_, sql);
  select.Bind(filter.owner);
  for (JobState state : filter.states) select.Bind(static_cast<int>(state));
  for (const auto& tag : tags) select.Bind(tag);
  for (const auto& [key, value] : filter.labels) select.Bind(key).Bind(value);
  for (const auto& value : filter.values) {
    select.Bind(KeyGlob(value.pattern));
    if (value.op == "=" || value.op == "!=") {
      select.Bind(value.value);
    } else {
      select.Bind(value.bound);
    }
  }
  if (!filter.study_id.empty()) select.Bind(filter.study_id);
  if (filter.before_ordinal > 0) select.Bind(filter.before_ordinal);
  select.Bind(filter.limit);
  return Query(select);
}

bool JobStore::SceneKeyKnown(const std::string& owner, const std::string& pattern) {
  std::lock_guard lock(mutex_);
  Statement any(db_, "SELECT 1 FROM jobs WHERE owner = ? LIMIT 1");
  any.Bind(owner);
  if (!any.Step()) return true;
  Statement select(db_,
                   "SELECT 1 FROM job_values JOIN jobs ON jobs.id = job_values.job_id"
                   " WHERE jobs.owner = ? AND job_values.key GLOB ? LIMIT 1");
  select.Bind(owner).Bind(KeyGlob(pattern));
  return select.Step();
}

int64_t JobStore::CountUnfinished() {
  std::lock_guard lock(mutex_);
  Statement select(db_, "SELECT COUNT(*) FROM jobs WHERE state IN (?, ?)");
  select.Bind(static_cast<int>(JobState::kQueued)).Bind(static_cast<int>(JobState::kRunning));
  select.Step();
  return select.Int(0);
}

std::vector<std::string> JobStore::UnfinishedJobIds() {
  std::lock_guard lock(mutex_);
  Statement select(db_, "SELECT id FROM jobs WHERE state IN (?, ?)");
  select.Bind(static_cast<int>(JobState::kQueued)).Bind(static_cast<int>(JobState::kRunning));
  std::vector<std::string> ids;
  while (select.Step()) ids.push_back(select.Text(0));
  return ids;
}

int JobStore::CountRunning() {
  std::lock_guard lock(mutex_);
  Statement select(db_, "SELECT COUNT(*) FROM jobs WHERE state = ?");
  select.Bind(static_cast<int>(JobState::kRunning));
  select.Step();
  return static_cast<int>(select.Int(0));
}

std::vector<JobRecord> JobStore::StudyJobs(const std::string& owner, const std::string& study_id) {
  std::lock_guard lock(mutex_);
  Statement select(db_, SelectJobs() + " WHERE owner = ? AND study_id = ? ORDER BY ordinal");
  select.Bind(owner).Bind(study_id);
  return Query(select);
}

std::optional<StudyRecord> JobStore::GetStudy(const std::string& owner,
                                              const std::string& study_id) {
  std::lock_guard lock(mutex_);
  Statement select(
      db_, std::string("SELECT ") + kStudyColumns + " FROM studies WHERE owner = ? AND id = ?");
  select.Bind(owner).Bind(study_id);
  auto studies = QueryStudies(select);
  if (studies.empty()) return std::nullopt;
  return std::move(studies.front());
}

std::vector<StudyRecord> JobStore::ListStudies(const std::string& owner, const std::string& tag,
                                               int64_t before_ordinal, int limit) {
  std::lock_guard lock(mutex_);
  std::string sql = std::string("SELECT ") + kStudyColumns + " FROM studies WHERE owner = ?";
  if (!tag.empty()) sql += " AND instr(',' || tags || ',', ',' || ? || ',') > 0";
  if (before_ordinal > 0) sql += " AND ordinal < ?";
  sql += " ORDER BY ordinal DESC LIMIT ?";
  Statement select(db_, sql);
  select.Bind(owner);
  if (!tag.empty()) select.Bind(tag);
  if (before_ordinal > 0) select.Bind(before_ordinal);
  select.Bind(limit);
  return QueryStudies(select);
}

StudyStats JobStore::StatsOfStudy(const std::string& owner, const std::string& study_id) {
  std::lock_guard lock(mutex_);
  Statement select(db_,
                   std::string("SELECT ") + kShownState +
                       ", COUNT(*), "
                       "SUM(CASE WHEN state IN (?, ?, ?) THEN 1.0 WHEN end_time > 0 "
                       "THEN MIN(1.0, MAX(0.0, time / end_time)) ELSE 0.0 END), "
                       "MIN(CASE WHEN slurm_waiting = 1 THEN NULL ELSE NULLIF(started_time, 0) "
                       "END), MAX(finished_time) "
                       "FROM " +
                       kJobRows + " jobs WHERE owner = ? AND study_id = ? GROUP BY 1");
  select.Bind(static_cast<int>(JobState::kCompleted))
      .Bind(static_cast<int>(JobState::kFailed))
      .Bind(static_cast<int>(JobState::kCancelled))
      .Bind(owner)
      .Bind(study_id);
  StudyStats stats;
  while (select.Step()) {
    const int64_t state = select.Int(0);
    const int count = static_cast<int>(select.Int(1));
    if (state >= 1 && state <= 5) stats.count[static_cast<size_t>(state)] += count;
    stats.jobs += count;
    stats.progress_sum += select.Real(2);
    const double started = select.Real(3);  // NULL reads 0
    if (started > 0 && (stats.first_started_time == 0 || started < stats.first_started_time)) {
      stats.first_started_time = started;
    }
    stats.last_finished_time = std::max(stats.last_finished_time, select.Real(4));
  }
  return stats;
}

std::vector<JobRecord> JobStore::Requeue(const std::vector<RequeueChange>& changes) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  const auto read = [&](const std::string& id) {
    Statement get(db_, SelectJobs() + " WHERE id = ?");
    get.Bind(id);
    return Query(get);
  };
  std::vector<JobRecord> requeued;
  for (const RequeueChange& change : changes) {
    const std::vector<JobRecord> found = read(change.id);
    if (found.empty() || !IsFinished(found.front().state)) {
      throw StoreError("job " + change.id + " is not finished");
    }
    const JobRecord& job = found.front();
    std::vector<AttemptRecord> attempts = job.previous_attempts;
    attempts.push_back({job.attempt, job.state, job.reason, job.started_time, job.finished_time,
                        job.step, job.time, job.overrides});
    Statement update(db_,
                     "UPDATE jobs SET state = ?, reason = '', started_time = 0, finished_time = 0, "
                     "cancel_requested = 0, attempt = attempt + 1, previous_attempts = ?, "
                     "name = ?, overrides = ?, "
                     "exit_code = -1, exit_signal = 0, cpu_seconds = 0, peak_memory_bytes = 0, "
                     "parameters = ?, warnings = ?, numerics = ?, end_time = ?, fresh_start = ?, "
                     "step = CASE WHEN ? THEN 0 ELSE step END, "
                     "time = CASE WHEN ? THEN 0 ELSE time END WHERE id = ? AND state IN " +
                         JobStatesBefore(JobTransition::kRetry));
    CheckTransition(JobTransition::kRetry, JobState::kQueued);
    update.Bind(static_cast<int>(JobState::kQueued))
        .Bind(EncodeAttempts(attempts))
        .Bind(change.name.empty() ? job.name : change.name)
        .Bind(Join(change.overrides, '\n'))
        .Bind(EncodeParameters(change.parameters))
        .Bind(EncodeWarnings(change.warnings))
        .Bind(EncodeNumerics(change.numerics))
        .Bind(change.end_time)
        .Bind(change.fresh_start ? 1 : 0)
        .Bind(change.fresh_start ? 1 : 0)
        .Bind(change.fresh_start ? 1 : 0)
        .Bind(change.id);
    update.Run();
    if (update.Changes() != 1) throw StoreError("job " + change.id + " is not finished");
    // A retry starts the Slurm record afresh (slurm_max_attempts counts from here).
    Statement(db_, "DELETE FROM slurm_jobs WHERE job_id = ?").Bind(change.id).Run();
    WriteSceneValues(change.id, change.scene_values);
    requeued.push_back(read(change.id).front());
  }
  transaction.Commit();
  return requeued;
}

void JobStore::ClearFreshStart(const std::string& id) {
  std::lock_guard lock(mutex_);
  Statement(db_, "UPDATE jobs SET fresh_start = 0 WHERE id = ?").Bind(id).Run();
}

std::optional<JobRecord> JobStore::NextQueued() {
  std::lock_guard lock(mutex_);
  // A study at its max_running holds its queued jobs back; others may start meanwhile; a held job
  // waits for its Release, one with dependencies for them to complete. A job whose Slurm run
  // outlived the daemon (slurm_live) is in Slurm's hands already: it comes first and no limit
  // holds it back.
  Statement select(db_, SelectJobs("j") +
                            " WHERE state = ? AND held = 0 AND (slurm_live = 1 OR (NOT "
                            "EXISTS (SELECT 1 FROM studies s WHERE s.id = j.study_id AND "
                            "s.max_running > 0 AND s.max_running <= (SELECT COUNT(*) FROM jobs r "
                            "WHERE r.study_id = j.study_id AND r.state = ?)) AND NOT " +
                            WaitsForDependency() +
                            ")) ORDER BY slurm_live DESC, priority DESC, ordinal LIMIT 1");
  select.Bind(static_cast<int>(JobState::kQueued)).Bind(static_cast<int>(JobState::kRunning));
  auto jobs = Query(select);
  if (jobs.empty()) return std::nullopt;
  return std::move(jobs.front());
}

void JobStore::MarkRunning(const std::string& id, double started_time, RunStart start) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  // An adopted run is no new solver start and keeps its start time; a run that waits in the
  // executor first has none yet (SetSlurmState gives it when Slurm starts it).
  const char* set =
      start == RunStart::kAdopt ? "UPDATE jobs SET state = ?, reason = ''"
      : start == RunStart::kWaiting
          ? "UPDATE jobs SET state = ?, started_time = 0, attempts = attempts + 1, reason = ''"
          : "UPDATE jobs SET state = ?, started_time = ?, attempts = attempts + 1, reason = ''";
  CheckTransition(JobTransition::kStart, JobState::kRunning);
  Statement update(db_, std::string(set) + " WHERE id = ? AND state IN " +
                            JobStatesBefore(JobTransition::kStart));
  update.Bind(static_cast<int>(JobState::kRunning));
  if (start == RunStart::kRun) update.Bind(started_time);
  update.Bind(id);
  update.Run();
  if (update.Changes() != 1) throw StoreError("job " + id + " is not queued");
  if (start == RunStart::kWaiting) {
    Statement(db_,
              "INSERT INTO slurm_jobs (job_id, waiting) VALUES (?, 1) ON CONFLICT (job_id) DO "
              "UPDATE SET state = '', reason = '', waiting = 1")
        .Bind(id)
        .Run();
  }
  transaction.Commit();
}

bool JobStore::MarkFinished(const std::string& id, JobState state, const std::string& reason,
                            double when) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  CheckTransition(JobTransition::kFinish, state);
  Statement update(db_,
                   "UPDATE jobs SET state = ?, reason = ?, finished_time = ? "
                   "WHERE id = ? AND state IN " +
                       JobStatesBefore(JobTransition::kFinish));
  update.Bind(static_cast<int>(state)).Bind(reason).Bind(when).Bind(id);
  update.Run();
  const bool changed = update.Changes() == 1;
  if (changed) {  // the Slurm id stays for `dlmfd show`
    Statement(db_,
              "UPDATE slurm_jobs SET live = 0, state = '', reason = '', waiting = 0 "
              "WHERE job_id = ?")
        .Bind(id)
        .Run();
  }
  transaction.Commit();
  return changed;
}

bool JobStore::CancelQueued(const std::string& id, const std::string& reason, double when) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  CheckTransition(JobTransition::kCancelQueued, JobState::kCancelled);
  Statement update(db_,
                   "UPDATE jobs SET state = ?, reason = ?, finished_time = ?, cancel_requested = 1 "
                   "WHERE id = ? AND NOT " +
                       SlurmLive("jobs") + " AND state IN " +
                       JobStatesBefore(JobTransition::kCancelQueued));
  update.Bind(static_cast<int>(JobState::kCancelled)).Bind(reason).Bind(when).Bind(id);
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

std::optional<int64_t> JobStore::LastSeq(const std::string& id) {
  std::lock_guard lock(mutex_);
  Statement select(db_, "SELECT last_seq FROM jobs WHERE id = ?");
  select.Bind(id);
  if (!select.Step()) return std::nullopt;
  return select.Int(0);
}

std::vector<std::string> JobStore::RequeueRunning(double now) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  std::vector<std::string> ids;
  {
    Statement select(db_, "SELECT id FROM jobs WHERE cancel_requested = 0 AND state IN " +
                              JobStatesBefore(JobTransition::kDaemonStart) + " ORDER BY ordinal");
    while (select.Step()) ids.push_back(select.Text(0));
  }
  {
    // A cancel that was requested before the crash is honoured: the job does not run again.
    CheckTransition(JobTransition::kDaemonStart, JobState::kCancelled);
    Statement cancel(db_,
                     "UPDATE jobs SET state = ?, reason = 'cancelled', finished_time = ? "
                     "WHERE cancel_requested = 1 AND state IN " +
                         JobStatesBefore(JobTransition::kDaemonStart));
    cancel.Bind(static_cast<int>(JobState::kCancelled)).Bind(now).Run();
  }
  CheckTransition(JobTransition::kDaemonStart, JobState::kQueued);
  Statement update(db_, "UPDATE jobs SET state = ?, reason = 'daemon restarted' WHERE state IN " +
                            JobStatesBefore(JobTransition::kDaemonStart));
  update.Bind(static_cast<int>(JobState::kQueued)).Run();
  transaction.Commit();
  return ids;
}

bool JobStore::SetHeld(const std::string& id, bool held) {
  std::lock_guard lock(mutex_);
  Statement update(
      db_, "UPDATE jobs SET held = ? WHERE id = ? AND state = ? AND NOT " + SlurmLive("jobs"));
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

void JobStore::RecordUsage(const std::string& id, const RunUsage& usage) {
  std::lock_guard lock(mutex_);
  Statement update(db_,
                   "UPDATE jobs SET exit_code = ?, exit_signal = ?, "
                   "cpu_seconds = cpu_seconds + MAX(?, 0), "
                   "peak_memory_bytes = MAX(peak_memory_bytes, ?) WHERE id = ?");
  update.Bind(usage.exit_code)
      .Bind(usage.exit_signal)
      .Bind(usage.cpu_seconds)
      .Bind(usage.peak_memory_bytes)
      .Bind(id)
      .Run();
}

void JobStore::SetDiskBytes(const std::string& id, int64_t bytes) {
  std::lock_guard lock(mutex_);
  Statement(db_, "UPDATE jobs SET disk_bytes = ? WHERE id = ?").Bind(bytes).Bind(id).Run();
}

void JobStore::Delete(const std::vector<std::string>& ids) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  std::set<std::string> studies;
  for (const std::string& id : ids) {
    Statement study(db_, "SELECT study_id FROM jobs WHERE id = ? AND study_id != ''");
    study.Bind(id);
    if (study.Step()) studies.insert(study.Text(0));
    Statement(db_, "DELETE FROM job_tags WHERE job_id = ?").Bind(id).Run();
    Statement(db_, "DELETE FROM job_labels WHERE job_id = ?").Bind(id).Run();
    Statement(db_, "DELETE FROM job_values WHERE job_id = ?").Bind(id).Run();
    // Its own dependencies go; those on it stay, so that its queued dependants are cancelled.
    Statement(db_, "DELETE FROM job_dependencies WHERE job_id = ?").Bind(id).Run();
    Statement(db_, "DELETE FROM slurm_jobs WHERE job_id = ?").Bind(id).Run();
    Statement(db_, "DELETE FROM jobs WHERE id = ?").Bind(id).Run();
  }
  // A study whose last job went is gone too: it is no longer listed, shown or found.
  for (const std::string& study : studies) {
    Statement(db_,
              "DELETE FROM studies WHERE id = ? AND NOT EXISTS "
              "(SELECT 1 FROM jobs WHERE jobs.study_id = studies.id)")
        .Bind(study)
        .Run();
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

std::vector<JobRecord> JobStore::QueuedOfStudy(const std::string& study_id, int limit) {
  std::lock_guard lock(mutex_);
  Statement select(db_, SelectJobs("j") +
                            " WHERE study_id = ? AND state = ? AND held = 0 AND "
                            "slurm_live = 0 AND NOT " +
                            WaitsForDependency() + " ORDER BY priority DESC, ordinal LIMIT ?");
  select.Bind(study_id).Bind(static_cast<int>(JobState::kQueued)).Bind(limit);
  return Query(select);
}

std::vector<std::pair<std::string, std::string>> JobStore::Blocked() {
  std::lock_guard lock(mutex_);
  Statement select(db_,
                   "SELECT d.job_id, d.after_id, p.state FROM job_dependencies d "
                   "JOIN jobs j ON j.id = d.job_id LEFT JOIN jobs p ON p.id = d.after_id "
                   "WHERE j.state = ? AND NOT " +
                       SlurmLive("j") +
                       " AND (p.state IS NULL OR p.state IN (?, ?)) ORDER BY j.ordinal, d.rowid");
  select.Bind(static_cast<int>(JobState::kQueued))
      .Bind(static_cast<int>(JobState::kFailed))
      .Bind(static_cast<int>(JobState::kCancelled));
  std::vector<std::pair<std::string, std::string>> blocked;
  while (select.Step()) {
    if (!blocked.empty() && blocked.back().first == select.Text(0)) continue;
    const std::string after = select.Text(1);
    blocked.emplace_back(select.Text(0),
                         select.IsNull(2)
                             ? "dependency " + after + " was deleted"
                             : "dependency " + after + " failed (" +
                                   JobStateName(static_cast<JobState>(select.Int(2))) + ")");
  }
  return blocked;
}

int JobStore::CountRunningOfStudy(const std::string& study_id) {
  std::lock_guard lock(mutex_);
  Statement select(db_, "SELECT COUNT(*) FROM jobs WHERE study_id = ? AND state = ?");
  select.Bind(study_id).Bind(static_cast<int>(JobState::kRunning));
  select.Step();
  return static_cast<int>(select.Int(0));
}

void JobStore::SetSlurmSubmitted(const std::string& id, const std::string& slurm_job_id) {
  std::lock_guard lock(mutex_);
  Statement(db_,
            "INSERT INTO slurm_jobs (job_id, slurm_job_id, live, attempts, restarts, state, "
            "reason, waiting) SELECT id, ?, 1, 1, 0, 'PENDING', '', 1 FROM jobs WHERE id = ? "
            "ON CONFLICT (job_id) DO UPDATE SET slurm_job_id = excluded.slurm_job_id, live = 1, "
            "attempts = attempts + 1, restarts = 0, state = 'PENDING', reason = '', waiting = 1")
      .Bind(slurm_job_id)
      .Bind(id)
      .Run();
}

bool JobStore::SetSlurmState(const std::string& id, const std::string& slurm_state,
                             const std::string& slurm_reason, bool waiting, double now) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  const std::string live_of_running =
      "FROM slurm_jobs s JOIN jobs ON jobs.id = s.job_id WHERE s.job_id = ? AND s.live = 1 AND "
      "jobs.state = " +
      std::to_string(static_cast<int>(JobState::kRunning));
  // A job that Slurm held waiting and now runs starts now.
  if (!waiting) {
    Statement(db_, "UPDATE jobs SET started_time = ? WHERE id IN (SELECT s.job_id " +
                       live_of_running + " AND s.waiting = 1)")
        .Bind(now)
        .Bind(id)
        .Run();
  }
  Statement update(db_,
                   "UPDATE slurm_jobs SET state = ?, reason = ?, waiting = ? WHERE job_id IN "
                   "(SELECT s.job_id " +
                       live_of_running + ") AND (state != ? OR reason != ? OR waiting != ?)");
  update.Bind(slurm_state)
      .Bind(slurm_reason)
      .Bind(waiting ? 1 : 0)
      .Bind(id)
      .Bind(slurm_state)
      .Bind(slurm_reason)
      .Bind(waiting ? 1 : 0);
  update.Run();
  const bool changed = update.Changes() == 1;
  transaction.Commit();
  return changed;
}

void JobStore::EndAttempt(const std::string& id, const AttemptEnd& end) {
  std::lock_guard lock(mutex_);
  Transaction transaction(db_);
  std::vector<JobRecord> found;
  {
    Statement get(db_, SelectJobs() + " WHERE id = ?");
    get.Bind(id);
    found = Query(get);
  }
  if (found.empty() || !TransitionFrom(JobTransition::kEndAttempt, found.front().state)) {
    throw StoreError("job " + id + " is not running");
  }
  const JobRecord& job = found.front();
  std::vector<AttemptRecord> attempts = job.previous_attempts;
  attempts.push_back({job.attempt, end.state, end.reason, job.started_time, end.when, job.step,
                      job.time, job.overrides});
  // Slurm ran the job again by itself: it stays RUNNING, its restarts are recorded. Otherwise
  // the daemon queues it again.
  const bool restarted = end.slurm_restarts > 0;
  const JobState next = restarted ? JobState::kRunning : JobState::kQueued;
  CheckTransition(JobTransition::kEndAttempt, next);
  Statement update(db_,
                   "UPDATE jobs SET state = ?, reason = ?, attempt = attempt + 1, "
                   "previous_attempts = ?, started_time = ? WHERE id = ?");
  update.Bind(static_cast<int>(next))
      .Bind(restarted ? std::string() : end.reason)
      .Bind(EncodeAttempts(attempts))
      .Bind(restarted ? end.when : 0.0)
      .Bind(id)
      .Run();
  Statement(db_,
            "UPDATE slurm_jobs SET live = ?, attempts = attempts + ?, restarts = ?, state = '', "
            "reason = '', waiting = 0 WHERE job_id = ?")
      .Bind(restarted ? 1 : 0)
      .Bind(restarted ? 1 : 0)
      .Bind(restarted ? end.slurm_restarts : 0)
      .Bind(id)
      .Run();
  transaction.Commit();
}

std::vector<JobRecord> JobStore::OwnerJobs(const std::string& owner) {
  std::lock_guard lock(mutex_);
  Statement select(db_, SelectJobs() + " WHERE owner = ? ORDER BY ordinal");
  select.Bind(owner);
  return Query(select);
}

}  // namespace dlmfd::server
