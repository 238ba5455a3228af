// WatcherQueue: the bounded buffer between one job's event channel and one Watch stream.
//
// The producer (the thread that reads a solver's events) never waits: Push is O(capacity) at worst
// and never blocks on the network. When the queue is full the oldest event that is not a state
// change is dropped; an unsent snapshot is replaced by a newer one. Either way the watcher is told
// where events went missing: Gaps (seq 0) come just before the event sent after the dropped ones,
// each naming the first and last sequence numbers of one run of dropped events. A run holds only
// dropped events: an event sent in between (a state change, a snapshot) ends it, so a Gap is never
// wider than what was dropped. State changes are never dropped. Sending is serialised by a token:
// whoever takes it (Push, PushEnd or Cancel returning true) owns the stream until Next returns
// kEmpty (token given back), kEnd or kClosed (stream must be finished). Snapshots are downsampled
// here to the watcher's requested size.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

#include "dlmfd/v1/jobs.pb.h"

namespace dlmfd::server {

struct WatchOptions {
  size_t capacity = 256;
  bool include_snapshots = false;
  int max_width = 0;  // 0: as sent
  int max_height = 0;
};

// Nearest-node downsampling of a (ny+1) x (nx+1) node field to at most max_width x max_height
// nodes.
v1::Snapshot DownsampleSnapshot(const v1::Snapshot& full, int max_width, int max_height);

class WatcherQueue {
 public:
  enum class Next { kEvent, kEmpty, kEnd, kClosed };

  explicit WatcherQueue(WatchOptions options)
      : options_(options) {}

  // Called by the token holder outside any lock to start sending.
  void SetWake(std::function<void()> wake) { wake_ = std::move(wake); }
  // Enqueue; returns true when the caller took the send token and must call Wake().
  bool Push(const v1::WatchEvent& event);
  // No more events after those queued.
  bool PushEnd();
  // The client went away: drop everything; returns true when the caller took the token.
  bool Cancel();
  void Wake() { wake_(); }

  // For the token holder: the next event to send.
  Next Pop(v1::WatchEvent* out);

  int64_t dropped() const;

 private:
  // A run of dropped events; a run of the event lane may grow, a replaced snapshot is a run alone.
  struct Run {
    int64_t from = 0, to = 0;
    bool grows = true;
  };
  // An event to send, and the runs dropped just before it.
  struct Entry {
    v1::WatchEvent event;
    std::vector<Run> gaps;
  };
  bool TakeToken();
  // Drops `victim` (an event-lane entry): its seq and its runs go before `next` (the trailing runs,
  // which the next pushed event takes, when next is null), merged where nothing lies between.
  void Drop(Entry victim, Entry* next);
  // Writes the first Gap of entry into out and removes it; false when entry has none.
  static bool TakeGap(Entry& entry, v1::WatchEvent* out);

  const WatchOptions options_;
  std::function<void()> wake_;
  mutable std::mutex mutex_;
  std::deque<Entry> queue_;
  std::optional<Entry> snapshot_;
  Entry trailing_;  // only its gaps: dropped after the last queued event
  int64_t dropped_ = 0;
  bool sending_ = false;
  bool end_ = false;
  bool closed_ = false;
  bool cancelled_ = false;
};

}  // namespace dlmfd::server
