#include "watcher_queue.h"

#include <algorithm>
#include <cmath>

#include "job_proto.h"

namespace dlmfd::server {
namespace {

// Indices of `count` nodes spread evenly over n nodes, ends included.
int SourceIndex(int i, int count, int n) {
  if (count <= 1) return 0;
  return static_cast<int>(std::lround(static_cast<double>(i) * (n - 1) / (count - 1)));
}

}  // namespace

v1::Snapshot DownsampleSnapshot(const v1::Snapshot& full, int max_width, int max_height) {
  const int nodes_x = full.nx() + 1, nodes_y = full.ny() + 1;
  if (static_cast<int64_t>(nodes_x) * nodes_y != full.values_size()) return full;
  const int out_x = max_width > 0 ? std::min(max_width, nodes_x) : nodes_x;
  const int out_y = max_height > 0 ? std::min(max_height, nodes_y) : nodes_y;
  if (out_x == nodes_x && out_y == nodes_y) return full;
  v1::Snapshot out;
  out.set_nx(out_x - 1);
  out.set_ny(out_y - 1);
  out.set_time(full.time());
  out.set_step(full.step());
  out.set_quantity(full.quantity());
  out.set_width(full.width());
  out.set_height(full.height());
  out.mutable_values()->Reserve(out_x * out_y);
  for (int j = 0; j < out_y; ++j) {
    const int sj = SourceIndex(j, out_y, nodes_y);
    for (int i = 0; i < out_x; ++i) {
      out.add_values(full.values(sj * nodes_x + SourceIndex(i, out_x, nodes_x)));
    }
  }
  return out;
}

bool WatcherQueue::TakeToken() {
  if (sending_ || closed_) return false;
  sending_ = true;
  return true;
}

bool WatcherQueue::Start(v1::WatchEvent head, int64_t after, int64_t upto) {
  std::lock_guard lock(mutex_);
  head_.push_back(std::move(head));
  taken_ = std::max<int64_t>(after, 0);
  if (after < upto) {
    catching_up_ = true;
    catch_up_after_ = after;
    catch_up_upto_ = upto;
    taken_ = upto;
  }
  return TakeToken();
}

bool WatcherQueue::Push(const v1::WatchEvent& event) {
  std::lock_guard lock(mutex_);
  if (closed_ || end_) return false;
  if (event.has_snapshot()) {
    if (!options_.include_snapshots) return false;
    PendingSnapshot pending{event, {}};
    *pending.event.mutable_snapshot() =
        DownsampleSnapshot(event.snapshot(), options_.max_width, options_.max_height);
    if (snapshot_) {
      ++dropped_;
      pending.replaced = std::move(snapshot_->replaced);
      pending.replaced.push_back(snapshot_->event.seq());
    }
    snapshot_ = std::move(pending);
    return TakeToken();
  }
  if (queue_.size() >= options_.capacity) {
    // A slow watcher: what waits here is in the log; the catch-up reads it back, up to this one.
    ++overflows_;
    if (!catching_up_) {
      catching_up_ = true;
      catch_up_after_ = taken_;
    }
    catch_up_upto_ = event.seq();
    queue_.clear();
    if (snapshot_ && snapshot_->event.seq() <= event.seq()) snapshot_.reset();
    return TakeToken();
  }
  queue_.push_back(event);
  return TakeToken();
}

bool WatcherQueue::PushEnd() {
  std::lock_guard lock(mutex_);
  if (closed_) return false;
  end_ = true;
  return TakeToken();
}

bool WatcherQueue::Cancel() {
  std::lock_guard lock(mutex_);
  if (cancelled_ || closed_) return false;
  cancelled_ = true;
  head_.clear();
  queue_.clear();
  snapshot_.reset();
  catching_up_ = false;
  if (sending_) return false;  // the holder sees cancelled_ at its next Pop
  sending_ = true;
  return true;
}

bool WatcherQueue::ReadCatchUp(std::unique_lock<std::mutex>& lock) {
  const int64_t after = catch_up_after_, upto = catch_up_upto_;
  lock.unlock();
  if (!reader_) {
    reader_ = std::make_unique<WatchLog::Reader>(log_dir_, after, upto, options_.include_snapshots,
                                                 *options_.clock);
  }
  reader_->ExtendTo(upto);
  std::vector<v1::WatchEvent> chunk;
  const size_t most = std::max<size_t>(1, options_.capacity / 2);
  bool more = reader_->Next(most, chunk);
  for (auto& event : chunk) {
    if (event.has_snapshot()) {
      *event.mutable_snapshot() =
          DownsampleSnapshot(event.snapshot(), options_.max_width, options_.max_height);
    }
  }
  lock.lock();
  if (!catching_up_) return false;  // cancelled meanwhile
  for (auto& event : chunk) head_.push_back(std::move(event));
  if (!more && catch_up_upto_ == upto) {
    catching_up_ = false;
    reader_.reset();
  }
  return true;
}

WatcherQueue::Next WatcherQueue::Pop(v1::WatchEvent* out) {
  std::unique_lock lock(mutex_);
  while (true) {
    if (cancelled_) {
      closed_ = true;
      return Next::kClosed;
    }
    if (!head_.empty()) {
      *out = std::move(head_.front());
      head_.pop_front();
      Taken(out->seq());
      return Next::kEvent;
    }
    if (!catching_up_) break;
    ReadCatchUp(lock);
  }
  const bool take_snapshot =
      snapshot_ && (queue_.empty() || snapshot_->event.seq() < queue_.front().seq());
  if (take_snapshot) {
    if (!snapshot_->replaced.empty()) {
      // A snapshot replaced by a newer one before it was sent: its number alone.
      const int64_t seq = snapshot_->replaced.front();
      snapshot_->replaced.erase(snapshot_->replaced.begin());
      out->Clear();
      out->set_wall_time(options_.clock->Now());
      out->mutable_gap()->set_from_seq(seq);
      out->mutable_gap()->set_to_seq(seq);
      out->mutable_gap()->set_reason("snapshot replaced by a newer one before it was sent");
      return Next::kEvent;
    }
    *out = std::move(snapshot_->event);
    snapshot_.reset();
    Taken(out->seq());
    return Next::kEvent;
  }
  if (!queue_.empty()) {
    *out = std::move(queue_.front());
    queue_.pop_front();
    Taken(out->seq());
    return Next::kEvent;
  }
  if (end_) {
    closed_ = true;
    return Next::kEnd;
  }
  sending_ = false;
  return Next::kEmpty;
}

int64_t WatcherQueue::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

int64_t WatcherQueue::overflows() const {
  std::lock_guard lock(mutex_);
  return overflows_;
}

}  // namespace dlmfd::server
