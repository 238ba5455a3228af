// Disk accounting of the daemon: the bytes of a job's directory (results, log, inputs), and a
// user's total, held against max_user_disk_mb when a job is submitted.
//
// A finished job's bytes are counted once, when it finishes (JobStore disk_bytes); an unfinished
// job's directory is counted at the moment of asking, since its results still grow. Symbolic links
// are neither followed nor counted (the solver makes none).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "job_store.h"

namespace dlmfd::server {

// The sizes of the regular files under dir (0 when it does not exist).
int64_t DirectoryBytes(const std::filesystem::path& dir);

// The bytes of every job of `owner`; job_dir maps a job id to its directory.
template <class JobDir>
int64_t UserDiskBytes(JobStore& store, const std::string& owner, JobDir&& job_dir) {
  int64_t total = 0;
  for (const JobRecord& job : store.OwnerJobs(owner)) {
    total += IsFinished(job.state) && job.disk_bytes > 0 ? job.disk_bytes
                                                         : DirectoryBytes(job_dir(job.id));
  }
  return total;
}

}  // namespace dlmfd::server
