#include "job_watch_set.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <utility>

namespace dlmfd::web {
namespace {

std::atomic<int> open_streams{0};

}  // namespace

int JobWatchSet::OpenStreams() { return open_streams.load(); }

class JobWatchSet::Reactor : public grpc::ClientReadReactor<v1::WatchEvent> {
 public:
  Reactor(JobWatchSet* owner, std::string job_id, std::unique_ptr<grpc::ClientContext> context,
          v1::WatchRequest request)
      : owner_(owner),
        job_id_(std::move(job_id)),
        context_(std::move(context)),
        request_(std::move(request)) {}

  void Start(v1::Jobs::Stub& stub) {
    stub.async()->Watch(context_.get(), &request_, this);
    StartRead(&event_);
    StartCall();
  }
  void Cancel() { context_->TryCancel(); }

  void OnReadDone(bool ok) override {
    if (!ok) return;  // the stream ends; OnDone follows
    owner_->Deliver(job_id_, event_);
    StartRead(&event_);
  }
  void OnDone(const grpc::Status& status) override {
    owner_->Ended(this, job_id_, status);
    delete this;  // gRPC touches a reactor no more once OnDone runs
  }

 private:
  JobWatchSet* owner_;
  const std::string job_id_;
  std::unique_ptr<grpc::ClientContext> context_;
  v1::WatchRequest request_;
  v1::WatchEvent event_;
};

JobWatchSet::JobWatchSet(DaemonLink& link, std::string token, bool include_snapshots,
                         std::size_t queue_limit)
    : link_(link),
      token_(std::move(token)),
      include_snapshots_(include_snapshots),
      queue_limit_(std::max<std::size_t>(queue_limit, 8)) {}

JobWatchSet::~JobWatchSet() {
  std::unique_lock<std::mutex> lock(mutex_);
  closing_ = true;
  for (auto& [id, stream] : streams_) {
    if (stream.reactor != nullptr) stream.reactor->Cancel();
  }
  changed_.wait(lock, [&] { return live_reactors_ == 0; });
}

void JobWatchSet::Follow(const std::string& job_id, std::int64_t from_seq) {
  Reactor* reactor = nullptr;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closing_) return;
    Stream& stream = streams_[job_id];
    if (stream.reactor != nullptr || stream.waiting) return;
    stream.last_seq = std::max(stream.last_seq, from_seq);
    reactor = StartLocked(job_id, stream);
  }
  // Started outside the lock: gRPC may run a reaction on this thread.
  reactor->Start(link_.jobs());
}

bool JobWatchSet::Follows(const std::string& job_id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = streams_.find(job_id);
  return it != streams_.end() && (it->second.reactor != nullptr || it->second.waiting);
}

std::size_t JobWatchSet::Active() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::size_t n = 0;
  for (const auto& [id, stream] : streams_) n += stream.reactor != nullptr || stream.waiting;
  return n;
}

JobWatchSet::Reactor* JobWatchSet::StartLocked(const std::string& job_id, Stream& stream) {
  v1::WatchRequest request;
  request.set_job_id(job_id);
  request.set_from_seq(stream.last_seq);
  request.set_include_snapshots(include_snapshots_);
  request.set_snapshot_max_width(2);
  request.set_snapshot_max_height(2);
  stream.waiting = false;
  stream.reactor = new Reactor(this, job_id, link_.Stream(token_), std::move(request));
  ++live_reactors_;
  ++open_streams;
  return stream.reactor;
}

void JobWatchSet::PushLocked(WatchItem item) {
  if (queue_.size() >= queue_limit_ && item.kind == WatchItem::Kind::kEvent &&
      !item.event.has_state()) {
    auto droppable = std::find_if(queue_.begin(), queue_.end(), [](const WatchItem& queued) {
      return queued.kind == WatchItem::Kind::kEvent && !queued.event.has_state();
    });
    if (droppable != queue_.end()) {
      queue_.erase(droppable);
    } else {
      ++dropped_;
      return;
    }
    ++dropped_;
  }
  queue_.push_back(std::move(item));
  changed_.notify_all();
}

void JobWatchSet::Deliver(const std::string& job_id, const v1::WatchEvent& event) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (closing_) return;
  Stream& stream = streams_[job_id];
  if (event.seq() > stream.last_seq) stream.last_seq = event.seq();
  stream.backoff = std::chrono::milliseconds(200);
  if (lost_) {
    lost_ = false;
    PushLocked({WatchItem::Kind::kRestored, job_id, {}, {}});
  }
  PushLocked({WatchItem::Kind::kEvent, job_id, event, {}});
}

void JobWatchSet::Ended(Reactor* reactor, const std::string& job_id, const grpc::Status& status) {
  std::lock_guard<std::mutex> lock(mutex_);
  --live_reactors_;
  --open_streams;
  Stream& stream = streams_[job_id];
  if (stream.reactor == reactor) stream.reactor = nullptr;
  if (!closing_) {
    const grpc::StatusCode code = status.error_code();
    const bool permanent = code == grpc::StatusCode::OK || code == grpc::StatusCode::NOT_FOUND ||
                           code == grpc::StatusCode::UNAUTHENTICATED ||
                           code == grpc::StatusCode::PERMISSION_DENIED ||
                           code == grpc::StatusCode::INVALID_ARGUMENT;
    if (permanent) {
      PushLocked({WatchItem::Kind::kEnded, job_id, {}, status});
    } else {
      stream.waiting = true;
      stream.retry_at = std::chrono::steady_clock::now() + stream.backoff;
      stream.backoff = std::min(stream.backoff * 2, std::chrono::milliseconds(2000));
      if (!lost_) {
        lost_ = true;
        PushLocked({WatchItem::Kind::kLost, job_id, {}, status});
      }
    }
  }
  changed_.notify_all();
}

WatchBatch JobWatchSet::Next(std::chrono::milliseconds wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto deadline = std::chrono::steady_clock::now() + wait;
  while (queue_.empty() && dropped_ == 0) {
    auto until = deadline;
    for (const auto& [id, stream] : streams_) {
      if (stream.waiting) until = std::min(until, stream.retry_at);
    }
    changed_.wait_until(lock, until);
    const auto now = std::chrono::steady_clock::now();
    std::vector<Reactor*> restarted;
    for (auto& [id, stream] : streams_) {
      if (stream.waiting && stream.retry_at <= now && !closing_) {
        restarted.push_back(StartLocked(id, stream));
      }
    }
    if (!restarted.empty()) {
      lock.unlock();  // gRPC may run a reaction on this thread
      for (Reactor* reactor : restarted) reactor->Start(link_.jobs());
      lock.lock();
    }
    if (now >= deadline) break;
  }
  WatchBatch batch;
  batch.items.assign(std::make_move_iterator(queue_.begin()),
                     std::make_move_iterator(queue_.end()));
  queue_.clear();
  batch.dropped = dropped_;
  dropped_ = 0;
  return batch;
}

}  // namespace dlmfd::web
