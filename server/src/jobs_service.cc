#include "jobs_service.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>

#include "job_proto.h"
#include "scene_admission.h"
#include "service_error.h"
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
constexpr int kMaxPriority = 1000;
constexpr int kDefaultPageSize = 100;
constexpr int kMaxPageSize = 1000;
constexpr int kMaxSnapshotSize = 4096;
constexpr int64_t kChunkBytes = 1 << 20;

std::string NewId(char kind) {
  static thread_local std::mt19937_64 random(std::random_device{}());
  static const char kHex[] = "0123456789abcdef";
  std::string id(1, kind);
  id += '-';
  uint64_t bits = random();
  for (int i = 0; i < 16; ++i, bits >>= 4) id += kHex[bits & 15];
  return id;
}

void Require(bool ok, const std::string& message) {
  if (!ok) throw ServiceError(StatusCode::INVALID_ARGUMENT, message);
}

void CheckJobId(const std::string& id) {
  Require(!id.empty(), "job_id: empty");
  Require(id.size() <= 64, "job_id: too long");
}

void CheckLabels(const std::string& name, const std::vector<std::string>& tags, int priority,
                 const std::string& request_id, size_t override_count) {
  Require(name.size() <= kMaxNameBytes, "name: longer than 256 bytes");
  Require(name.find('\n') == std::string::npos, "name: contains a line break");
  Require(static_cast<int>(tags.size()) <= kMaxTags, "tags: more than 32");
  for (const auto& tag : tags) {
    Require(!tag.empty() && tag.size() <= kMaxTagBytes, "tags: each must have 1 to 64 bytes");
    Require(tag.find_first_of("\n,") == std::string::npos,
            "tags: \"" + tag + "\" contains a comma or a line break");
  }
  Require(priority >= -kMaxPriority && priority <= kMaxPriority,
          "priority = " + std::to_string(priority) + " is not allowed: expected -1000 to 1000");
  Require(request_id.size() <= kMaxRequestIdBytes, "client_request_id: longer than 128 bytes");
  Require(static_cast<int>(override_count) <= kMaxOverrides, "overrides: more than 256");
}

std::vector<std::string> ToVector(const google::protobuf::RepeatedPtrField<std::string>& field) {
  return {field.begin(), field.end()};
}

// A unary reply: runs body under Guarded and finishes the default reactor with its status.
template <class Body>
grpc::ServerUnaryReactor* Reply(grpc::CallbackServerContext* context, const char* rpc,
                                Body&& body) {
  auto* reactor = context->DefaultReactor();
  grpc::Status status = Guarded(std::forward<Body>(body));
  if (!status.ok() && status.error_code() == StatusCode::INTERNAL) {
    spdlog::error("{}: {}", rpc, status.error_message());
  }
  reactor->Finish(status);
  return reactor;
}

// The files under a results directory, relative paths, sorted.
std::vector<std::pair<std::string, fs::directory_entry>> ResultFiles(const fs::path& root) {
  std::vector<std::pair<std::string, fs::directory_entry>> files;
  std::error_code error;
  if (!fs::is_directory(root, error)) return files;
  for (auto it = fs::recursive_directory_iterator(root, error);
       !error && it != fs::recursive_directory_iterator(); it.increment(error)) {
    if (it->is_regular_file(error)) {
      files.emplace_back(fs::relative(it->path(), root, error).generic_string(), *it);
    }
  }
  std::sort(files.begin(), files.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  return files;
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
    if (queue_->Cancel()) Pump();
  }

  void OnDone() override {
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
};

// Streams result files in chunks of at most 1 MiB.
class FetchReactor final : public grpc::ServerWriteReactor<v1::FileChunk> {
 public:
  FetchReactor(fs::path root, std::vector<std::string> files)
      : root_(std::move(root)),
        files_(std::move(files)) {
    Next();
  }
  void OnWriteDone(bool ok) override {
    if (!ok) {
      Finish(grpc::Status(StatusCode::CANCELLED, "fetch cancelled"));
      return;
    }
    Next();
  }
  void OnDone() override { delete this; }

 private:
  void Next() {
    grpc::Status status = Guarded([&] {
      while (true) {
        if (!in_.is_open()) {
          if (index_ >= files_.size()) {
            done_ = true;
            return;
          }
          const fs::path path = root_ / files_[index_];
          in_.open(path, std::ios::binary);
          if (!in_) throw ServiceError(StatusCode::NOT_FOUND, files_[index_] + ": cannot be read");
          std::error_code error;
          size_ = static_cast<int64_t>(fs::file_size(path, error));
          offset_ = 0;
        }
        const int64_t length =
            std::min<int64_t>(kChunkBytes, std::max<int64_t>(size_ - offset_, 0));
        chunk_.Clear();
        chunk_.set_path(files_[index_]);
        chunk_.set_offset(offset_);
        chunk_.set_size(size_);
        std::string* data = chunk_.mutable_data();
        data->resize(static_cast<size_t>(length));
        in_.read(data->data(), length);
        data->resize(static_cast<size_t>(in_.gcount()));
        offset_ += static_cast<int64_t>(data->size());
        const bool last = offset_ >= size_ || data->empty();
        chunk_.set_last(last);
        if (last) {
          in_.close();
          in_.clear();
          ++index_;
        }
        return;
      }
    });
    if (!status.ok()) {
      Finish(status);
    } else if (done_) {
      Finish(grpc::Status::OK);
    } else {
      StartWrite(&chunk_);
    }
  }

  const fs::path root_;
  const std::vector<std::string> files_;
  size_t index_ = 0;
  std::ifstream in_;
  int64_t size_ = 0, offset_ = 0;
  bool done_ = false;
  v1::FileChunk chunk_;
};

// A write reactor that only reports an error.
template <class Message>
class FailedStream final : public grpc::ServerWriteReactor<Message> {
 public:
  explicit FailedStream(const grpc::Status& status) { this->Finish(status); }
  void OnDone() override { delete this; }
};

}  // namespace

JobsService::JobsService(const Config& config, JobStore& store, EventHub& hub, Scheduler& scheduler)
    : config_(config),
      store_(store),
      hub_(hub),
      scheduler_(scheduler),
      auth_(config.tokens) {}

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
    throw ServiceError(StatusCode::RESOURCE_EXHAUSTED,
                       "the queue is full: " + std::to_string(unfinished) +
                           " unfinished jobs, the limit is " + std::to_string(config_.max_queued));
  }
}

JobRecord JobsService::NewJob(const std::string& user, const std::string& scene,
                              const std::vector<std::string>& overrides, const std::string& name,
                              const std::vector<std::string>& tags, int priority) {
  SceneEstimate estimate = AdmitScene(scene, overrides, config_);
  JobRecord job;
  job.id = NewId('j');
  job.name = name.empty() ? job.id : name;
  job.owner = user;
  job.state = JobState::kQueued;
  job.priority = priority;
  job.tags = tags;
  job.created_time = NowSeconds();
  job.end_time = estimate.end_time;
  job.results_dir = fs::absolute(scheduler_.ResultsDir(job.id)).string();
  job.scene = scene;
  job.overrides = overrides;
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
    const std::string key =
        request->client_request_id().empty() ? "" : "submit:" + request->client_request_id();
    if (!key.empty()) {
      auto earlier = store_.FindRequest(user, key);
      if (!earlier.empty()) {
        *reply = ToProto(earlier.front());
        return;
      }
    }
    CheckQueueRoom(1);
    JobRecord job =
        NewJob(user, request->scene(), overrides, request->name(), tags, request->priority());
    job.client_request_id = request->client_request_id();
    auto result = store_.InsertJobs({job}, user, key);
    *reply = ToProto(result.jobs.front());
    if (!result.existed) {
      spdlog::info("job {}: QUEUED by {} (priority {})", job.id, user, job.priority);
      scheduler_.Wake();
    }
  });
}

grpc::ServerUnaryReactor* JobsService::Get(grpc::CallbackServerContext* context,
                                           const v1::GetRequest* request, v1::Job* reply) {
  return Reply(context, "Get",
               [&] { *reply = ToProto(OwnJob(auth_.User(*context), request->job_id())); });
}

grpc::ServerUnaryReactor* JobsService::List(grpc::CallbackServerContext* context,
                                            const v1::ListRequest* request,
                                            v1::ListResponse* reply) {
  return Reply(context, "List", [&] {
    ListFilter filter;
    filter.owner = auth_.User(*context);
    Require(request->page_size() >= 0 && request->page_size() <= kMaxPageSize,
            "page_size = " + std::to_string(request->page_size()) +
                " is not allowed: expected 0 to 1000");
    filter.limit = request->page_size() == 0 ? kDefaultPageSize : request->page_size();
    for (int state : request->states()) {
      Require(state >= static_cast<int>(JobState::kQueued) &&
                  state <= static_cast<int>(JobState::kCancelled),
              "states: unknown state " + std::to_string(state));
      filter.states.push_back(static_cast<JobState>(state));
    }
    filter.tag = request->tag();
    filter.sweep_id = request->sweep_id();
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
    for (const auto& job : jobs) *reply->add_jobs() = ToProto(job);
    if (more) reply->set_next_page_token(std::to_string(jobs.back().ordinal));
  });
}

grpc::ServerUnaryReactor* JobsService::Cancel(grpc::CallbackServerContext* context,
                                              const v1::CancelRequest* request, v1::Job* reply) {
  return Reply(context, "Cancel", [&] {
    JobRecord job = OwnJob(auth_.User(*context), request->job_id());
    *reply = ToProto(scheduler_.Cancel(job.id));
  });
}

grpc::ServerWriteReactor<v1::WatchEvent>* JobsService::Watch(grpc::CallbackServerContext* context,
                                                             const v1::WatchRequest* request) {
  JobRecord job;
  grpc::Status status = Guarded([&] {
    const std::string user = auth_.User(*context);
    Require(request->from_seq() >= 0, "from_seq: negative");
    Require(request->snapshot_max_width() >= 0 && request->snapshot_max_width() <= kMaxSnapshotSize,
            "snapshot_max_width: expected 0 to 4096");
    Require(
        request->snapshot_max_height() >= 0 && request->snapshot_max_height() <= kMaxSnapshotSize,
        "snapshot_max_height: expected 0 to 4096");
    job = OwnJob(user, request->job_id());
  });
  if (!status.ok()) return new FailedStream<v1::WatchEvent>(status);
  WatchOptions options;
  options.capacity = static_cast<size_t>(config_.watcher_buffer);
  options.include_snapshots = request->include_snapshots();
  options.max_width = request->snapshot_max_width();
  options.max_height = request->snapshot_max_height();
  auto queue = std::make_shared<WatcherQueue>(options);
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

grpc::ServerUnaryReactor* JobsService::SubmitSweep(grpc::CallbackServerContext* context,
                                                   const v1::SubmitSweepRequest* request,
                                                   v1::SubmitSweepResponse* reply) {
  return Reply(context, "SubmitSweep", [&] {
    const std::string user = auth_.User(*context);
    const auto base = ToVector(request->overrides());
    const auto tags = ToVector(request->tags());
    CheckLabels(request->name(), tags, request->priority(), request->client_request_id(),
                base.size() + static_cast<size_t>(request->axes_size()));
    Require(request->axes_size() > 0, "axes: at least one axis is needed");
    std::set<std::string> keys;
    int64_t points = 1;
    for (const auto& axis : request->axes()) {
      Require(!axis.key().empty(), "axes: an axis has no key");
      Require(axis.key().find_first_of("=\n") == std::string::npos,
              "axes: key \"" + axis.key() + "\" contains '=' or a line break");
      Require(keys.insert(axis.key()).second, "axes: key " + axis.key() + " appears twice");
      Require(axis.values_size() > 0, "axes: " + axis.key() + " has no values");
      points *= axis.values_size();
      if (points > config_.max_queued) {
        throw ServiceError(
            StatusCode::RESOURCE_EXHAUSTED,
            "the sweep has more points than max_queued = " + std::to_string(config_.max_queued));
      }
    }
    const std::string key =
        request->client_request_id().empty() ? "" : "sweep:" + request->client_request_id();
    if (!key.empty()) {
      auto earlier = store_.FindRequest(user, key);
      if (!earlier.empty()) {
        reply->set_sweep_id(earlier.front().sweep_id);
        for (const auto& job : earlier) *reply->add_jobs() = ToProto(job);
        return;
      }
    }
    CheckQueueRoom(points);
    const std::string sweep_id = NewId('s');
    std::vector<JobRecord> jobs;
    std::vector<int> index(static_cast<size_t>(request->axes_size()), 0);
    for (int64_t p = 0; p < points; ++p) {
      std::vector<std::string> overrides = base;
      std::string label;
      for (int a = 0; a < request->axes_size(); ++a) {
        const auto& axis = request->axes(a);
        const std::string pair = axis.key() + "=" + axis.values(index[static_cast<size_t>(a)]);
        overrides.push_back(pair);
        label += (a ? "," : "") + pair;
      }
      std::vector<std::string> job_tags = tags;
      job_tags.push_back(sweep_id);
      const std::string name =
          (request->name().empty() ? sweep_id : request->name()) + "[" + label + "]";
      try {
        jobs.push_back(
            NewJob(user, request->scene(), overrides, name, job_tags, request->priority()));
      } catch (const ServiceError& e) {
        throw ServiceError(e.code(), std::string(e.what()) + " (sweep point " + label + ")");
      } catch (const std::exception& e) {
        throw ServiceError(StatusCode::INVALID_ARGUMENT,
                           std::string(e.what()) + " (sweep point " + label + ")");
      }
      jobs.back().sweep_id = sweep_id;
      jobs.back().client_request_id = request->client_request_id();
      for (int a = request->axes_size() - 1; a >= 0; --a) {
        auto& i = index[static_cast<size_t>(a)];
        if (++i < request->axes(a).values_size()) break;
        i = 0;
      }
    }
    auto result = store_.InsertJobs(std::move(jobs), user, key);
    reply->set_sweep_id(result.jobs.front().sweep_id);
    for (const auto& job : result.jobs) *reply->add_jobs() = ToProto(job);
    if (!result.existed) {
      spdlog::info("sweep {}: {} jobs QUEUED by {}", sweep_id, result.jobs.size(), user);
      scheduler_.Wake();
    }
  });
}

grpc::ServerUnaryReactor* JobsService::CancelSweep(grpc::CallbackServerContext* context,
                                                   const v1::CancelSweepRequest* request,
                                                   v1::CancelSweepResponse* reply) {
  return Reply(context, "CancelSweep", [&] {
    const std::string user = auth_.User(*context);
    Require(!request->sweep_id().empty(), "sweep_id: empty");
    auto jobs = store_.SweepJobs(user, request->sweep_id());
    if (jobs.empty()) {
      throw ServiceError(StatusCode::NOT_FOUND, "sweep " + request->sweep_id() + " not found");
    }
    for (const auto& job : jobs) {
      if (IsFinished(job.state)) continue;
      try {
        scheduler_.Cancel(job.id);
      } catch (const ServiceError& e) {
        if (e.code() != StatusCode::FAILED_PRECONDITION) throw;  // finished meanwhile
      }
    }
    for (const auto& job : store_.SweepJobs(user, request->sweep_id())) {
      *reply->add_jobs() = ToProto(job);
    }
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
      for (auto& [path, entry] : ResultFiles(root)) files.push_back(path);
      return;
    }
    const fs::path wanted(request->path());
    Require(wanted.is_relative(), "path: must be relative to the results directory");
    for (const auto& part : wanted) {
      Require(part != "..", "path: must not contain \"..\"");
    }
    std::error_code error;
    const fs::path full = fs::weakly_canonical(root / wanted, error);
    const fs::path base = fs::weakly_canonical(root, error);
    const std::string full_text = full.string(), base_text = base.string() + "/";
    Require(!error && full_text.compare(0, base_text.size(), base_text) == 0,
            "path: leaves the results directory");
    if (!fs::is_regular_file(full, error)) {
      throw ServiceError(StatusCode::NOT_FOUND, "file " + request->path() + " not found");
    }
    files.push_back(wanted.lexically_normal().generic_string());
  });
  if (!status.ok()) return new FailedStream<v1::FileChunk>(status);
  return new FetchReactor(root, std::move(files));
}

grpc::ServerUnaryReactor* JobsService::ListFiles(grpc::CallbackServerContext* context,
                                                 const v1::ListFilesRequest* request,
                                                 v1::ListFilesResponse* reply) {
  return Reply(context, "ListFiles", [&] {
    JobRecord job = OwnJob(auth_.User(*context), request->job_id());
    for (auto& [path, entry] : ResultFiles(job.results_dir)) {
      std::error_code error;
      auto* info = reply->add_files();
      info->set_path(path);
      info->set_size(static_cast<int64_t>(entry.file_size(error)));
      const auto modified = entry.last_write_time(error);
      const auto system = std::chrono::time_point_cast<std::chrono::system_clock::duration>(
          modified - fs::file_time_type::clock::now() + std::chrono::system_clock::now());
      info->set_modified_time(std::chrono::duration<double>(system.time_since_epoch()).count());
    }
  });
}

}  // namespace dlmfd::server
