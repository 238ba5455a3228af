#include "slurm_executor.h"

#include <signal.h>
#include <spdlog/spdlog.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "dlmfd/io/atomic_file.h"
#include "dlmfd/solver/exit_codes.h"
#include "event_file_tail.h"
#include "job_time_limit.h"
#include "local_executor.h"
#include "scene_admission.h"
#include "slurm_array.h"
#include "slurm_states.h"

namespace dlmfd::server {
namespace fs = std::filesystem;
namespace {

constexpr auto kTailInterval = std::chrono::milliseconds(500);  // between reads of events.bin
// Answers of squeue, run after the submission, that find the job nowhere (nor the jobcomp file)
// before it is lost.
constexpr int kUnknownPollsToFail = 3;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

std::optional<SlurmJobStatus> SlurmQueue::Status(const std::string& id,
                                                 Clock::time_point* answered_at) {
  std::unique_lock lock(mutex_);
  const auto now = Clock::now();
  if (!polling_ && now - polled_ >= std::chrono::seconds(settings_.poll_seconds)) {
    polling_ = true;
    polled_ = now;
    lock.unlock();
    const CommandResult result = RunCommand({"squeue", "--json"});
    std::optional<std::map<std::string, SlurmJobStatus>> jobs;
    if (result.status == 0) {
      try {
        jobs = ParseSqueueJson(result.out);
      } catch (const std::exception& e) {
        spdlog::warn("squeue --json failed: {}; keeping the last states", e.what());
      }
    } else {
      spdlog::warn("squeue --json failed ({}): {}; keeping the last states", result.status,
                   result.err.substr(0, 300));
    }
    lock.lock();
    polling_ = false;
    if (jobs) {
      squeue_ = std::move(*jobs);
      answered_at_ = now;
    }
  }
  *answered_at = answered_at_;
  if (auto it = squeue_.find(id); it != squeue_.end()) return it->second;
  return FromJobComp(id);
}

std::optional<SlurmJobStatus> SlurmQueue::FromJobComp(const std::string& id) {
  if (settings_.jobcomp_file.empty()) return std::nullopt;
  struct stat info {};
  if (stat(settings_.jobcomp_file.c_str(), &info) == 0) {
    const auto changed = std::chrono::system_clock::from_time_t(info.st_mtim.tv_sec) +
                         std::chrono::nanoseconds(info.st_mtim.tv_nsec);
    if (info.st_size != jobcomp_size_ || changed != jobcomp_changed_) {
      jobcomp_ = ParseJobComp(ReadFile(settings_.jobcomp_file));
      jobcomp_size_ = info.st_size;
      jobcomp_changed_ = changed;
    }
  }
  if (auto it = jobcomp_.find(id); it != jobcomp_.end()) return it->second;
  return std::nullopt;
}

bool SlurmRun::Adopt(const std::string& job_dir, const JobRecord& job, const ReadFrom& read_from) {
  if (!job.slurm_live || job.slurm_job_id.empty()) return false;
  job_dir_ = job_dir;
  // The events the daemon before logged are not read again (event_hub.h).
  read_from_ = read_from("slurm:" + job.slurm_job_id).value_or(0);
  restarts_ = job.slurm_restarts;
  reported_ = ExecutorState{job.slurm_state, job.slurm_reason, job.slurm_waiting};
  submitted_ = true;
  followed_since_ = SlurmQueue::Clock::now();
  std::lock_guard lock(mutex_);
  slurm_id_ = job.slurm_job_id;
  return true;
}

void SlurmRun::Start(const LaunchSpec& spec) {
  const fs::path results = spec.results_dir;
  const fs::path dir = results.parent_path();
  job_dir_ = dir.string();
  if (FollowUnrecordedJob(dir)) return;
  BatchJob job;
  std::string script;
  try {
    for (const char* name : {kSlurmEventsFile, kSlurmExitFile, kSlurmWarnedFile, kSlurmIdFile}) {
      fs::remove(dir / name);
    }
    job.name = "dlmfd-" + dir.filename().string();
    job.job_dir = job_dir_;
    job.solver = config_.slurm.solver;
    job.scene_path = spec.scene_path;
    job.results_dir = spec.results_dir;
    job.log_path = spec.log_path;
    job.overrides = spec.overrides;
    job.resume = spec.resume;
    job.threads = config_.solver_threads > 0 ? config_.solver_threads : 1;
    job.time_limit_seconds = spec.time_limit_seconds;
    job.memory_mb = AdmitScene(ReadFile(spec.scene_path), spec.overrides, config_).memory_mb +
                    kProcessHeadroomMb;
    script = (dir / kSlurmScript).string();
    WriteTextAtomically(script, BatchScript(job));
  } catch (...) {
    if (array_) array_->Withdraw();
    throw;
  }
  const std::string id = array_ ? array_->Join(index_, job) : Submit(job, script);
  if (id.empty()) {
    // Signalled before it reached Slurm: it never ran (the scheduler maps SIGTERM as for a
    // solver stopped by it).
    std::lock_guard lock(mutex_);
    exit_.signalled = true;
    exit_.code = SIGTERM;
    return;
  }
  Follow(dir, id);
}

void SlurmRun::Follow(const fs::path& dir, const std::string& id) {
  int pending = 0;
  {
    std::lock_guard lock(mutex_);
    slurm_id_ = id;
    pending = pending_signal_;
  }
  submitted_ = true;
  followed_since_ = SlurmQueue::Clock::now();
  reported_ = ExecutorState{"PENDING", "", true};  // as JobStore::SetSlurmSubmitted records it
  WriteTextAtomically((dir / kSlurmIdFile).string(), id + "\n");
  if (pending != 0) Signal(pending);  // a cancel that came during the submission
}

bool SlurmRun::FollowUnrecordedJob(const fs::path& dir) {
  // A job of its own whose script is there has been handed to sbatch before; an array's task is
  // submitted with its array (slurm_array.h).
  if (array_ || !fs::exists(dir / kSlurmScript)) return false;
  const std::string name = "dlmfd-" + dir.filename().string();
  std::vector<std::string> argv = {"squeue"};
  for (auto& a : SqueueOfNameArguments(name)) argv.push_back(std::move(a));
  const CommandResult result = RunCommand(argv);
  const std::string id = result.status == 0 ? ParseLiveJobIn(result.out, job_dir_) : "";
  if (id.empty()) return false;
  spdlog::warn(
      "{}: Slurm job {} of this job runs or waits, unrecorded (the daemon was killed between "
      "sbatch's answer and the store): followed, not submitted again",
      name, id);
  Follow(dir, id);
  return true;
}

std::string SlurmRun::Submit(const BatchJob& job, const std::string& script) {
  std::vector<std::string> argv = {"sbatch"};
  for (auto& a : SbatchArguments(job, config_.slurm, script)) argv.push_back(std::move(a));
  while (true) {
    const CommandResult result = RunCommand(argv);
    if (result.status == 0) return ParseSbatchId(result.out);
    const std::string message = "sbatch failed (status " + std::to_string(result.status) +
                                "): " + result.err.substr(0, 500);
    if (!TransientSlurmError(result.err)) throw std::runtime_error(message);
    spdlog::warn("{}: {}; trying again in {} s", job.name, message, kSbatchRetryInterval.count());
    std::unique_lock lock(mutex_);
    signalled_.wait_for(lock, kSbatchRetryInterval,
                        [this] { return pending_signal_ != 0 || detached_; });
    if (pending_signal_ != 0 || detached_) return {};
  }
}

void SlurmRun::Abandon() {
  if (array_) array_->Withdraw();
}

std::string SlurmRun::ExecutorId() const {
  std::lock_guard lock(mutex_);
  return slurm_id_;
}

std::string SlurmRun::Describe() const { return "Slurm job " + ExecutorId(); }

std::optional<SlurmRun::ExitFile> SlurmRun::ReadExitFile() const {
  const fs::path path = fs::path(job_dir_) / kSlurmExitFile;
  if (!fs::exists(path)) return std::nullopt;
  ExitFile file;
  std::istringstream(ReadFile(path)) >> file.status >> file.restarts;
  return file;
}

void SlurmRun::SetExit(const ExitFile& file) {
  // bash reports a child killed by signal N as 128 + N.
  exit_.signalled = file.status > 128 && file.status != solver::kExitCancelled;
  exit_.code = exit_.signalled ? file.status - 128 : file.status;
}

void SlurmRun::ReadEvents(const EventHandler& on_event) {
  if (submitted_) FollowUntilEnd(on_event);
}

bool SlurmRun::Sleep() {
  std::unique_lock lock(mutex_);
  signalled_.wait_for(lock, kTailInterval, [this] { return woken_; });
  woken_ = false;
  return detached_;
}

// NOLINTNEXTLINE(readability-function-size): predates the limit; split it when you change it
void SlurmRun::FollowUntilEnd(const EventHandler& on_event) {
  EventFileTail tail((fs::path(job_dir_) / kSlurmEventsFile).string(), read_from_);
  const std::string id = ExecutorId();
  const std::string source = "slurm:" + id;
  std::string live_reason;
  int unknown = 0;  // answers of squeue since the submission that did not list the job
  SlurmQueue::Clock::time_point counted{};
  // Events from the solver show the job running before squeue may (it is asked every
  // slurm_poll_seconds, and not at all while slurmctld is down): from then on, an answer of squeue
  // run before that time that still says PENDING is out of date.
  SlurmQueue::Clock::time_point ran_at{};
  int delivered = 0;
  auto deliver = [&](const v1::SolverEvent& event) {
    ++delivered;
    on_event(event, EventPosition{source, static_cast<int64_t>(tail.offset())});
  };
  auto next_poll = std::chrono::steady_clock::now();
  auto asked = [this] {
    std::lock_guard lock(mutex_);
    return asked_;
  };
  while (true) {
    // The exit file of the attempt followed (an older one is a requeued attempt's), read before
    // the events: the batch script writes it after the solver has exited, so the events read next
    // are all that the solver wrote. Read after them, an exit that came while they were handled
    // (the store's writes on a loaded machine) would end the run without its last events: the
    // finished event, the last progress (the job COMPLETED at an earlier step, its stream short).
    std::optional<ExitFile> exit = ReadExitFile();
    if (exit && exit->restarts < restarts_) exit.reset();
    delivered = 0;
    tail.ReadNew(deliver);
    if (delivered > 0 && reported_.waiting) {
      ran_at = SlurmQueue::Clock::now();
      Report(ExecutorState{"RUNNING", "", false});
    }
    if (exit) {
      const int s = exit->status;
      const bool warned = fs::exists(fs::path(job_dir_) / kSlurmWarnedFile);
      if (s == solver::kExitCompleted || s == solver::kExitFailed || s == solver::kExitInvalid ||
          asked()) {
        SetExit(*exit);
        return;
      }
      if (s == solver::kExitCancelled && warned) {
        SetExit(*exit);
        outcome_ =
            RunOutcome{JobState::kFailed,
                       "Slurm: the job's time limit (--time) came: the solver checkpointed", true};
        return;
      }
      // Stopped from outside the daemon: Slurm says whether the job runs again or has ended.
    }
    if (std::chrono::steady_clock::now() >= next_poll) {
      next_poll =
          std::chrono::steady_clock::now() + std::chrono::seconds(config_.slurm.poll_seconds);
      SlurmQueue::Clock::time_point answered_at{};
      const auto status = queue_->Status(id, &answered_at);
      if (status) {
        unknown = 0;
        if (status->restarts > restarts_) {
          restarts_ = status->restarts;
          live_reason.clear();          // the state of the next run is reported afresh
          reported_ = ExecutorState{};  // the store clears it with the attempt
          const std::string reason = "Slurm requeued job " + id + " (restart " +
                                     std::to_string(restarts_) +
                                     "): the next run resumes from the checkpoint";
          spdlog::info("{}", reason);
          if (on_restart_) on_restart_(restarts_, reason);
          continue;
        }
        const SlurmStateMeaning meaning = MapSlurmState(status->state, status->reason);
        if (meaning.finished) {
          tail.ReadNew(deliver);
          exit = ReadExitFile();
          if (exit && exit->restarts >= restarts_) {
            SetExit(*exit);
            if (meaning.retryable) {
              outcome_ = RunOutcome{meaning.state, meaning.reason, true};
            } else if (meaning.state == JobState::kCancelled &&
                       exit->status == solver::kExitCancelled) {
              outcome_ = RunOutcome{JobState::kCancelled,
                                    "Slurm job " + id + " was cancelled in Slurm (scancel)", false};
            }
          } else {
            outcome_ = RunOutcome{meaning.state, meaning.reason, meaning.retryable};
            exit_.signalled = true;
            exit_.code = SIGKILL;
          }
          return;
        }
        if (meaning.reason != live_reason) {
          live_reason = meaning.reason;
          spdlog::info("Slurm job {}: {}", id, live_reason);
        }
        if (!(meaning.waiting && answered_at <= ran_at)) {
          Report(ExecutorState{status->state, status->reason == "None" ? "" : status->reason,
                               meaning.waiting});
        }
      } else if (answered_at > followed_since_ && answered_at > counted) {
        counted = answered_at;
        if (++unknown >= kUnknownPollsToFail) {
          if (exit) {
            SetExit(*exit);  // Slurm has forgotten it: the exit status tells
            return;
          }
          outcome_ = RunOutcome{JobState::kFailed,
                                "Slurm job " + id +
                                    " is neither in squeue nor in the jobcomp file "
                                    "(slurm_jobcomp_file) and left no exit status",
                                false};
          exit_.signalled = true;
          exit_.code = SIGKILL;
          return;
        }
      }
    }
    if (Sleep()) {
      // The daemon shuts down: the Slurm job runs on, the next start adopts it.
      exit_.signalled = true;
      exit_.code = SIGTERM;
      return;
    }
  }
}

void SlurmRun::Report(const ExecutorState& state) {
  if (state.state == reported_.state && state.reason == reported_.reason &&
      state.waiting == reported_.waiting) {
    return;
  }
  reported_ = state;
  if (on_state_) on_state_(state);
}

void SlurmRun::Signal(int signal_number) {
  std::string id;
  {
    std::lock_guard lock(mutex_);
    // Detached for the daemon's shutdown: the Slurm job is left to run and be adopted.
    if (detached_) return;
    if (slurm_id_.empty()) {
      pending_signal_ = signal_number;
      signalled_.notify_all();
    } else {
      asked_ = true;
      id = slurm_id_;
    }
  }
  if (id.empty()) {
    if (array_) array_->Signal(index_);
    return;
  }
  std::vector<std::string> argv = {"scancel"};
  if (signal_number == SIGKILL) argv.push_back("--signal=KILL");
  argv.push_back(id);
  const CommandResult result = RunCommand(argv);
  if (result.status != 0) {
    spdlog::warn("scancel {} failed ({}): {}", id, result.status, result.err.substr(0, 300));
  }
  std::lock_guard lock(mutex_);
  woken_ = true;
  signalled_.notify_all();
}

void SlurmRun::Detach() {
  bool submitted = false;
  {
    std::lock_guard lock(mutex_);
    detached_ = true;
    woken_ = true;
    submitted = !slurm_id_.empty();
    signalled_.notify_all();
  }
  if (!submitted && array_) array_->Signal(index_);
}

DaemonTimeLimit SlurmExecutor::TimeLimit() const {
  DaemonTimeLimit slurm;
  if (config_.slurm.time_limit_minutes > 0) {
    slurm = {int64_t{config_.slurm.time_limit_minutes} * 60, "slurm_time_limit_minutes"};
  }
  return Tighter(WallSecondsLimit(config_), slurm);
}

std::string SlurmExecutor::JobDirectory(const std::string& job_id) const {
  if (config_.slurm.shared_dir.empty()) return DataJobDirectory(config_, job_id);
  return (fs::path(config_.slurm.shared_dir) / job_id).string();
}

std::shared_ptr<JobRun> SlurmExecutor::NewRun() {
  return std::make_shared<SlurmRun>(config_, queue_);
}

std::vector<std::shared_ptr<JobRun>> SlurmExecutor::NewStudyRuns(const std::string& study,
                                                                 int count, int throttle) {
  auto array = std::make_shared<SlurmArray>(config_, "dlmfd-" + study, count, throttle);
  std::vector<std::shared_ptr<JobRun>> runs;
  for (int i = 0; i < count; ++i) {
    runs.push_back(std::make_shared<SlurmRun>(config_, queue_, array, i));
  }
  return runs;
}

}  // namespace dlmfd::server
