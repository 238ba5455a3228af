// JobsService: the dlmfd.v1.Jobs rpcs (proto/dlmfd/v1/jobs.proto documents each one's error codes).
//
// Callback API: unary rpcs answer on the gRPC callback thread (scene validation and one SQLite
// transaction); Watch and Fetch are ServerWriteReactors, so 100 watchers cost no thread each. A
// Watch reactor sends from a WatcherQueue: the solver's reader thread only enqueues and, when the
// stream is idle, starts a write; it never waits for a client. Every handler runs inside Guarded(),
// so every exception becomes a status through ToStatus and none escapes into gRPC. Ownership: a job
// of another user is NOT_FOUND, never PERMISSION_DENIED.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "auth.h"
#include "config.h"
#include "dlmfd/v1/jobs.grpc.pb.h"
#include "event_hub.h"
#include "job_store.h"
#include "scheduler.h"

namespace dlmfd::server {

class JobsService final : public v1::Jobs::CallbackService {
 public:
  // clock: the creation times it records and the elapsed times it reports (clock.h).
  JobsService(const Config& config, JobStore& store, EventHub& hub, Scheduler& scheduler,
              Clock& clock = SystemClock());

  grpc::ServerUnaryReactor* Submit(grpc::CallbackServerContext* context,
                                   const v1::SubmitRequest* request, v1::Job* reply) override;
  grpc::ServerUnaryReactor* Get(grpc::CallbackServerContext* context, const v1::GetRequest* request,
                                v1::Job* reply) override;
  grpc::ServerUnaryReactor* List(grpc::CallbackServerContext* context,
                                 const v1::ListRequest* request, v1::ListResponse* reply) override;
  grpc::ServerUnaryReactor* Cancel(grpc::CallbackServerContext* context,
                                   const v1::CancelRequest* request, v1::Job* reply) override;
  grpc::ServerWriteReactor<v1::WatchEvent>* Watch(grpc::CallbackServerContext* context,
                                                  const v1::WatchRequest* request) override;
  grpc::ServerUnaryReactor* SubmitStudy(grpc::CallbackServerContext* context,
                                        const v1::SubmitStudyRequest* request,
                                        v1::SubmitStudyResponse* reply) override;
  grpc::ServerUnaryReactor* CancelStudy(grpc::CallbackServerContext* context,
                                        const v1::CancelStudyRequest* request,
                                        v1::CancelStudyResponse* reply) override;
  grpc::ServerUnaryReactor* ListStudies(grpc::CallbackServerContext* context,
                                        const v1::ListStudiesRequest* request,
                                        v1::ListStudiesResponse* reply) override;
  grpc::ServerUnaryReactor* GetStudy(grpc::CallbackServerContext* context,
                                     const v1::GetStudyRequest* request, v1::Study* reply) override;
  grpc::ServerUnaryReactor* Retry(grpc::CallbackServerContext* context,
                                  const v1::RetryRequest* request,
                                  v1::RetryResponse* reply) override;
  grpc::ServerWriteReactor<v1::FileChunk>* Fetch(grpc::CallbackServerContext* context,
                                                 const v1::FetchRequest* request) override;
  grpc::ServerUnaryReactor* ListFiles(grpc::CallbackServerContext* context,
                                      const v1::ListFilesRequest* request,
                                      v1::ListFilesResponse* reply) override;
  // Housekeeping and study rpcs (jobs_service_housekeeping.cc).
  grpc::ServerUnaryReactor* GetUsage(grpc::CallbackServerContext* context,
                                     const v1::GetUsageRequest* request, v1::Usage* reply) override;
  grpc::ServerUnaryReactor* Table(grpc::CallbackServerContext* context,
                                  const v1::TableRequest* request,
                                  v1::TableResponse* reply) override;
  grpc::ServerUnaryReactor* ReadLog(grpc::CallbackServerContext* context,
                                    const v1::ReadLogRequest* request,
                                    v1::LogChunk* reply) override;
  grpc::ServerUnaryReactor* GetInputs(grpc::CallbackServerContext* context,
                                      const v1::GetInputsRequest* request,
                                      v1::JobInputs* reply) override;
  grpc::ServerUnaryReactor* Delete(grpc::CallbackServerContext* context,
                                   const v1::DeleteRequest* request,
                                   v1::DeleteResponse* reply) override;
  grpc::ServerUnaryReactor* SetPriority(grpc::CallbackServerContext* context,
                                        const v1::SetPriorityRequest* request,
                                        v1::Job* reply) override;
  grpc::ServerUnaryReactor* Hold(grpc::CallbackServerContext* context,
                                 const v1::HoldRequest* request, v1::Job* reply) override;
  grpc::ServerUnaryReactor* Release(grpc::CallbackServerContext* context,
                                    const v1::HoldRequest* request, v1::Job* reply) override;

 private:
  // The jobs a Table or Delete request names: the study's, or each of job_ids (NOT_FOUND for one
  // that is not the caller's).
  std::vector<JobRecord> SelectedJobs(const std::string& user, const std::string& study_id,
                                      const google::protobuf::RepeatedPtrField<std::string>& ids);
  // RESOURCE_EXHAUSTED when the user's jobs hold max_user_disk_mb or more.
  void CheckDiskQuota(const std::string& user);
  // The job as an rpc reports it: last_seq is the last number issued (the hub's, while it has a
  // channel), not the end of a block reserved in the store.
  v1::Job Reported(const JobRecord& job);
  // The caller's job, or NOT_FOUND (also for another user's job).
  JobRecord OwnJob(const std::string& user, const std::string& job_id);
  // Validates and builds the record of one job to queue.
  JobRecord NewJob(const std::string& user, const std::string& scene,
                   const std::vector<std::string>& overrides, const std::string& name,
                   const std::vector<std::string>& tags, int priority,
                   const std::map<std::string, std::string>& labels);
  // The caller's study, or NOT_FOUND.
  StudyRecord OwnStudy(const std::string& user, const std::string& study_id);
  // The jobs a Retry names, each finished; throws as jobs.proto says.
  std::vector<JobRecord> RetryTargets(const std::string& user, const v1::RetryRequest& request);
  void CheckQueueRoom(int64_t adding);
  // The jobs a new job runs after (SubmitRequest.after), each once, in the order given: each must
  // be the user's (NOT_FOUND) and not have ended FAILED or CANCELLED (FAILED_PRECONDITION).
  std::vector<std::string> Dependencies(
      const std::string& user, const google::protobuf::RepeatedPtrField<std::string>& after);

  const Config& config_;
  JobStore& store_;
  EventHub& hub_;
  Clock& clock_;
  Scheduler& scheduler_;
  Authenticator auth_;
};

}  // namespace dlmfd::server
