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

void WatcherQueue::RecordDrop(int64_t seq) {
  ++dropped_;
  if (gap_from_ == 0 || seq < gap_from_) gap_from_ = seq;
  gap_to_ = std::max(gap_to_, seq);
}

bool WatcherQueue::Push(const v1::WatchEvent& event) {
  std::lock_guard lock(mutex_);
  if (closed_ || end_) return false;
  if (event.has_snapshot()) {
    if (!options_.include_snapshots) return false;
    if (snapshot_) RecordDrop(snapshot_->seq());
    snapshot_ = event;
    *snapshot_->mutable_snapshot() =
        DownsampleSnapshot(event.snapshot(), options_.max_width, options_.max_height);
    return TakeToken();
  }
  if (queue_.size() >= options_.capacity) {
    auto victim = std::find_if(queue_.begin(), queue_.end(),
                               [](const v1::WatchEvent& e) { return !e.has_state(); });
    if (!event.has_state() && victim == queue_.end()) {
      RecordDrop(event.seq());
      return TakeToken();
    }
    if (victim != queue_.end()) {
      RecordDrop(victim->seq());
      queue_.erase(victim);
    }
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
  queue_.clear();
  snapshot_.reset();
  if (sending_) return false;  // the holder sees cancelled_ at its next Pop
  sending_ = true;
  return true;
}

WatcherQueue::Next WatcherQueue::Pop(v1::WatchEvent* out) {
  std::lock_guard lock(mutex_);
  if (cancelled_) {
    closed_ = true;
    return Next::kClosed;
  }
  if (gap_from_ != 0) {
    out->Clear();
    out->set_wall_time(NowSeconds());
    auto* gap = out->mutable_gap();
    gap->set_from_seq(gap_from_);
    gap->set_to_seq(gap_to_);
    gap->set_reason("slow watcher: events dropped");
    gap_from_ = gap_to_ = 0;
    return Next::kEvent;
  }
  const bool take_snapshot =
      snapshot_ && (queue_.empty() || snapshot_->seq() < queue_.front().seq());
  if (take_snapshot) {
    *out = std::move(*snapshot_);
    snapshot_.reset();
    return Next::kEvent;
  }
  if (!queue_.empty()) {
    *out = std::move(queue_.front());
    queue_.pop_front();
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

}  // namespace dlmfd::server
