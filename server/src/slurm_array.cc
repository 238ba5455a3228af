#include "slurm_array.h"

#include <spdlog/spdlog.h>
#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "dlmfd/io/atomic_file.h"

namespace dlmfd::server {
namespace fs = std::filesystem;

std::string SlurmArray::Join(int index, const BatchJob& job) {
  std::unique_lock lock(mutex_);
  joined_[index] = job;
  Arrive(lock);
  changed_.wait(lock, [this] { return done_; });
  if (submitted_.count(index)) return ArrayTaskId(array_id_, index);
  if (signalled_.count(index)) return {};
  throw std::runtime_error(error_.empty() ? "the job array was not submitted" : error_);
}

void SlurmArray::Withdraw() {
  std::unique_lock lock(mutex_);
  Arrive(lock);
}

void SlurmArray::Signal(int index) {
  std::lock_guard lock(mutex_);
  signalled_.insert(index);
  changed_.notify_all();
}

std::vector<std::string> SlurmArray::Prepare(const std::vector<int>& indices,
                                             std::string* dir_out) {
  const BatchJob& first = joined_.at(indices.front());
  const fs::path root = fs::path(first.job_dir).parent_path() / "slurm-arrays";
  fs::create_directories(root);
  std::string pattern = (root / (name_ + "-XXXXXX")).string();
  if (!mkdtemp(pattern.data())) {
    throw std::runtime_error("cannot create a directory in " + root.string() + " for the array");
  }
  const fs::path dir = pattern;
  *dir_out = dir.string();
  BatchJob array = first;
  array.name = name_;
  array.job_dir = dir.string();
  array.log_path = (dir / "task-%a.log").string();
  array.array = ArraySpec(indices, throttle_);
  std::vector<std::pair<int, std::string>> task_dirs;
  for (int index : indices) {
    const BatchJob& member = joined_.at(index);
    array.memory_mb = std::max(array.memory_mb, member.memory_mb);
    array.time_limit_seconds = std::max(array.time_limit_seconds, member.time_limit_seconds);
    task_dirs.emplace_back(index, member.job_dir);
    // Slurm's own lines of the task (its time limit, a requeue) go to the member's log.
    fs::create_symlink(member.log_path, dir / ("task-" + std::to_string(index) + ".log"));
  }
  const std::string script = (dir / kSlurmScript).string();
  WriteTextAtomically(script, ArrayScript(name_, task_dirs));
  std::vector<std::string> argv = {"sbatch"};
  for (auto& a : SbatchArguments(array, config_.slurm, script)) argv.push_back(std::move(a));
  return argv;
}

void SlurmArray::Arrive(std::unique_lock<std::mutex>& lock) {
  if (--waiting_for_ > 0) return;
  while (true) {
    std::vector<int> indices;
    for (const auto& [index, job] : joined_) {
      if (!signalled_.count(index)) indices.push_back(index);
    }
    if (indices.empty()) break;
    std::vector<std::string> argv;
    std::string dir;
    try {
      argv = Prepare(indices, &dir);
    } catch (const std::exception& e) {
      error_ = e.what();
      break;
    }
    lock.unlock();
    const CommandResult result = RunCommand(argv);
    lock.lock();
    if (result.status == 0) {
      try {
        array_id_ = ParseSbatchId(result.out);
        submitted_.insert(indices.begin(), indices.end());
        spdlog::info("Slurm job array {} ({}): {} jobs, --array={}", array_id_, name_,
                     indices.size(), ArraySpec(indices, throttle_));
      } catch (const std::exception& e) {
        error_ = e.what();
      }
      break;
    }
    std::error_code ignored;
    fs::remove_all(dir, ignored);  // written again for the next try
    const std::string message = "sbatch failed (status " + std::to_string(result.status) +
                                "): " + result.err.substr(0, 500);
    if (!TransientSlurmError(result.err)) {
      error_ = message;
      break;
    }
    spdlog::warn("job array {}: {}; trying again in {} s", name_, message,
                 kSbatchRetryInterval.count());
    changed_.wait_for(lock, kSbatchRetryInterval);
  }
  done_ = true;
  changed_.notify_all();
}

}  // namespace dlmfd::server
