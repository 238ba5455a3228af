#include "slurm_executor.h"

#include <signal.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "dlmfd/io/atomic_file.h"
#include "dlmfd/solver/exit_codes.h"
#include "event_file_tail.h"
#include "scene_admission.h"
#include "slurm_states.h"

namespace dlmfd::server {
namespace fs = std::filesystem;
namespace {

constexpr auto kTailInterval = std::chrono::milliseconds(500);  // between reads of events.bin
constexpr int kUnknownPollsToFail = 3;  // polls that find the job nowhere before it is lost

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

std::optional<SlurmJobStatus> SlurmQueue::Status(const std::string& id, bool* answered) {
  std::string json;
  {
    std::lock_guard lock(mutex_);
    const auto now = std::chrono::steady_clock::now();
    if (now - polled_ >= std::chrono::seconds(settings_.poll_seconds)) {
      polled_ = now;
      CommandResult result = RunCommand({"squeue", "--json"});
      answered_ = result.status == 0;
      if (answered_) {
        json_ = std::move(result.out);
      } else {
        spdlog::warn("squeue --json failed ({}): {}; keeping the last states", result.status,
                     result.err.substr(0, 300));
      }
    }
    json = json_;
    *answered = answered_;
  }
  if (!json.empty()) {
    try {
      if (auto status = FindInSqueueJson(json, id)) return status;
    } catch (const std::exception& e) {
      spdlog::warn("Slurm job {}: {}", id, e.what());
      *answered = false;
    }
  }
  if (settings_.jobcomp_file.empty()) return std::nullopt;
  return FindInJobComp(ReadFile(settings_.jobcomp_file), id);
}

bool SlurmRun::Adopt(const std::string& job_dir) {
  const fs::path dir = job_dir;
  if (!fs::exists(dir / kSlurmLiveFile)) return false;
  std::istringstream(ReadFile(dir / kSlurmIdFile)) >> slurm_id_;
  if (slurm_id_.empty()) return false;
  job_dir_ = job_dir;
  return true;
}

void SlurmRun::Start(const LaunchSpec& spec) {
  const fs::path results = spec.results_dir;
  const fs::path dir = results.parent_path();
  job_dir_ = dir.string();
  for (const char* name :
       {kSlurmEventsFile, kSlurmExitFile, kSlurmWarnedFile, kSlurmIdFile, kSlurmLiveFile}) {
    fs::remove(dir / name);
  }
  BatchJob job;
  job.name = "dlmfd-" + dir.filename().string();
  job.job_dir = job_dir_;
  job.solver = config_.slurm.solver;
  job.scene_path = spec.scene_path;
  job.results_dir = spec.results_dir;
  job.log_path = spec.log_path;
  job.overrides = spec.overrides;
  job.resume = spec.resume;
  job.threads = config_.solver_threads > 0 ? config_.solver_threads : 1;
  job.memory_mb =
      AdmitScene(ReadFile(spec.scene_path), spec.overrides, config_).memory_mb + kProcessHeadroomMb;
  const std::string script = (dir / kSlurmScript).string();
  WriteTextAtomically(script, BatchScript(job));
  std::vector<std::string> argv = {"sbatch"};
  for (auto& a : SbatchArguments(job, config_.slurm, script)) argv.push_back(std::move(a));
  const CommandResult result = RunCommand(argv);
  if (result.status != 0) {
    throw std::runtime_error("sbatch failed (status " + std::to_string(result.status) +
                             "): " + result.err.substr(0, 500));
  }
  slurm_id_ = ParseSbatchId(result.out);
  WriteTextAtomically((dir / kSlurmIdFile).string(), slurm_id_ + "\n");
  WriteTextAtomically((dir / kSlurmLiveFile).string(), slurm_id_ + "\n");
}

bool SlurmRun::ReadExitFile() {
  const fs::path path = fs::path(job_dir_) / kSlurmExitFile;
  if (!fs::exists(path)) return false;
  int status = 0;
  std::istringstream(ReadFile(path)) >> status;
  // bash reports a child killed by signal N as 128 + N.
  exit_.signalled = status > 128 && status != solver::kExitCancelled;
  exit_.code = exit_.signalled ? status - 128 : status;
  if (status == solver::kExitCancelled && fs::exists(fs::path(job_dir_) / kSlurmWarnedFile)) {
    outcome_.emplace(JobState::kFailed,
                     "Slurm: the time limit (slurm_time_limit_minutes) came: the solver "
                     "checkpointed; retry resumes from the checkpoint");
  }
  return true;
}

void SlurmRun::ReadEvents(const std::function<void(const v1::SolverEvent&)>& on_event) {
  FollowUntilEnd(on_event);
  // The end is known: a later start of the daemon must not adopt this job again.
  fs::remove(fs::path(job_dir_) / kSlurmLiveFile);
}

void SlurmRun::FollowUntilEnd(const std::function<void(const v1::SolverEvent&)>& on_event) {
  EventFileTail tail((fs::path(job_dir_) / kSlurmEventsFile).string());
  std::string live_reason;
  int unknown = 0;
  auto next_poll = std::chrono::steady_clock::now();
  while (true) {
    tail.ReadNew(on_event);
    if (ReadExitFile()) break;
    if (std::chrono::steady_clock::now() >= next_poll) {
      next_poll =
          std::chrono::steady_clock::now() + std::chrono::seconds(config_.slurm.poll_seconds);
      bool answered = false;
      const auto status = queue_->Status(slurm_id_, &answered);
      if (status) {
        unknown = 0;
        const SlurmStateMeaning meaning = MapSlurmState(status->state, status->reason);
        if (meaning.finished) {
          tail.ReadNew(on_event);
          if (ReadExitFile()) break;
          outcome_.emplace(meaning.state, meaning.reason);
          exit_.signalled = true;
          exit_.code = SIGKILL;
          break;
        }
        if (meaning.reason != live_reason) {
          live_reason = meaning.reason;
          spdlog::info("Slurm job {}: {}", slurm_id_, live_reason);
        }
      } else if (answered && ++unknown >= kUnknownPollsToFail) {
        outcome_.emplace(JobState::kFailed, "Slurm job " + slurm_id_ +
                                                " is neither in squeue nor in the jobcomp file "
                                                "(slurm_jobcomp_file) and left no exit status");
        exit_.signalled = true;
        exit_.code = SIGKILL;
        break;
      }
    }
    std::unique_lock lock(mutex_);
    signalled_.wait_for(lock, kTailInterval, [this] { return woken_; });
    if (woken_) {
      woken_ = false;
      next_poll = std::chrono::steady_clock::now();
    }
  }
}

void SlurmRun::Signal(int signal_number) {
  if (slurm_id_.empty()) return;
  std::vector<std::string> argv = {"scancel"};
  if (signal_number == SIGKILL) argv.push_back("--signal=KILL");
  argv.push_back(slurm_id_);
  const CommandResult result = RunCommand(argv);
  if (result.status != 0) {
    spdlog::warn("scancel {} failed ({}): {}", slurm_id_, result.status, result.err.substr(0, 300));
  }
  std::lock_guard lock(mutex_);
  woken_ = true;
  signalled_.notify_all();
}

}  // namespace dlmfd::server
