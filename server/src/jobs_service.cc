#include "jobs_service.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <random>
#include <set>

#include "job_proto.h"
#include "job_time_limit.h"
#include "result_files.h"
#include "retry_plan.h"
#include "rpc_reply.h"
#include "scene_admission.h"
#include "scene_values.h"
#include "service_error.h"
#include "study_expansion.h"
#include "watcher_queue.h"

namespace dlmfd::server {
namespace fs = std::filesystem;
namespace {

using grpc::StatusCode;

constexpr size_t kMaxNameBytes = 256;
constexpr int kMaxTags = 32;
constexpr size_t kMaxTagBytes = 64;
constexpr size_t kMaxRequestIdBytes = 128;
constexpr int kMaxOverrides = 256;
constexpr int kDefaultPageSize = 100;
constexpr int kMaxPageSize = 1000;
constexpr int kMaxSnapshotSize = 4096;
constexpr int kMaxLabels = 32;
constexpr size_t kMaxLabelKeyBytes = 64;
constexpr size_t kMaxLabelValueBytes = 256;
constexpr int kMaxFilters = 32;

std::string NewId(char kind) {
  static thread_local std::mt19937_64 random(std::random_device{}());
  static const char kHex[] = "0123456789abcdef";
  std::string id(1, kind);
  id += '-';
  uint64_t bits = random();
  for (int i = 0; i < 16; ++i, bits >>= 4) id += kHex[bits & 15];
  return id;
}

void CheckLabels(const std::string& name, const std::vector<std::string>& tags, int priority,
                 const std::string& request_id, size_t override_count) {
  RequireNoNul("name", name);
  Require(name.size() <= kMaxNameBytes,
          "name: longer than " + std::to_string(kMaxNameBytes) + " bytes");
  Require(name.find('\n') == std::string::npos, "name: contains a line break");
  Require(static_cast<int>(tags.size()) <= kMaxTags, "tags: more than " + std::to_string(kMaxTags));
  for (const auto& tag : tags) {
    RequireNoNul("tags", tag);
    Require(!tag.empty() && tag.size() <= kMaxTagBytes,
            "tags: each must have 1 to " + std::to_string(kMaxTagBytes) + " bytes");
    Require(tag.find_first_of("\n,") == std::string::npos,
            "tags: \"" + tag + "\" contains a comma or a line break");
  }
  CheckPriority(priority);
  RequireNoNul("client_request_id", request_id);
  Require(request_id.size() <= kMaxRequestIdBytes,
          "client_request_id: longer than " + std::to_string(kMaxRequestIdBytes) + " bytes");
  Require(static_cast<int>(override_count) <= kMaxOverrides,
          "overrides: more than " + std::to_string(kMaxOverrides));
}

// Labels: keys of letters, digits and "_-./" (so `list --label k=v` needs no quoting), values
// without line breaks or NUL bytes.
void CheckJobLabels(const google::protobuf::Map<std::string, std::string>& labels) {
  Require(labels.size() <= static_cast<size_t>(kMaxLabels),
          "labels: more than " + std::to_string(kMaxLabels));
  for (const auto& [key, value] : labels) {
    const bool key_ok =
        !key.empty() && key.size() <= kMaxLabelKeyBytes &&
        std::all_of(key.begin(), key.end(), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("_-./", c) != nullptr;
        });
    Require(key_ok, "labels: key \"" + CutForMessage(key) + "\" is not allowed: expected 1 to " +
                        std::to_string(kMaxLabelKeyBytes) +
                        " letters, digits, '_', '-', '.' or '/'");
    RequireNoNul("labels: " + key, value);
    Require(value.size() <= kMaxLabelValueBytes && value.find('\n') == std::string::npos,
            "labels: " + key + " value must have at most " + std::to_string(kMaxLabelValueBytes) +
                " bytes and no line break");
  }
}

std::map<std::string, std::string> ToMap(
    const google::protobuf::Map<std::string, std::string>& labels) {
  return {labels.begin(), labels.end()};
}

// Runs body; an error it throws keeps its status code and gains `where` ("study point ...").
template <class Body>
void Naming(const std::string& where, Body&& body) {
  const grpc::Status status = Guarded(std::forward<Body>(body));
  if (!status.ok()) {
    throw ServiceError(status.error_code(), status.error_message() + " (" + where + ")");
  }
}

// The scene text and its overrides: free of NUL bytes, and together within max_scene_bytes (the
// overrides are part of the scene as run: a limit on the file alone would not bound it).
void CheckSceneText(const std::string& scene, const std::vector<std::string>& overrides,
                    int64_t max_scene_bytes) {
  RequireNoNul("scene", scene);
  int64_t bytes = static_cast<int64_t>(scene.size());
  for (const auto& text : overrides) {
    RequireNoNul("overrides", text);
    bytes += static_cast<int64_t>(text.size());
  }
  if (bytes > max_scene_bytes) {
    throw ServiceError(
        StatusCode::RESOURCE_EXHAUSTED,
        "scene and overrides: " + std::to_string(bytes) +
            " bytes, over the limit of max_scene_bytes = " + std::to_string(max_scene_bytes));
  }
}

// A retry of client_request_id must repeat the request: the same scene and, job by job, the same
// overrides. Anything else is a new request under a used id.
void CheckSameRequest(const std::string& request_id, const std::vector<JobRecord>& earlier,
                      const std::string& scene,
                      const std::vector<std::vector<std::string>>& overrides) {
  bool same = earlier.size() == overrides.size();
  for (size_t i = 0; same && i < earlier.size(); ++i) {
    same = earlier[i].scene == scene && earlier[i].overrides == overrides[i];
  }
  if (!same) {
    throw ServiceError(
        StatusCode::ALREADY_EXISTS,
        "client_request_id = \"" + CutForMessage(request_id) + "\" was used for " +
            (earlier.empty() ? std::string("another request") : "job " + earlier.front().id) +
            " with another scene or other overrides: a retry must repeat the "
            "request; use a new client_request_id for a new one");
  }
}

std::vector<std::string> ToVector(const google::protobuf::RepeatedPtrField<std::string>& field) {
  return {field.begin(), field.end()};
}

// Streams a WatcherQueue to one client.
class WatchReactor final : public grpc::ServerWriteReactor<v1::WatchEvent> {
 public:
  WatchReactor(EventHub& hub, std::string job_id, std::shared_ptr<WatcherQueue> queue)
      : hub_(hub),
        job_id_(std::move(job_id)),
        queue_(std::move(queue)) {
    queue_->SetWake([this] { Pump(); });
  }

  // Called once the queue is attached: starts sending when the attach took the token.
  void Begin(bool has_token) {
    if (has_token) Pump();
  }

  void Fail(const grpc::Status& status) { Finish(status); }

  void OnWriteDone(bool ok) override {
    if (!ok) {
      // The client is gone: drop the queue; the next Pop reports kClosed.
      queue_->Cancel();
    }
    Pump();
  }

  void OnCancel() override {
    const std::lock_guard lock(cancel_mutex_);
    if (queue_->Cancel()) Pump();
  }

  // gRPC runs OnDone after OnCancel has returned, but that order is carried by an atomic counter
  // inside libgrpc++ (1.51's ServerCallbackCall::CallOnCancel runs OnCancel on its executor, then
  // decrements the call's counter there). The teardown below frees the queue that OnCancel used,
  // so the reactor orders it after OnCancel itself: OnCancel's unlock happens before this lock.
  // Uncontended in practice; without it ThreadSanitizer reported the queue freed here while
  // OnCancel's Cancel() was its previous user (issue 38).
  void OnDone() override {
    { const std::lock_guard lock(cancel_mutex_); }
    hub_.Detach(job_id_, queue_.get());
    delete this;
  }

 private:
  // Runs only while holding the send token.
  void Pump() {
    switch (queue_->Pop(&current_)) {
      case WatcherQueue::Next::kEvent:
        StartWrite(&current_);
        break;
      case WatcherQueue::Next::kEnd:
        Finish(grpc::Status::OK);
        break;
      case WatcherQueue::Next::kClosed:
        Finish(grpc::Status(StatusCode::CANCELLED, "watch cancelled"));
        break;
      case WatcherQueue::Next::kEmpty:
        break;
    }
  }

  EventHub& hub_;
  const std::string job_id_;
  std::shared_ptr<WatcherQueue> queue_;
  v1::WatchEvent current_;
  std::mutex cancel_mutex_;  // held by OnCancel; OnDone takes it before the teardown
};

// A write reactor that only reports an error.
template <class Message>
class FailedStream final : public grpc::ServerWriteReactor<Message> {
 public:
  explicit FailedStream(const grpc::Status& status) { this->Finish(status); }
  void OnDone() override { delete this; }
};

}  // namespace

JobsService::JobsService(const Config& config, JobStore& store, EventHub& hub, Scheduler& scheduler,
                         Clock& clock)
    : config_(config),
      store_(store),
      hub_(hub),
      clock_(clock),
      scheduler_(scheduler),
      auth_(config.tokens) {}

v1::Job JobsService::Reported(const JobRecord& job) {
  v1::Job out = ToProto(job, clock_.Now());
  out.set_last_seq(hub_.ReportedLastSeq(job));
  return out;
}

JobRecord JobsService::OwnJob(const std::string& user, const std::string& job_id) {
  CheckJobId(job_id);
  auto job = store_.Get(job_id);
  if (!job || job->owner != user) {
    throw ServiceError(StatusCode::NOT_FOUND, "job " + job_id + " not found");
  }
  return *job;
}

void JobsService::CheckQueueRoom(int64_t adding) {
  const int64_t unfinished = store_.CountUnfinished();
  if (unfinished + adding > config_.max_queued) {
    const std::string limit = "max_queued = " + std::to_string(config_.max_queued);
    if (adding == 1) {
      throw ServiceError(StatusCode::RESOURCE_EXHAUSTED,
                         "the queue is full: " + std::to_string(unfinished) +
                             " unfinished jobs, at the limit of " + limit);
    }
    // A study or a retry of many: what it adds is what does not fit (issue 38: 10,000 points
    // against 1 unfinished job read "1 unfinished jobs, the limit is 10000").
    throw ServiceError(StatusCode::RESOURCE_EXHAUSTED,
                       "the queue has no room for " + std::to_string(adding) +
                           " jobs: " + std::to_string(unfinished) + " unfinished and " +
                           std::to_string(adding) + " new make " +
                           std::to_string(unfinished + adding) + ", over the limit of " + limit);
  }
}

std::vector<std::string> JobsService::Dependencies(
    const std::string& user, const google::protobuf::RepeatedPtrField<std::string>& after) {
  constexpr int kMaxDependencies = 100;
  Require(after.size() <= kMaxDependencies, "after: " + std::to_string(after.size()) +
                                                " jobs, more than " +
                                                std::to_string(kMaxDependencies));
  std::vector<std::string> ids;
  for (const std::string& id : after) {
    CheckJobId(id, "after");
    if (std::find(ids.begin(), ids.end(), id) != ids.end()) continue;
    const JobRecord job = OwnJob(user, id);
    if (job.state == JobState::kFailed || job.state == JobState::kCancelled) {
      throw ServiceError(StatusCode::FAILED_PRECONDITION,
                         "after: job " + id + " has ended " + JobStateName(job.state) +
                             ", so a job after it would never start (retry it first)");
    }
    ids.push_back(id);
  }
  return ids;
}

StudyRecord JobsService::OwnStudy(const std::string& user, const std::string& study_id) {
  CheckJobId(study_id, "study_id");
  auto study = store_.GetStudy(user, study_id);
  if (!study) throw ServiceError(StatusCode::NOT_FOUND, "study " + study_id + " not found");
  return *study;
}

JobRecord JobsService::NewJob(const std::string& user, const std::string& scene,
                              const std::vector<std::string>& overrides, const std::string& name,
                              const std::vector<std::string>& tags, int priority,
                              const std::map<std::string, std::string>& labels) {
  CheckSceneText(scene, overrides, config_.max_scene_bytes);
  SceneEstimate estimate = AdmitScene(scene, overrides, config_);
  JobRecord job;
  job.id = NewId('j');
  job.name = name.empty() ? job.id : name;
  job.owner = user;
  job.state = JobState::kQueued;
  job.priority = priority;
  job.tags = tags;
  job.created_time = clock_.Now();
  job.end_time = estimate.end_time;
  job.results_dir = fs::absolute(scheduler_.ResultsDir(job.id)).string();
  job.scene = scene;
  job.overrides = overrides;
  job.warnings = std::move(estimate.warnings);
  job.numerics = std::move(estimate.numerics);
  job.scene_values = std::move(estimate.scene_values);
  job.labels = labels;
  return job;
}

grpc::ServerUnaryReactor* JobsService::Submit(grpc::CallbackServerContext* context,
                                              const v1::SubmitRequest* request, v1::Job* reply) {
  return Reply(context, "Submit", [&] {
    const std::string user = auth_.User(*context);
    const auto overrides = ToVector(request->overrides());
    const auto tags = ToVector(request->tags());
    CheckLabels(request->name(), tags, request->priority(), request->client_request_id(),
                overrides.size());
    CheckJobLabels(request->labels());
    CheckTimeLimit(request->time_limit_seconds(), scheduler_.executor().TimeLimit());
    const std::string key =
        request->client_request_id().empty() ? "" : "submit:" + request->client_request_id();
    if (!key.empty()) {
      auto earlier = store_.FindRequest(user, key);
      if (!earlier.empty()) {
        CheckSameRequest(request->client_request_id(), earlier, request->scene(), {overrides});
        *reply = ToProto(earlier.front(), clock_.Now());
        return;
      }
    }
    CheckQueueRoom(1);
    CheckDiskQuota(user);
    const std::vector<std::string> after = Dependencies(user, request->after());
    JobRecord job = NewJob(user, request->scene(), overrides, request->name(), tags,
                           request->priority(), ToMap(request->labels()));
    job.after = after;
    job.client_request_id = request->client_request_id();
    job.time_limit_seconds = request->time_limit_seconds();
    auto result = store_.InsertJobs({job}, user, key);
    *reply = ToProto(result.jobs.front(), clock_.Now());
    if (!result.existed) {
      spdlog::info("job {}: QUEUED by {} (priority {})", job.id, user, job.priority);
      scheduler_.Wake();
    }
  });
}

grpc::ServerUnaryReactor* JobsService::Get(grpc::CallbackServerContext* context,
                                           const v1::GetRequest* request, v1::Job* reply) {
  return Reply(context, "Get",
               [&] { *reply = Reported(OwnJob(auth_.User(*context), request->job_id())); });
}

grpc::ServerUnaryReactor* JobsService::List(grpc::CallbackServerContext* context,
                                            const v1::ListRequest* request,
                                            v1::ListResponse* reply) {
  return Reply(context, "List", [&] {
    ListFilter filter;
    filter.owner = auth_.User(*context);
    Require(request->page_size() >= 0 && request->page_size() <= kMaxPageSize,
            "page_size = " + std::to_string(request->page_size()) +
                " is not allowed: expected 0 to " + std::to_string(kMaxPageSize));
    filter.limit = request->page_size() == 0 ? kDefaultPageSize : request->page_size();
    for (int state : request->states()) {
      Require(state >= static_cast<int>(JobState::kQueued) &&
                  state <= static_cast<int>(JobState::kCancelled),
              "states: unknown state " + std::to_string(state));
      filter.states.push_back(static_cast<JobState>(state));
    }
    RequireNoNul("tag", request->tag());
    RequireNoNul("study_id", request->study_id());
    filter.tag = request->tag();
    filter.study_id = request->study_id();
    Require(
        request->tags_size() + static_cast<int>(request->labels().size()) + request->where_size() <=
            kMaxFilters,
        "tags, labels, where: more than " + std::to_string(kMaxFilters) + " filters");
    for (const auto& tag : request->tags()) {
      RequireNoNul("tags", tag);
      filter.tags.push_back(tag);
    }
    for (const auto& [key, value] : request->labels()) {
      RequireNoNul("labels", key);
      RequireNoNul("labels: " + key, value);
      filter.labels[key] = value;
    }
    for (const auto& text : request->where()) {
      filter.values.push_back(ParseWhere(text));
      // A typo in a key would silently match nothing.
      Require(store_.SceneKeyKnown(filter.owner, filter.values.back().pattern),
              "where: no job of yours has the scene key \"" +
                  CutForMessage(filter.values.back().pattern) +
                  "\" (keys are the effective scene's: fluid.viscosity, particles.*.density; "
                  "`dlmfd inputs --as-run JOB` shows a job's)");
    }
    if (!filter.study_id.empty()) OwnStudy(filter.owner, filter.study_id);  // NOT_FOUND
    if (!request->page_token().empty()) {
      const std::string& token = request->page_token();
      Require(token.size() <= 18 && std::all_of(token.begin(), token.end(),
                                                [](char c) { return c >= '0' && c <= '9'; }),
              "page_token: malformed");
      filter.before_ordinal = std::stoll(token);
      Require(filter.before_ordinal > 0, "page_token: malformed");
    }
    // One more than asked tells whether there is a next page.
    ++filter.limit;
    auto jobs = store_.List(filter);
    const bool more = static_cast<int>(jobs.size()) == filter.limit;
    if (more) jobs.pop_back();
    for (const auto& job : jobs) *reply->add_jobs() = Reported(job);
    if (more) reply->set_next_page_token(std::to_string(jobs.back().ordinal));
  });
}

grpc::ServerUnaryReactor* JobsService::Cancel(grpc::CallbackServerContext* context,
                                              const v1::CancelRequest* request, v1::Job* reply) {
  return Reply(context, "Cancel", [&] {
    JobRecord job = OwnJob(auth_.User(*context), request->job_id());
    *reply = Reported(scheduler_.Cancel(job.id));
  });
}

grpc::ServerWriteReactor<v1::WatchEvent>* JobsService::Watch(grpc::CallbackServerContext* context,
                                                             const v1::WatchRequest* request) {
  JobRecord job;
  grpc::Status status = Guarded([&] {
    const std::string user = auth_.User(*context);
    Require(request->from_seq() >= 0, "from_seq: negative");
    Require(request->snapshot_max_width() >= 0 && request->snapshot_max_width() <= kMaxSnapshotSize,
            "snapshot_max_width: expected 0 to " + std::to_string(kMaxSnapshotSize));
    Require(
        request->snapshot_max_height() >= 0 && request->snapshot_max_height() <= kMaxSnapshotSize,
        "snapshot_max_height: expected 0 to " + std::to_string(kMaxSnapshotSize));
    job = OwnJob(user, request->job_id());
  });
  if (!status.ok()) return new FailedStream<v1::WatchEvent>(status);
  WatchOptions options;
  options.capacity = static_cast<size_t>(config_.watcher_buffer);
  options.include_snapshots = request->include_snapshots();
  options.max_width = request->snapshot_max_width();
  options.max_height = request->snapshot_max_height();
  auto queue = std::make_shared<WatcherQueue>(options, hub_.LogDirectory(job.id));
  auto* reactor = new WatchReactor(hub_, job.id, queue);
  bool token = false;
  status = Guarded([&] { token = hub_.Attach(job, request->from_seq(), queue); });
  if (!status.ok()) {
    // Not attached: nothing else can send on this stream.
    reactor->Fail(status);
    return reactor;
  }
  reactor->Begin(token);
  return reactor;
}

grpc::ServerUnaryReactor* JobsService::SubmitStudy(grpc::CallbackServerContext* context,
                                                   const v1::SubmitStudyRequest* request,
                                                   v1::SubmitStudyResponse* reply) {
  return Reply(context, "SubmitStudy", [&] {
    const std::string user = auth_.User(*context);
    const auto tags = ToVector(request->tags());
    CheckLabels(request->name(), tags, request->priority(), request->client_request_id(),
                static_cast<size_t>(request->overrides_size() + request->axes_size()));
    CheckJobLabels(request->labels());
    Require(request->max_running() >= 0, "max_running = " + std::to_string(request->max_running()) +
                                             " is not allowed: expected 0 (no limit) or more");
    CheckTimeLimit(request->time_limit_seconds(), scheduler_.executor().TimeLimit());
    for (const auto& axis : request->axes()) {
      RequireNoNul("axes: a key", axis.key());
      RequireNoNul("axes: " + axis.key() + " zip", axis.zip());
      for (const auto& value : axis.values()) RequireNoNul("axes: " + axis.key() + " value", value);
    }
    const StudyPlan plan = ExpandStudy(*request, config_.max_queued);
    const std::vector<StudyPoint>& points = plan.points;
    const std::string key =
        request->client_request_id().empty() ? "" : "study:" + request->client_request_id();
    if (!key.empty()) {
      auto earlier = store_.FindRequest(user, key);
      if (!earlier.empty()) {
        std::vector<std::vector<std::string>> point_overrides;
        for (const auto& point : points) point_overrides.push_back(point.overrides);
        CheckSameRequest(request->client_request_id(), earlier, request->scene(), point_overrides);
        reply->set_study_id(earlier.front().study_id);
        for (const auto& job : earlier) *reply->add_jobs() = ToProto(job, clock_.Now());
        return;
      }
    }
    CheckQueueRoom(static_cast<int64_t>(points.size()));
    CheckDiskQuota(user);
    const std::vector<std::string> after = Dependencies(user, request->after());
    const std::string study_id = NewId('s');
    const auto labels = ToMap(request->labels());
    std::vector<JobRecord> jobs;
    for (const StudyPoint& point : points) {
      std::vector<std::string> job_tags = tags;
      job_tags.push_back(study_id);
      const std::string name =
          (request->name().empty() ? study_id : request->name()) + "[" + point.label + "]";
      // Whatever the point's admission throws keeps its status (ToStatus) and names the point.
      Naming("study point " + point.label, [&] {
        jobs.push_back(NewJob(user, request->scene(), point.overrides, name, job_tags,
                              request->priority(), labels));
      });
      jobs.back().study_id = study_id;
      jobs.back().client_request_id = request->client_request_id();
      jobs.back().parameters = point.parameters;
      jobs.back().time_limit_seconds = request->time_limit_seconds();
      jobs.back().after = after;
    }
    StudyRecord study;
    study.id = study_id;
    study.owner = user;
    study.name = request->name().empty() ? study_id : request->name();
    study.tags = tags;
    study.labels = labels;
    study.axes = plan.axes;
    study.overrides.assign(request->overrides().begin(), request->overrides().end());
    study.max_running = request->max_running();
    study.created_time = clock_.Now();
    auto result = store_.InsertJobs(std::move(jobs), user, key, &study);
    reply->set_study_id(result.jobs.front().study_id);
    for (const auto& job : result.jobs) *reply->add_jobs() = ToProto(job, clock_.Now());
    if (!result.existed) {
      spdlog::info("study {}: {} jobs QUEUED by {}", study_id, result.jobs.size(), user);
      scheduler_.Wake();
    }
  });
}

grpc::ServerUnaryReactor* JobsService::CancelStudy(grpc::CallbackServerContext* context,
                                                   const v1::CancelStudyRequest* request,
                                                   v1::CancelStudyResponse* reply) {
  return Reply(context, "CancelStudy", [&] {
    const std::string user = auth_.User(*context);
    Require(!request->study_id().empty(), "study_id: empty");
    RequireNoNul("study_id", request->study_id());
    auto jobs = store_.StudyJobs(user, request->study_id());
    if (jobs.empty()) {
      throw ServiceError(StatusCode::NOT_FOUND, "study " + request->study_id() + " not found");
    }
    for (const auto& job : jobs) {
      if (!IsFinished(job.state)) scheduler_.CancelUnlessFinished(job.id);
    }
    for (const auto& job : store_.StudyJobs(user, request->study_id())) {
      *reply->add_jobs() = ToProto(job, clock_.Now());
    }
  });
}

grpc::ServerUnaryReactor* JobsService::ListStudies(grpc::CallbackServerContext* context,
                                                   const v1::ListStudiesRequest* request,
                                                   v1::ListStudiesResponse* reply) {
  return Reply(context, "ListStudies", [&] {
    const std::string user = auth_.User(*context);
    Require(request->page_size() >= 0 && request->page_size() <= kMaxPageSize,
            "page_size = " + std::to_string(request->page_size()) +
                " is not allowed: expected 0 to " + std::to_string(kMaxPageSize));
    RequireNoNul("tag", request->tag());
    int64_t before = 0;
    if (!request->page_token().empty()) {
      const std::string& token = request->page_token();
      Require(token.size() <= 18 && std::all_of(token.begin(), token.end(),
                                                [](char c) { return c >= '0' && c <= '9'; }),
              "page_token: malformed");
      before = std::stoll(token);
      Require(before > 0, "page_token: malformed");
    }
    const int limit = request->page_size() == 0 ? kDefaultPageSize : request->page_size();
    auto studies = store_.ListStudies(user, request->tag(), before, limit + 1);
    const bool more = static_cast<int>(studies.size()) == limit + 1;
    if (more) studies.pop_back();
    for (const auto& study : studies) {
      *reply->add_studies() = ToProto(study, store_.StatsOfStudy(user, study.id));
    }
    if (more) reply->set_next_page_token(std::to_string(studies.back().ordinal));
  });
}

grpc::ServerUnaryReactor* JobsService::GetStudy(grpc::CallbackServerContext* context,
                                                const v1::GetStudyRequest* request,
                                                v1::Study* reply) {
  return Reply(context, "GetStudy", [&] {
    const std::string user = auth_.User(*context);
    const StudyRecord study = OwnStudy(user, request->study_id());
    *reply = ToProto(study, store_.StatsOfStudy(user, study.id));
  });
}

std::vector<JobRecord> JobsService::RetryTargets(const std::string& user,
                                                 const v1::RetryRequest& request) {
  Require((request.job_ids_size() > 0) != !request.study_id().empty(),
          "job_ids, study_id: give job ids or a study id, not both and not neither");
  std::vector<JobRecord> jobs;
  if (request.job_ids_size() > 0) {
    Require(request.states_size() == 0, "states: only with study_id");
    Require(request.job_ids_size() <= kMaxPageSize,
            "job_ids: more than " + std::to_string(kMaxPageSize));
    std::set<std::string> seen;
    for (const auto& id : request.job_ids()) {
      JobRecord job = OwnJob(user, id);
      Require(seen.insert(id).second, "job_ids: " + id + " appears twice");
      if (!IsFinished(job.state)) {
        throw ServiceError(StatusCode::FAILED_PRECONDITION,
                           "job " + id + " is " + JobStateName(job.state) +
                               ": only a finished job (COMPLETED, FAILED, CANCELLED) is retried");
      }
      jobs.push_back(std::move(job));
    }
    return jobs;
  }
  const StudyRecord study = OwnStudy(user, request.study_id());
  std::set<JobState> states;
  for (int state : request.states()) {
    Require(state >= static_cast<int>(JobState::kQueued) &&
                state <= static_cast<int>(JobState::kCancelled),
            "states: unknown state " + std::to_string(state));
    Require(IsFinished(static_cast<JobState>(state)),
            std::string("states: ") + JobStateName(static_cast<JobState>(state)) +
                " is not allowed: expected COMPLETED, FAILED or CANCELLED");
    states.insert(static_cast<JobState>(state));
  }
  if (states.empty()) states = {JobState::kFailed, JobState::kCancelled};
  for (auto& job : store_.StudyJobs(user, study.id)) {
    if (states.count(job.state)) jobs.push_back(std::move(job));
  }
  if (jobs.empty()) {
    std::string names;
    for (JobState state : states)
      names += (names.empty() ? "" : ", ") + std::string(JobStateName(state));
    throw ServiceError(StatusCode::FAILED_PRECONDITION,
                       "study " + study.id + " has no job in the states " + names);
  }
  return jobs;
}

grpc::ServerUnaryReactor* JobsService::Retry(grpc::CallbackServerContext* context,
                                             const v1::RetryRequest* request,
                                             v1::RetryResponse* reply) {
  return Reply(context, "Retry", [&] {
    const std::string user = auth_.User(*context);
    const auto changes = ToVector(request->overrides());
    Require(static_cast<int>(changes.size()) <= kMaxOverrides,
            "overrides: more than " + std::to_string(kMaxOverrides));
    for (const auto& text : changes) {
      RequireNoNul("overrides", text);
      Require(text.find('=') != std::string::npos && text.find('=') > 0,
              "overrides: \"" + CutForMessage(text) + "\" is not allowed: expected key=value");
    }
    const std::vector<JobRecord> jobs = RetryTargets(user, *request);
    CheckQueueRoom(static_cast<int64_t>(jobs.size()));
    CheckDiskQuota(user);  // a rerun writes as much as a new job
    std::vector<RequeueChange> plan;
    for (const JobRecord& job : jobs) {
      RequeueChange change;
      change.id = job.id;
      change.overrides = MergeOverrides(job.overrides, changes);
      Naming("job " + job.id, [&] {
        CheckSceneText(job.scene, change.overrides, config_.max_scene_bytes);
        SceneEstimate estimate = AdmitScene(job.scene, change.overrides, config_);
        change.warnings = std::move(estimate.warnings);
        change.numerics = std::move(estimate.numerics);
        change.scene_values = std::move(estimate.scene_values);
        change.end_time = estimate.end_time;
      });
      change.parameters = UpdatedParameters(job.parameters, changes);
      change.name = RenamedPoint(job.name, job.parameters, change.parameters);
      change.fresh_start = !ResumesFromCheckpoint(job, change.overrides);
      plan.push_back(std::move(change));
    }
    // The records as the requeue wrote them: the scheduler may start a job before a fresh read
    // (the reply and the QUEUED event then said RUNNING, ahead of the scheduler's own event).
    const std::vector<JobRecord> requeued = store_.Requeue(plan);
    for (std::size_t k = 0; k < requeued.size(); ++k) {
      const JobRecord& job = requeued[k];
      spdlog::info("job {}: QUEUED again by {} (attempt {}, {})", job.id, user, job.attempt,
                   plan[k].fresh_start ? "fresh start" : "resumes from its checkpoint");
      // A fresh start is a new timeline: its steps are published again from 0 (event_hub.h).
      hub_.PublishState(job, plan[k].fresh_start);
      *reply->add_jobs() = Reported(job);
    }
    scheduler_.Wake();
  });
}

grpc::ServerWriteReactor<v1::FileChunk>* JobsService::Fetch(grpc::CallbackServerContext* context,
                                                            const v1::FetchRequest* request) {
  fs::path root;
  std::vector<std::string> files;
  grpc::Status status = Guarded([&] {
    JobRecord job = OwnJob(auth_.User(*context), request->job_id());
    root = job.results_dir;
    if (request->path().empty()) {
      files = ResultFilePaths(root);
    } else {
      files.push_back(CheckedResultPath(root, request->path()));
    }
  });
  if (!status.ok()) return new FailedStream<v1::FileChunk>(status);
  return new FetchReactor(root, std::move(files));
}

grpc::ServerUnaryReactor* JobsService::ListFiles(grpc::CallbackServerContext* context,
                                                 const v1::ListFilesRequest* request,
                                                 v1::ListFilesResponse* reply) {
  return Reply(context, "ListFiles", [&] {
    JobRecord job = OwnJob(auth_.User(*context), request->job_id());
    DescribeResultFiles(job.results_dir, reply);
  });
}

}  // namespace dlmfd::server
