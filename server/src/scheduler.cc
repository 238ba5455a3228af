#include "scheduler.h"

#include <signal.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "disk_usage.h"
#include "dlmfd/io/atomic_file.h"
#include "dlmfd/io/results_writer.h"
#include "dlmfd/solver/exit_codes.h"
#include "dlmfd/solver/run_summary.h"
#include "executor.h"
#include "job_proto.h"
#include "job_time_limit.h"
#include "service_error.h"
#include "solver_events.h"
#include "solver_process.h"
#include "wall_time_limit.h"

namespace dlmfd::server {
namespace fs = std::filesystem;
namespace {

constexpr double kProgressStoreInterval = 1.0;  // seconds between progress writes to the store

// The "reason" of results/summary.json, or empty when there is none to read.
std::string SummaryReason(const fs::path& results) {
  try {
    return solver::ReadRunSummary((results / solver::kRunSummaryFile).string()).reason;
  } catch (const solver::RunSummaryError&) {
    return {};
  }
}

// The last non-empty line of a log file (at most its last 4 KiB are read).
std::string LastLogLine(const fs::path& log) {
  std::ifstream in(log, std::ios::binary);
  if (!in) return {};
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff start = size > 4096 ? size - 4096 : 0;
  in.seekg(start);
  std::string tail((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::istringstream lines(tail);
  std::string line, last;
  while (std::getline(lines, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

v1::WatchEvent LogEvent(const std::string& level, const std::string& text) {
  v1::WatchEvent event;
  event.mutable_log()->set_level(level);
  event.mutable_log()->set_text(text);
  return event;
}

}  // namespace

Scheduler::Scheduler(const Config& config, Executor& executor, JobStore& store, EventHub& hub,
                     Clock& clock)
    : config_(config),
      executor_(executor),
      store_(store),
      hub_(hub),
      clock_(clock) {}

Scheduler::~Scheduler() { Stop(std::chrono::seconds(5)); }

std::string Scheduler::JobDir(const std::string& job_id) const {
  return executor_.JobDirectory(job_id);
}

std::string Scheduler::ResultsDir(const std::string& job_id) const {
  return (fs::path(JobDir(job_id)) / "results").string();
}

void Scheduler::Start() {
  loop_ = std::thread([this] { Loop(); });
}

void Scheduler::Wake() {
  std::lock_guard lock(mutex_);
  dirty_ = true;
  changed_.notify_all();
}

void Scheduler::Loop() {
  std::unique_lock lock(mutex_);
  while (!Stopping()) {
    changed_.wait(lock, [this] { return dirty_ || Stopping(); });
    if (Stopping()) break;
    dirty_ = false;
    for (auto it = running_.begin(); it != running_.end();) {
      if (it->second.done) {
        it->second.thread.join();
        it = running_.erase(it);
      } else {
        ++it;
      }
    }
    CancelBlocked();
    const int most = executor_.Capacity();
    while (static_cast<int>(running_.size()) < most && !Stopping()) {
      std::optional<JobRecord> next;
      try {
        next = store_.NextQueued();
        if (!next) break;
      } catch (const std::exception& e) {
        spdlog::error("scheduler: {}", e.what());
        break;
      }
      // A retried job whose previous run's thread has not ended yet: wait for it (its end wakes
      // this loop), so one job never has two runners.
      if (running_.count(next->id)) break;
      if (executor_.SubmitsStudiesTogether() && !next->study_id.empty() && !next->slurm_live) {
        if (!StartStudyBatch(*next, most - static_cast<int>(running_.size()))) break;
        continue;
      }
      auto run = executor_.NewRun();
      try {
        // A live Slurm job of a daemon before is adopted, not started (JobRun::Adopt).
        const bool adopt = next->slurm_live && !next->slurm_job_id.empty();
        store_.MarkRunning(next->id, clock_.Now(),
                           adopt                       ? JobStore::RunStart::kAdopt
                           : run->WaitsBeforeRunning() ? JobStore::RunStart::kWaiting
                                                       : JobStore::RunStart::kRun);
        next = store_.Get(next->id);
      } catch (const std::exception& e) {
        // Cancelled between the two statements: take the next one. Still queued: the store
        // failed; wait for the next change rather than spin.
        std::optional<JobRecord> again;
        try {
          again = store_.Get(next->id);
        } catch (const std::exception&) {}
        if (!again || again->state == JobState::kQueued) {
          spdlog::error("job {}: cannot start: {}", next->id, e.what());
          break;
        }
        continue;
      }
      Launch(*next, std::move(run));
    }
  }
}

void Scheduler::CancelBlocked() {
  // A cancelled dependant may block its own dependants: until none is left.
  for (int pass = 0; pass < 1000 && !Stopping(); ++pass) {
    std::vector<std::pair<std::string, std::string>> blocked;
    try {
      blocked = store_.Blocked();
    } catch (const std::exception& e) {
      spdlog::error("scheduler: {}", e.what());
      return;
    }
    if (blocked.empty()) return;
    for (const auto& [id, reason] : blocked) {
      try {
        if (!store_.CancelQueued(id, reason, clock_.Now())) continue;
        spdlog::info("job {}: CANCELLED: {}", id, reason);
        if (auto job = store_.Get(id)) hub_.PublishState(*job);
      } catch (const std::exception& e) {
        spdlog::error("job {}: cannot cancel ({}): {}", id, reason, e.what());
      }
    }
  }
}

void Scheduler::Launch(const JobRecord& job, std::shared_ptr<JobRun> run) {
  spdlog::info("job {}: {} (attempt {}, priority {})", job.id, JobStateName(ShownState(job)),
               job.attempts, job.priority);
  hub_.PublishState(job);
  auto& entry = running_[job.id];
  entry.process = std::move(run);
  entry.thread = std::thread([this, job] { RunJob(job); });
}

bool Scheduler::StartStudyBatch(const JobRecord& first, int room) {
  std::vector<JobRecord> batch;
  int throttle = 0;
  try {
    const auto study = store_.GetStudy(first.owner, first.study_id);
    if (study && study->max_running > 0) {
      // The study's jobs already in Slurm count against its limit (NextQueued gave this job, so
      // fewer than max_running are).
      throttle = std::max(1, study->max_running - store_.CountRunningOfStudy(first.study_id));
    }
    for (JobRecord& job : store_.QueuedOfStudy(first.study_id, room)) {
      if (running_.count(job.id)) continue;  // its previous run's thread is still ending
      try {
        // Handed to the executor together; each waits there before it runs.
        store_.MarkRunning(job.id, clock_.Now(), JobStore::RunStart::kWaiting);
      } catch (const std::exception&) {
        continue;  // cancelled or held since it was read
      }
      if (auto started = store_.Get(job.id)) batch.push_back(std::move(*started));
    }
  } catch (const std::exception& e) {
    spdlog::error("study {}: cannot start: {}", first.study_id, e.what());
  }
  if (batch.empty()) return false;
  auto runs = executor_.NewStudyRuns(first.study_id, static_cast<int>(batch.size()), throttle);
  for (size_t i = 0; i < batch.size(); ++i) Launch(batch[i], runs[i]);
  return true;
}

void Scheduler::FinishJob(const std::string& job_id, JobState state, const std::string& reason) {
  // Counted first, so that a finished job always has its bytes: the solver has exited.
  store_.SetDiskBytes(job_id, DirectoryBytes(JobDir(job_id)));
  if (!store_.MarkFinished(job_id, state, reason, clock_.Now())) return;
  auto job = store_.Get(job_id);
  if (!job) return;
  if (state == JobState::kCompleted) {
    spdlog::info("job {}: {} after {} steps, t = {}", job_id, JobStateName(state), job->step,
                 job->time);
  } else {
    spdlog::warn("job {}: {}: {}", job_id, JobStateName(state), reason);
  }
  hub_.PublishState(*job);
}

// One attempt of a job in its runner thread: what its stages share.
struct Scheduler::Attempt {
  JobRecord job;
  std::shared_ptr<JobRun> run;
  fs::path dir, results;
  int lock_fd = -1;
  bool started = false;  // Start was called, or an earlier run adopted
  bool adopted = false;
  LaunchSpec spec;
  std::optional<v1::Finished> finished;
  // The latest progress, stored at most once a second while running and at the end of each
  // attempt, so that a recorded attempt has the step it reached.
  int64_t seen_step = 0;
  double seen_time = 0;
  bool unstored = false;
  double last_store = 0;
};

bool Scheduler::CancelRequested(const std::string& job_id) {
  std::lock_guard lock(mutex_);
  return running_[job_id].cancel;
}

void Scheduler::RunJob(JobRecord job) {
  Attempt attempt;
  attempt.job = std::move(job);
  {
    std::lock_guard lock(mutex_);
    attempt.run = running_[attempt.job.id].process;
  }
  std::optional<RunOutcome> outcome;
  try {
    outcome = RunAttempt(attempt);
  } catch (const std::exception& e) {
    outcome = RunOutcome{JobState::kFailed, e.what()};
  }
  if (!attempt.started) attempt.run->Abandon();
  if (attempt.lock_fd >= 0) close(attempt.lock_fd);
  if (outcome) RecordEnd(attempt.job, *outcome);
  std::lock_guard lock(mutex_);
  running_[attempt.job.id].done = true;
  dirty_ = true;
  changed_.notify_all();
}

std::optional<RunOutcome> Scheduler::RunAttempt(Attempt& a) {
  a.dir = JobDir(a.job.id);
  a.results = ResultsDir(a.job.id);
  fs::create_directories(a.dir);
  a.lock_fd =
      LockDirectory(a.dir.string(), [&] { return Stopping() || CancelRequested(a.job.id); });
  if (a.lock_fd < 0) {
    if (Stopping()) return std::nullopt;
    return RunOutcome{JobState::kCancelled, "cancelled before the solver started"};
  }
  PrepareLaunch(a);
  StartOrAdopt(a);
  WallTimeLimit wall_limit(
      executor_.LimitsTimeItself() ? 0 : a.spec.time_limit_seconds, [&] { a.run->Signal(SIGTERM); },
      clock_);
  if (CancelRequested(a.job.id)) a.run->Signal(SIGTERM);
  a.run->ReadEvents([&](const v1::SolverEvent& in, const EventPosition& position) {
    OnSolverEvent(a, in, position);
  });
  StoreSeenProgress(a);
  const SolverExit exit = a.run->Wait();
  RecordUsage(a.job.id, exit, a.finished);
  const bool over_wall_time = wall_limit.End();
  return EndOf(a, exit, over_wall_time);
}

void Scheduler::PrepareLaunch(Attempt& a) {
  // A run that outlived the daemon (a Slurm job) is followed, not started again; a retry with
  // another scene starts afresh: its old checkpoint must not be resumed.
  a.adopted = a.run->Adopt(a.dir.string(), a.job, [&](const std::string& source) {
    return hub_.SourceOffset(a.job, source);
  });
  a.started = a.adopted;
  const bool resume =
      !a.adopted && !a.job.fresh_start && fs::exists(a.results / ResultsWriter::kCheckpoint);
  if (!resume && !a.adopted) fs::remove_all(a.results);
  fs::create_directories(a.results);
  if (a.job.fresh_start) store_.ClearFreshStart(a.job.id);
  WriteTextAtomically((a.dir / "scene.in.toml").string(), a.job.scene);
  LaunchSpec& spec = a.spec;
  spec.solver = config_.solver;
  spec.scene_path = (a.dir / "scene.in.toml").string();
  spec.results_dir = a.results.string();
  spec.log_path = (a.dir / "solver.log").string();
  spec.overrides = a.job.overrides;
  spec.resume = resume;
  spec.lock_fd = a.lock_fd;
  spec.time_limit_seconds = EffectiveTimeLimit(a.job.time_limit_seconds, executor_.TimeLimit());
  if (config_.solver_threads > 0) {
    spec.environment.push_back("OMP_NUM_THREADS=" + std::to_string(config_.solver_threads));
  } else if (!std::getenv("OMP_NUM_THREADS")) {
    // Concurrent solvers share the cores; oversubscribed OpenMP teams spin and crawl.
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    spec.environment.push_back("OMP_NUM_THREADS=" +
                               std::to_string(std::max(1, cores / config_.max_concurrent)));
  }
  if (access(spec.solver.c_str(), X_OK) != 0) {
    throw std::runtime_error("cannot execute the solver " + spec.solver);
  }
}

void Scheduler::StartOrAdopt(Attempt& a) {
  const JobRecord& job = a.job;
  a.run->OnRestart([this, &a](int restarts, const std::string& reason) {
    StoreSeenProgress(a);
    RecordRestart(a.job, restarts, reason);
  });
  a.run->OnStateChange([this, &a](const ExecutorState& state) { RecordState(a.job, state); });
  if (a.adopted) {
    spdlog::info("job {}: {} adopted (it outlived the daemon's previous run)", job.id,
                 a.run->Describe());
    hub_.Publish(job.id, LogEvent("info", a.run->Describe() + " adopted"));
    // A cancel asked for while it waited to be adopted.
    if (auto now = store_.Get(job.id); now && now->cancel_requested) {
      std::lock_guard lock(mutex_);
      running_[job.id].cancel = true;
    }
    return;
  }
  a.started = true;
  a.run->Start(a.spec);
  if (const std::string id = a.run->ExecutorId(); !id.empty()) {
    store_.SetSlurmSubmitted(job.id, id);
  }
  const bool resume = a.spec.resume;
  spdlog::info("job {}: {} started{}", job.id, a.run->Describe(), resume ? " with --resume" : "");
  // A run that waits in its executor has started nothing yet: it was handed over.
  const std::string what =
      a.run->WaitsBeforeRunning()
          ? a.run->Describe() + " submitted" +
                (resume ? " to resume from results/checkpoint.h5" : "")
          : (resume ? "solver resumed from results/checkpoint.h5" : "solver started");
  hub_.Publish(job.id, LogEvent("info", what));
}

void Scheduler::OnSolverEvent(Attempt& a, const v1::SolverEvent& in,
                              const EventPosition& position) {
  auto published = PublishedEventOf(in);
  if (!published) return;
  // Where it was read orders it against a resumed solver's events (event_hub.h).
  published->origin.source = position.source;
  published->origin.source_offset = position.offset;
  bool store_now = in.has_started();
  if (in.has_finished()) {
    a.finished = in.finished();
    published->end_time = a.job.end_time;
    store_now = true;
  } else if (in.has_progress()) {
    store_now = clock_.Now() - a.last_store >= kProgressStoreInterval;
  }
  if (published->reports_progress) {
    a.seen_step = published->step;
    a.seen_time = published->time;
    a.unstored = true;
  }
  if (store_now) {
    if (published->end_time > 0) a.job.end_time = published->end_time;
    store_.UpdateProgress(a.job.id, published->step, published->time, a.job.end_time);
    a.last_store = clock_.Now();
    a.unstored = false;
  }
  hub_.Publish(a.job.id, std::move(published->event), published->origin);
}

void Scheduler::StoreSeenProgress(Attempt& a) {
  if (!a.unstored) return;
  store_.UpdateProgress(a.job.id, a.seen_step, a.seen_time, a.job.end_time);
  a.unstored = false;
}

std::optional<RunOutcome> Scheduler::EndOf(const Attempt& a, const SolverExit& exit,
                                           bool over_wall_time) {
  const JobRecord& job = a.job;
  const bool cancelled = CancelRequested(job.id);
  const std::string reported = a.finished ? a.finished->reason() : std::string();
  const auto exited = [&exit](int code) { return !exit.signalled && exit.code == code; };
  if (over_wall_time && !cancelled && !exited(solver::kExitCompleted) &&
      !exited(solver::kExitFailed)) {
    const std::string limit =
        job.time_limit_seconds > 0
            ? "the job's time_limit_seconds = " + std::to_string(job.time_limit_seconds)
            : "max_wall_seconds = " + std::to_string(config_.max_wall_seconds);
    return RunOutcome{JobState::kFailed, "wall time limit: the solver ran longer than " + limit +
                                             " and was stopped (its checkpoint is kept)"};
  }
  if (Stopping() && (exited(solver::kExitCancelled) || exit.signalled)) {
    spdlog::info("job {}: solver stopped for the daemon's shutdown; stays RUNNING to resume",
                 job.id);
    return std::nullopt;
  }
  if (auto ended = a.run->Outcome(); ended && !(cancelled && ended->retryable)) return ended;
  if (exited(solver::kExitCompleted)) return RunOutcome{JobState::kCompleted, ""};
  if (exited(solver::kExitFailed)) {
    std::string reason = !reported.empty() ? reported : SummaryReason(a.results);
    return RunOutcome{JobState::kFailed, reason.empty() ? "solver failed" : reason};
  }
  if (exited(solver::kExitInvalid)) {
    std::string reason = !reported.empty() ? reported : LastLogLine(a.dir / "solver.log");
    return RunOutcome{JobState::kFailed, "invalid scene or arguments: " + reason};
  }
  if (exited(solver::kExitCancelled) || (cancelled && exit.signalled && exit.code == SIGTERM)) {
    return RunOutcome{JobState::kCancelled, cancelled ? "cancelled" : "solver interrupted"};
  }
  if (exit.signalled) {
    return RunOutcome{JobState::kFailed, "solver killed by signal " + std::to_string(exit.code)};
  }
  return RunOutcome{JobState::kFailed, "solver exited with status " + std::to_string(exit.code)};
}

void Scheduler::RecordEnd(const JobRecord& job, const RunOutcome& outcome) {
  try {
    if (!(outcome.retryable && Requeue(job, outcome))) {
      FinishJob(job.id, outcome.state, outcome.reason);
    }
  } catch (const std::exception& e) {
    spdlog::error("job {}: cannot record the end: {}", job.id, e.what());
  }
}

void Scheduler::RecordUsage(const std::string& job_id, const SolverExit& exit,
                            const std::optional<v1::Finished>& finished) {
  RunUsage usage;
  usage.exit_code = exit.signalled ? -1 : exit.code;
  usage.exit_signal = exit.signalled ? exit.code : 0;
  usage.cpu_seconds = exit.cpu_seconds;
  usage.peak_memory_bytes = exit.peak_memory_bytes;
  // An executor that cannot measure the process (Slurm): the solver's own numbers at its end.
  if (usage.cpu_seconds < 0 && finished) usage.cpu_seconds = finished->cpu_seconds();
  if (usage.peak_memory_bytes < 0 && finished) {
    usage.peak_memory_bytes = finished->peak_memory_bytes();
  }
  try {
    store_.RecordUsage(job_id, usage);
  } catch (const std::exception& e) {
    spdlog::error("job {}: cannot record its accounting: {}", job_id, e.what());
  }
}

void Scheduler::RecordState(const JobRecord& job, const ExecutorState& state) {
  try {
    if (!store_.SetSlurmState(job.id, state.state, state.reason, state.waiting, clock_.Now())) {
      return;
    }
    if (auto now = store_.Get(job.id)) {
      spdlog::info("job {}: {} (Slurm {}{})", job.id, JobStateName(ShownState(*now)), state.state,
                   state.reason.empty() ? "" : ", " + state.reason);
      hub_.PublishState(*now);
    }
  } catch (const std::exception& e) {
    spdlog::error("job {}: cannot record Slurm's state {}: {}", job.id, state.state, e.what());
  }
}

void Scheduler::RecordRestart(const JobRecord& job, int restarts, const std::string& reason) {
  try {
    AttemptEnd end;
    end.state = JobState::kCancelled;
    end.reason = reason;
    end.when = clock_.Now();
    end.slurm_restarts = restarts;
    store_.EndAttempt(job.id, end);
    if (auto now = store_.Get(job.id)) {
      spdlog::info("job {}: attempt {}: {}", job.id, now->attempt, reason);
      hub_.Publish(job.id, LogEvent("info", reason));
      hub_.PublishState(*now);
    }
  } catch (const std::exception& e) {
    spdlog::error("job {}: cannot record Slurm's restart {}: {}", job.id, restarts, e.what());
  }
}

bool Scheduler::Requeue(const JobRecord& job, const RunOutcome& outcome) {
  const auto now = store_.Get(job.id);
  if (!now || now->cancel_requested || now->state != JobState::kRunning) return false;
  if (now->slurm_attempts >= config_.slurm.max_attempts) return false;
  AttemptEnd end;
  end.state = outcome.state;
  end.reason = outcome.reason + "; queued again to resume from the checkpoint: Slurm attempt " +
               std::to_string(now->slurm_attempts + 1) +
               " of slurm_max_attempts = " + std::to_string(config_.slurm.max_attempts);
  end.when = clock_.Now();
  store_.SetDiskBytes(job.id, DirectoryBytes(JobDir(job.id)));
  store_.EndAttempt(job.id, end);
  spdlog::warn("job {}: {}", job.id, end.reason);
  hub_.Publish(job.id, LogEvent("warn", end.reason));
  if (auto queued = store_.Get(job.id)) hub_.PublishState(*queued);
  return true;
}

void Scheduler::WaitUntilStopped(const std::string& job_id) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] {
    auto it = running_.find(job_id);
    return it == running_.end() || it->second.done;
  });
}

JobRecord Scheduler::Cancel(const std::string& job_id) {
  if (auto job = CancelUnlessFinished(job_id)) return *job;
  const auto finished = store_.Get(job_id);
  if (!finished) throw ServiceError(grpc::StatusCode::NOT_FOUND, "job " + job_id + " not found");
  throw ServiceError(
      grpc::StatusCode::FAILED_PRECONDITION,
      "job " + job_id + " has already finished (" + JobStateName(finished->state) + ")");
}

std::optional<JobRecord> Scheduler::CancelUnlessFinished(const std::string& job_id) {
  auto job = store_.Get(job_id);
  if (!job) throw ServiceError(grpc::StatusCode::NOT_FOUND, "job " + job_id + " not found");
  if (IsFinished(job->state)) return std::nullopt;
  if (job->state == JobState::kQueued && store_.CancelQueued(job_id, "cancelled", clock_.Now())) {
    job = store_.Get(job_id);
    spdlog::info("job {}: CANCELLED while queued", job_id);
    hub_.PublishState(*job);
    Wake();  // its dependants, if any, are cancelled in turn
    return job;
  }
  // Running (or started since it was read).
  store_.SetCancelRequested(job_id);
  {
    std::lock_guard lock(mutex_);
    auto it = running_.find(job_id);
    if (it != running_.end() && !it->second.done) {
      it->second.cancel = true;
      it->second.process->Signal(SIGTERM);
      spdlog::info("job {}: cancel requested, SIGTERM sent to the solver", job_id);
    }
  }
  job = store_.Get(job_id);
  if (job->state == JobState::kRunning) job->reason = "cancel requested";
  return job;
}

void Scheduler::Stop(std::chrono::seconds grace) {
  {
    std::lock_guard lock(mutex_);
    if (stopping_.exchange(true)) {
      if (!loop_.joinable() && running_.empty()) return;
    }
    changed_.notify_all();
  }
  if (loop_.joinable()) loop_.join();
  std::unique_lock lock(mutex_);
  for (auto& [id, entry] : running_) entry.process->Detach();
  auto all_done = [this] {
    for (auto& [id, entry] : running_) {
      if (!entry.done) return false;
    }
    return true;
  };
  if (!changed_.wait_for(lock, grace, all_done)) {
    for (auto& [id, entry] : running_) {
      if (!entry.done) {
        spdlog::warn("job {}: solver did not stop within {} s, SIGKILL", id, grace.count());
        entry.process->Signal(SIGKILL);
      }
    }
    changed_.wait(lock, all_done);
  }
  auto entries = std::move(running_);
  running_.clear();
  lock.unlock();
  for (auto& [id, entry] : entries) entry.thread.join();
}

}  // namespace dlmfd::server
