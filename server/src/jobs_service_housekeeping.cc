// The rpcs of a study's table, a job's log and inputs, and housekeeping (delete, priority, hold,
// release, the disk quota) of JobsService; jobs.proto documents each one's error codes.
#include <fcntl.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <set>

#include "disk_usage.h"
#include "job_proto.h"
#include "job_table.h"
#include "jobs_service.h"
#include "result_files.h"
#include "rpc_reply.h"

namespace dlmfd::server {
namespace fs = std::filesystem;
namespace {

using grpc::StatusCode;

constexpr int kMaxSelectedJobs = 1000;
constexpr int kMaxLogChunk = 1 << 20;
constexpr const char* kSolverLog = "solver.log";

// At most max_bytes of root/name from offset, opened without following a link (result_files.h);
// sets *size to the file's size. A missing file reads as empty.
std::string ReadPart(const fs::path& root, const std::string& name, int64_t offset,
                     int64_t max_bytes, int64_t* size) {
  *size = 0;
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(root / name, ec))) return {};
  const int fd = OpenResultFile(root, name);
  const off_t end = lseek(fd, 0, SEEK_END);
  *size = end < 0 ? 0 : static_cast<int64_t>(end);
  std::string data;
  if (offset < *size) {
    data.resize(static_cast<size_t>(std::min(max_bytes, *size - offset)));
    size_t got = 0;
    while (got < data.size()) {
      const ssize_t n = pread(fd, data.data() + got, data.size() - got,
                              static_cast<off_t>(offset + static_cast<int64_t>(got)));
      if (n <= 0) break;
      got += static_cast<size_t>(n);
    }
    data.resize(got);
  }
  close(fd);
  return data;
}

}  // namespace

std::vector<JobRecord> JobsService::SelectedJobs(
    const std::string& user, const std::string& study_id,
    const google::protobuf::RepeatedPtrField<std::string>& ids) {
  Require(study_id.empty() != ids.empty(), "study_id, job_ids: give one of them");
  Require(ids.size() <= kMaxSelectedJobs, "job_ids: more than " + std::to_string(kMaxSelectedJobs));
  if (!study_id.empty()) {
    RequireNoNul("study_id", study_id);
    auto jobs = store_.StudyJobs(user, study_id);
    if (jobs.empty()) throw ServiceError(StatusCode::NOT_FOUND, "study " + study_id + " not found");
    return jobs;
  }
  std::vector<JobRecord> jobs;
  std::set<std::string> seen;
  for (const std::string& id : ids) {
    CheckJobId(id, "job_ids");
    if (seen.insert(id).second) jobs.push_back(OwnJob(user, id));
  }
  return jobs;
}

void JobsService::CheckDiskQuota(const std::string& user) {
  if (config_.max_user_disk_mb <= 0) return;
  const int64_t used = UserDiskBytes(
      store_, user, [this](const std::string& id) { return fs::path(scheduler_.JobDir(id)); });
  const int64_t quota = config_.max_user_disk_mb * 1024 * 1024;
  if (used >= quota) {
    throw ServiceError(
        StatusCode::RESOURCE_EXHAUSTED,
        "disk quota: the jobs of " + user + " hold " + std::to_string(used) +
            " bytes, at or over max_user_disk_mb = " + std::to_string(config_.max_user_disk_mb) +
            " MiB; delete jobs (dlmfd delete) to submit more");
  }
}

grpc::ServerUnaryReactor* JobsService::GetUsage(grpc::CallbackServerContext* context,
                                                const v1::GetUsageRequest* /*request*/,
                                                v1::Usage* reply) {
  return Reply(context, "GetUsage", [&] {
    const std::string user = auth_.User(*context);
    reply->set_user(user);
    reply->set_disk_bytes(UserDiskBytes(
        store_, user, [this](const std::string& id) { return fs::path(scheduler_.JobDir(id)); }));
    reply->set_disk_quota_bytes(std::max<int64_t>(0, config_.max_user_disk_mb) * 1024 * 1024);
    std::array<int, 6> count{};
    for (const JobRecord& job : store_.OwnerJobs(user)) ++count[static_cast<int>(ShownState(job))];
    reply->set_jobs(count[1] + count[2] + count[3] + count[4] + count[5]);
    reply->set_queued(count[static_cast<int>(JobState::kQueued)]);
    reply->set_running(count[static_cast<int>(JobState::kRunning)]);
    reply->set_completed(count[static_cast<int>(JobState::kCompleted)]);
    reply->set_failed(count[static_cast<int>(JobState::kFailed)]);
    reply->set_cancelled(count[static_cast<int>(JobState::kCancelled)]);
    reply->set_queue_unfinished(store_.CountUnfinished());
    reply->set_queue_limit(config_.max_queued);
  });
}

grpc::ServerUnaryReactor* JobsService::Table(grpc::CallbackServerContext* context,
                                             const v1::TableRequest* request,
                                             v1::TableResponse* reply) {
  return Reply(context, "Table", [&] {
    const std::string user = auth_.User(*context);
    for (const JobRecord& job : SelectedJobs(user, request->study_id(), request->job_ids())) {
      *reply->add_rows() = TableRowOf(job);
    }
  });
}

grpc::ServerUnaryReactor* JobsService::ReadLog(grpc::CallbackServerContext* context,
                                               const v1::ReadLogRequest* request,
                                               v1::LogChunk* reply) {
  return Reply(context, "ReadLog", [&] {
    const std::string user = auth_.User(*context);
    Require(request->offset() >= 0, "offset: negative");
    Require(request->max_bytes() >= 0 && request->max_bytes() <= kMaxLogChunk,
            "max_bytes = " + std::to_string(request->max_bytes()) +
                " is not allowed: expected 0 to " + std::to_string(kMaxLogChunk));
    const JobRecord job = OwnJob(user, request->job_id());
    // Read the state first: a job finished now has its whole log on disk already.
    reply->set_finished(IsFinished(job.state));
    int64_t size = 0;
    const int64_t max_bytes = request->max_bytes() == 0 ? kMaxLogChunk : request->max_bytes();
    reply->set_data(
        ReadPart(scheduler_.JobDir(job.id), kSolverLog, request->offset(), max_bytes, &size));
    reply->set_offset(request->offset());
    reply->set_size(size);
  });
}

grpc::ServerUnaryReactor* JobsService::GetInputs(grpc::CallbackServerContext* context,
                                                 const v1::GetInputsRequest* request,
                                                 v1::JobInputs* reply) {
  return Reply(context, "GetInputs", [&] {
    const JobRecord job = OwnJob(auth_.User(*context), request->job_id());
    reply->set_scene(job.scene);
    for (const std::string& o : job.overrides) reply->add_overrides(o);
    int64_t size = 0;
    reply->set_scene_as_run(ReadPart(job.results_dir, "scene.toml", 0, kMaxLogChunk, &size));
  });
}

grpc::ServerUnaryReactor* JobsService::Delete(grpc::CallbackServerContext* context,
                                              const v1::DeleteRequest* request,
                                              v1::DeleteResponse* reply) {
  return Reply(context, "Delete", [&] {
    const std::string user = auth_.User(*context);
    const std::vector<JobRecord> jobs = SelectedJobs(user, request->study_id(), request->job_ids());
    if (!request->force()) {
      for (const JobRecord& job : jobs) {
        // A job that waits in Slurm has not run: it is removed from Slurm's queue as a queued one
        // from the daemon's.
        if (ShownState(job) == JobState::kRunning) {
          throw ServiceError(StatusCode::FAILED_PRECONDITION,
                             "job " + job.id +
                                 " is running: delete it with force (dlmfd delete --force), "
                                 "which cancels it first");
        }
      }
    }
    std::vector<std::string> ids;
    int64_t freed = 0;
    for (const JobRecord& job : jobs) {
      if (!IsFinished(job.state)) {
        scheduler_.CancelUnlessFinished(job.id);
        scheduler_.WaitUntilStopped(job.id);
      }
      ids.push_back(job.id);
    }
    store_.Delete(ids);
    for (const std::string& id : ids) {
      const fs::path dir = scheduler_.JobDir(id);
      freed += DirectoryBytes(dir);
      std::error_code ec;
      fs::remove_all(dir, ec);
      if (ec) spdlog::warn("job {}: deleted, but {} stays: {}", id, dir.string(), ec.message());
      reply->add_deleted(id);
    }
    reply->set_freed_bytes(freed);
    spdlog::info("{} jobs deleted by {} ({} bytes)", ids.size(), user, freed);
  });
}

grpc::ServerUnaryReactor* JobsService::SetPriority(grpc::CallbackServerContext* context,
                                                   const v1::SetPriorityRequest* request,
                                                   v1::Job* reply) {
  return Reply(context, "SetPriority", [&] {
    const std::string user = auth_.User(*context);
    CheckPriority(request->priority());
    const JobRecord job = OwnJob(user, request->job_id());
    if (!store_.SetPriority(job.id, request->priority())) {
      throw ServiceError(StatusCode::FAILED_PRECONDITION,
                         "job " + job.id + " has already finished (" +
                             JobStateName(store_.Get(job.id)->state) + ")");
    }
    scheduler_.Wake();
    *reply = Reported(OwnJob(user, job.id));
  });
}

grpc::ServerUnaryReactor* JobsService::Hold(grpc::CallbackServerContext* context,
                                            const v1::HoldRequest* request, v1::Job* reply) {
  return Reply(context, "Hold", [&] {
    const std::string user = auth_.User(*context);
    const JobRecord job = OwnJob(user, request->job_id());
    if (!store_.SetHeld(job.id, true)) {
      const JobRecord now = OwnJob(user, job.id);
      if (now.state == JobState::kRunning && now.slurm_waiting) {
        throw ServiceError(StatusCode::FAILED_PRECONDITION,
                           "job " + job.id + " waits in Slurm (Slurm job " + now.slurm_job_id +
                               ", " + now.slurm_state +
                               "): only a job in the daemon's queue can be held; scontrol hold " +
                               now.slurm_job_id + " holds it in Slurm");
      }
      throw ServiceError(
          StatusCode::FAILED_PRECONDITION,
          "job " + job.id + " is " + JobStateName(now.state) + ": only a QUEUED job can be held");
    }
    *reply = Reported(OwnJob(user, job.id));
  });
}

grpc::ServerUnaryReactor* JobsService::Release(grpc::CallbackServerContext* context,
                                               const v1::HoldRequest* request, v1::Job* reply) {
  return Reply(context, "Release", [&] {
    const std::string user = auth_.User(*context);
    const JobRecord job = OwnJob(user, request->job_id());
    if (job.held && store_.SetHeld(job.id, false)) scheduler_.Wake();
    *reply = Reported(OwnJob(user, job.id));
  });
}

}  // namespace dlmfd::server
