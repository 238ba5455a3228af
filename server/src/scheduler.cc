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

Scheduler::Scheduler(const Config& config, Executor& executor, JobStore& store, EventHub& hub)
    : config_(config),
      executor_(executor),
      store_(store),
      hub_(hub) {}

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
      if (executor_.SubmitsStudiesTogether() && !next->sweep_id.empty() && !next->slurm_live) {
        if (!StartStudyBatch(*next, most - static_cast<int>(running_.size()))) break;
        continue;
      }
      auto run = executor_.NewRun();
      try {
        // A live Slurm job of a daemon before is adopted, not started (JobRun::Adopt).
        const bool adopt = next->slurm_live && !next->slurm_job_id.empty();
        store_.MarkRunning(next->id, NowSeconds(),
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
        if (!store_.CancelQueued(id, reason, NowSeconds())) continue;
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
    const auto sweep = store_.GetSweep(first.owner, first.sweep_id);
    if (sweep && sweep->max_running > 0) {
      // The study's jobs already in Slurm count against its limit (NextQueued gave this job, so
      // fewer than max_running are).
      throttle = std::max(1, sweep->max_running - store_.CountRunningOfSweep(first.sweep_id));
    }
    for (JobRecord& job : store_.QueuedOfSweep(first.sweep_id, room)) {
      if (running_.count(job.id)) continue;  // its previous run's thread is still ending
      try {
        // Handed to the executor together; each waits there before it runs.
        store_.MarkRunning(job.id, NowSeconds(), JobStore::RunStart::kWaiting);
      } catch (const std::exception&) {
        continue;  // cancelled or held since it was read
      }
      if (auto started = store_.Get(job.id)) batch.push_back(std::move(*started));
    }
  } catch (const std::exception& e) {
    spdlog::error("study {}: cannot start: {}", first.sweep_id, e.what());
  }
  if (batch.empty()) return false;
  auto runs = executor_.NewStudyRuns(first.sweep_id, static_cast<int>(batch.size()), throttle);
  for (size_t i = 0; i < batch.size(); ++i) Launch(batch[i], runs[i]);
  return true;
}

void Scheduler::FinishJob(const std::string& job_id, JobState state, const std::string& reason) {
  // Counted first, so that a finished job always has its bytes: the solver has exited.
  store_.SetDiskBytes(job_id, DirectoryBytes(JobDir(job_id)));
  if (!store_.MarkFinished(job_id, state, reason, NowSeconds())) return;
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

// NOLINTNEXTLINE(readability-function-size): predates the limit; split it when you change it
void Scheduler::RunJob(JobRecord job) {
  std::shared_ptr<JobRun> process;
  {
    std::lock_guard lock(mutex_);
    process = running_[job.id].process;
  }
  auto cancel_requested = [&] {
    std::lock_guard lock(mutex_);
    return running_[job.id].cancel;
  };
  int lock_fd = -1;
  bool started = false;  // Start was called, or an earlier run adopted
  std::optional<RunOutcome> outcome;
  try {
    const fs::path dir = JobDir(job.id);
    const fs::path results = ResultsDir(job.id);
    fs::create_directories(dir);
    lock_fd = LockDirectory(dir.string(), [&] { return Stopping() || cancel_requested(); });
    if (lock_fd < 0) {
      if (!Stopping())
        outcome = RunOutcome{JobState::kCancelled, "cancelled before the solver started"};
    } else {
      // A run that outlived the daemon (a Slurm job) is followed, not started again; a retry with
      // another scene starts afresh: its old checkpoint must not be resumed.
      const bool adopted = process->Adopt(dir.string(), job, [&](const std::string& source) {
        return hub_.SourceOffset(job, source);
      });
      started = adopted;
      const bool resume =
          !adopted && !job.fresh_start && fs::exists(results / ResultsWriter::kCheckpoint);
      if (!resume && !adopted) fs::remove_all(results);
      fs::create_directories(results);
      if (job.fresh_start) store_.ClearFreshStart(job.id);
      WriteTextAtomically((dir / "scene.in.toml").string(), job.scene);
      LaunchSpec spec;
      spec.solver = config_.solver;
      spec.scene_path = (dir / "scene.in.toml").string();
      spec.results_dir = results.string();
      spec.log_path = (dir / "solver.log").string();
      spec.overrides = job.overrides;
      spec.resume = resume;
      spec.lock_fd = lock_fd;
      spec.time_limit_seconds = EffectiveTimeLimit(job.time_limit_seconds, executor_.TimeLimit());
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
      // The latest progress, stored at most once a second while running and at the end of each
      // attempt, so that a recorded attempt has the step it reached.
      int64_t seen_step = 0;
      double seen_time = 0;
      bool unstored = false;
      auto store_seen = [&] {
        if (!unstored) return;
        store_.UpdateProgress(job.id, seen_step, seen_time, job.end_time);
        unstored = false;
      };
      process->OnRestart([&](int restarts, const std::string& reason) {
        store_seen();
        RecordRestart(job, restarts, reason);
      });
      process->OnStateChange([&](const ExecutorState& state) { RecordState(job, state); });
      if (adopted) {
        spdlog::info("job {}: {} adopted (it outlived the daemon's previous run)", job.id,
                     process->Describe());
        hub_.Publish(job.id, LogEvent("info", process->Describe() + " adopted"));
        // A cancel asked for while it waited to be adopted.
        if (auto now = store_.Get(job.id); now && now->cancel_requested) {
          std::lock_guard lock(mutex_);
          running_[job.id].cancel = true;
        }
      } else {
        started = true;
        process->Start(spec);
        if (const std::string id = process->ExecutorId(); !id.empty()) {
          store_.SetSlurmSubmitted(job.id, id);
        }
        spdlog::info("job {}: {} started{}", job.id, process->Describe(),
                     resume ? " with --resume" : "");
        // A run that waits in its executor has started nothing yet: it was handed over.
        const std::string what =
            process->WaitsBeforeRunning()
                ? process->Describe() + " submitted" +
                      (resume ? " to resume from results/checkpoint.h5" : "")
                : (resume ? "solver resumed from results/checkpoint.h5" : "solver started");
        hub_.Publish(job.id, LogEvent("info", what));
      }
      WallTimeLimit wall_limit(executor_.LimitsTimeItself() ? 0 : spec.time_limit_seconds,
                               [&] { process->Signal(SIGTERM); });
      if (cancel_requested()) process->Signal(SIGTERM);

      std::optional<v1::Finished> finished;
      double last_store = 0;
      process->ReadEvents([&](const v1::SolverEvent& in, const EventPosition& position) {
        v1::WatchEvent out;
        out.set_wall_time(in.wall_time());
        bool store_progress = false;
        int64_t step = 0;
        double time = 0, end_time = 0;
        // The lane and step that order the event against a resumed solver's (event_hub.h).
        LogOrigin origin{"", 0, position.source, position.offset};
        switch (in.event_case()) {
          case v1::SolverEvent::kStarted: {
            origin.lane = "progress";
            origin.step = in.started().step();
            auto* p = out.mutable_progress();
            step = in.started().step();
            time = in.started().time();
            end_time = in.started().end_time();
            p->set_step(step);
            p->set_time(time);
            p->set_end_time(end_time);
            store_progress = true;
            break;
          }
          case v1::SolverEvent::kProgress: {
            const auto& src = in.progress();
            origin.lane = "progress";
            origin.step = src.step();
            auto* p = out.mutable_progress();
            p->set_step(src.step());
            p->set_time(src.time());
            p->set_end_time(src.end_time());
            p->set_steps_per_second(src.steps_per_second());
            p->set_eta_seconds(src.eta_seconds());
            p->set_max_tra(src.max_tra());
            p->set_min_eig_a(src.min_eig_a());
            step = src.step();
            time = src.time();
            end_time = src.end_time();
            store_progress = NowSeconds() - last_store >= kProgressStoreInterval;
            break;
          }
          case v1::SolverEvent::kParticles:
            *out.mutable_particles() = in.particles();
            origin.lane = "particles";
            origin.step = in.particles().step();
            break;
          case v1::SolverEvent::kSnapshot: {
            const auto& src = in.snapshot();
            origin.lane = "snapshot";
            origin.step = src.step();
            auto* s = out.mutable_snapshot();
            s->set_nx(src.nx());
            s->set_ny(src.ny());
            *s->mutable_values() = src.values();
            s->set_time(src.time());
            s->set_step(src.step());
            s->set_quantity(src.quantity());
            s->set_width(src.nx() * src.h());
            s->set_height(src.ny() * src.h());
            break;
          }
          case v1::SolverEvent::kLog:
            *out.mutable_log() = in.log();
            break;
          case v1::SolverEvent::kCheckpointed: {
            origin.lane = "checkpoint";
            origin.step = in.checkpointed().step();
            std::ostringstream text;
            text << "checkpoint at step " << in.checkpointed().step()
                 << ", t = " << in.checkpointed().time();
            out = LogEvent("info", text.str());
            break;
          }
          case v1::SolverEvent::kFinished:
            finished = in.finished();
            step = in.finished().steps();
            time = in.finished().time();
            end_time = job.end_time;
            store_progress = true;
            out = LogEvent("info", "solver finished: " + in.finished().status());
            break;
          default:
            return;
        }
        if (in.has_started() || in.has_progress() || in.has_finished()) {
          seen_step = step;
          seen_time = time;
          unstored = true;
        }
        if (store_progress) {
          if (end_time > 0) job.end_time = end_time;
          store_.UpdateProgress(job.id, step, time, job.end_time);
          last_store = NowSeconds();
          unstored = false;
        }
        hub_.Publish(job.id, std::move(out), origin);
      });
      store_seen();
      const SolverExit exit = process->Wait();
      RecordUsage(job.id, exit, finished);
      const bool over_wall_time = wall_limit.End();
      const bool cancelled = cancel_requested();
      const std::string reported = finished ? finished->reason() : std::string();
      const auto exited = [&exit](int code) { return !exit.signalled && exit.code == code; };
      if (over_wall_time && !cancelled && !exited(solver::kExitCompleted) &&
          !exited(solver::kExitFailed)) {
        const std::string limit =
            job.time_limit_seconds > 0
                ? "the job's time_limit_seconds = " + std::to_string(job.time_limit_seconds)
                : "max_wall_seconds = " + std::to_string(config_.max_wall_seconds);
        outcome =
            RunOutcome{JobState::kFailed, "wall time limit: the solver ran longer than " + limit +
                                              " and was stopped (its checkpoint is kept)"};
      } else if (Stopping() && (exited(solver::kExitCancelled) || exit.signalled)) {
        spdlog::info("job {}: solver stopped for the daemon's shutdown; stays RUNNING to resume",
                     job.id);
      } else if (auto ended = process->Outcome(); ended && !(cancelled && ended->retryable)) {
        outcome = std::move(ended);
      } else if (exited(solver::kExitCompleted)) {
        outcome = RunOutcome{JobState::kCompleted, ""};
      } else if (exited(solver::kExitFailed)) {
        std::string reason = !reported.empty() ? reported : SummaryReason(results);
        outcome = RunOutcome{JobState::kFailed, reason.empty() ? "solver failed" : reason};
      } else if (exited(solver::kExitInvalid)) {
        std::string reason = !reported.empty() ? reported : LastLogLine(dir / "solver.log");
        outcome = RunOutcome{JobState::kFailed, "invalid scene or arguments: " + reason};
      } else if (exited(solver::kExitCancelled) ||
                 (cancelled && exit.signalled && exit.code == SIGTERM)) {
        outcome = RunOutcome{JobState::kCancelled, cancelled ? "cancelled" : "solver interrupted"};
      } else if (exit.signalled) {
        outcome =
            RunOutcome{JobState::kFailed, "solver killed by signal " + std::to_string(exit.code)};
      } else {
        outcome =
            RunOutcome{JobState::kFailed, "solver exited with status " + std::to_string(exit.code)};
      }
    }
  } catch (const std::exception& e) {
    outcome = RunOutcome{JobState::kFailed, e.what()};
  }
  if (!started) process->Abandon();
  if (lock_fd >= 0) close(lock_fd);
  if (outcome) {
    try {
      if (!(outcome->retryable && Requeue(job, *outcome))) {
        FinishJob(job.id, outcome->state, outcome->reason);
      }
    } catch (const std::exception& e) {
      spdlog::error("job {}: cannot record the end: {}", job.id, e.what());
    }
  }
  std::lock_guard lock(mutex_);
  running_[job.id].done = true;
  dirty_ = true;
  changed_.notify_all();
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
    if (!store_.SetSlurmState(job.id, state.state, state.reason, state.waiting, NowSeconds())) {
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
    end.when = NowSeconds();
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
  end.when = NowSeconds();
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
  if (job->state == JobState::kQueued && store_.CancelQueued(job_id, "cancelled", NowSeconds())) {
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
