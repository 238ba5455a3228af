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

void WatcherQueue::Drop(Entry victim, Entry* next) {
  ++dropped_;
  const int64_t seq = victim.event.seq();
  std::vector<Run> runs = std::move(victim.gaps);
  // The victim's own runs lie just before it, with nothing sent in between.
  if (!runs.empty() && runs.back().grows) {
    runs.back().to = seq;
  } else {
    runs.push_back({seq, seq, true});
  }
  Entry& after = next ? *next : trailing_;
  if (!after.gaps.empty() && after.gaps.front().grows) {
    runs.back().to = after.gaps.front().to;
    after.gaps.erase(after.gaps.begin());
  }
  runs.insert(runs.end(), after.gaps.begin(), after.gaps.end());
  after.gaps = std::move(runs);
}

bool WatcherQueue::TakeGap(Entry& entry, v1::WatchEvent* out) {
  if (entry.gaps.empty()) return false;
  out->Clear();
  out->set_wall_time(NowSeconds());
  auto* gap = out->mutable_gap();
  gap->set_from_seq(entry.gaps.front().from);
  gap->set_to_seq(entry.gaps.front().to);
  gap->set_reason("slow watcher: events dropped");
  entry.gaps.erase(entry.gaps.begin());
  return true;
}

bool WatcherQueue::Push(const v1::WatchEvent& event) {
  std::lock_guard lock(mutex_);
  if (closed_ || end_) return false;
  if (event.has_snapshot()) {
    if (!options_.include_snapshots) return false;
    // A snapshot is newer than all that is queued: the trailing runs lie just before it.
    Entry entry{event, std::move(trailing_.gaps)};
    trailing_.gaps.clear();
    *entry.event.mutable_snapshot() =
        DownsampleSnapshot(event.snapshot(), options_.max_width, options_.max_height);
    if (snapshot_) {
      // The replaced snapshot's runs, then the snapshot as a run of its own: events of the other
      // lane may have been sent between it and the ones dropped after it.
      ++dropped_;
      std::vector<Run> runs = std::move(snapshot_->gaps);
      for (auto& run : runs) run.grows = false;
      runs.push_back({snapshot_->event.seq(), snapshot_->event.seq(), false});
      runs.insert(runs.end(), entry.gaps.begin(), entry.gaps.end());
      entry.gaps = std::move(runs);
    }
    snapshot_ = std::move(entry);
    return TakeToken();
  }
  if (queue_.size() >= options_.capacity) {
    auto victim = std::find_if(queue_.begin(), queue_.end(),
                               [](const Entry& e) { return !e.event.has_state(); });
    if (!event.has_state() && victim == queue_.end()) {
      // The new event itself is dropped, after the trailing runs.
      Entry dropped{event, std::move(trailing_.gaps)};
      trailing_.gaps.clear();
      Drop(std::move(dropped), nullptr);
      return TakeToken();
    }
    if (victim != queue_.end()) {
      Entry dropped = std::move(*victim);
      auto next = queue_.erase(victim);
      Drop(std::move(dropped), next == queue_.end() ? nullptr : &*next);
    }
  }
  queue_.push_back(Entry{event, std::move(trailing_.gaps)});
  trailing_.gaps.clear();
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
  trailing_.gaps.clear();
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
  const bool take_snapshot =
      snapshot_ && (queue_.empty() || snapshot_->event.seq() < queue_.front().event.seq());
  if (take_snapshot) {
    if (TakeGap(*snapshot_, out)) return Next::kEvent;
    *out = std::move(snapshot_->event);
    snapshot_.reset();
    return Next::kEvent;
  }
  if (!queue_.empty()) {
    if (TakeGap(queue_.front(), out)) return Next::kEvent;
    *out = std::move(queue_.front().event);
    queue_.pop_front();
    return Next::kEvent;
  }
  if (TakeGap(trailing_, out)) return Next::kEvent;
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
