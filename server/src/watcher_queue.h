// WatcherQueue: the bounded buffer between one job's event channel and one Watch stream.
//
// The producer (the thread that reads a solver's events) never waits: Push is O(capacity) at worst
// and never blocks on the network. When the queue is full the oldest event that is not a state
// change is dropped; an unsent snapshot is replaced by a newer one. Either way the watcher is told:
// the next event it receives is a Gap (seq 0) naming the first and last dropped sequence numbers.
// State changes are never dropped. Sending is serialised by a token: whoever takes it (Push,
// PushEnd or Cancel returning true) owns the stream until Next returns kEmpty (token given back),
// kEnd or kClosed (stream must be finished). Snapshots are downsampled here to the watcher's
// requested size.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>

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
  bool TakeToken();
  void RecordDrop(int64_t seq);

  const WatchOptions options_;
  std::function<void()> wake_;
  mutable std::mutex mutex_;
  std::deque<v1::WatchEvent> queue_;
  std::optional<v1::WatchEvent> snapshot_;
  int64_t gap_from_ = 0, gap_to_ = 0;  // 0: no gap pending
  int64_t dropped_ = 0;
  bool sending_ = false;
  bool end_ = false;
  bool closed_ = false;
  bool cancelled_ = false;
};

}  // namespace dlmfd::server
