// WatcherQueue: what one Watch stream still has to send, in the order of the job's sequence
// numbers.
//
// Every event is in the job's watch log (watch_log.h) before the hub pushes it here, so a queue
// never has to drop one for good. It sends, in order: the head (the summary of the current state,
// given at attach), then the catch-up (the events with seq in (after, upto], read from the log in
// chunks as the stream drains: what the watcher missed before it attached, or what did not fit
// since), then the live events pushed by the producer. The producer never waits: Push is O(1)
// and never blocks on the network or the disk; when `capacity` live events are waiting (a slow
// watcher) they are let go and the catch-up range grows over them, to be read back from the log
// later. A newer snapshot replaces one not yet sent (a Gap names it): snapshots are the one kind
// a slow watcher may miss (and a watcher that does not ask for snapshots never gets one; their
// numbers are not its concern). Sending is serialised by a token: whoever takes it (Push, PushEnd,
// Cancel or Start returning true) owns the stream until Pop returns kEmpty (token given back),
// kEnd or kClosed (stream must be finished). The catch-up is read by the token holder outside
// the queue's lock. Snapshots are downsampled here to the watcher's requested size.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "clock.h"
#include "dlmfd/v1/jobs.pb.h"
#include "watch_log.h"

namespace dlmfd::server {

struct WatchOptions {
  size_t capacity = 256;
  bool include_snapshots = false;
  int max_width = 0;  // 0: as sent
  int max_height = 0;
  Clock* clock = &SystemClock();  // the wall_time of the Gaps it makes (clock.h)
};

// Nearest-node downsampling of a (ny+1) x (nx+1) node field to at most max_width x max_height
// nodes.
v1::Snapshot DownsampleSnapshot(const v1::Snapshot& full, int max_width, int max_height);

class WatcherQueue {
 public:
  enum class Next { kEvent, kEmpty, kEnd, kClosed };

  // `log_dir`: the job directory whose watch log holds the events (the catch-up reads it).
  WatcherQueue(WatchOptions options, std::string log_dir)
      : options_(options),
        log_dir_(std::move(log_dir)) {}

  // Called by the token holder outside any lock to start sending.
  void SetWake(std::function<void()> wake) { wake_ = std::move(wake); }
  // At attach, before any Push: the head event, then the events with seq in (after, upto] from
  // the log (none when after >= upto). Returns true when the caller took the send token.
  bool Start(v1::WatchEvent head, int64_t after, int64_t upto);
  // A live event; returns true when the caller took the send token and must call Wake().
  bool Push(const v1::WatchEvent& event);
  // No more events after those pushed.
  bool PushEnd();
  // The client went away: drop everything; returns true when the caller took the token.
  bool Cancel();
  void Wake() { wake_(); }

  // For the token holder: the next event to send.
  Next Pop(v1::WatchEvent* out);

  // Snapshots replaced before they were sent.
  int64_t dropped() const;
  // Times the live events outgrew `capacity` and were left to the catch-up.
  int64_t overflows() const;

 private:
  bool TakeToken();
  // Reads the next chunk of the catch-up into head_ (lock held on entry and on return; released
  // while reading). False when the catch-up is done.
  bool ReadCatchUp(std::unique_lock<std::mutex>& lock);
  void Taken(int64_t seq) { taken_ = std::max(taken_, seq); }

  const WatchOptions options_;
  const std::string log_dir_;
  std::function<void()> wake_;
  mutable std::mutex mutex_;
  std::deque<v1::WatchEvent> head_;  // to send first: the head, then chunks of the catch-up
  // The catch-up: (after, upto] of the log, read by reader_ (made by the token holder).
  bool catching_up_ = false;
  int64_t catch_up_after_ = 0, catch_up_upto_ = 0;
  std::unique_ptr<WatchLog::Reader> reader_;
  std::deque<v1::WatchEvent> queue_;  // live events
  struct PendingSnapshot {
    v1::WatchEvent event;
    std::vector<int64_t> replaced;  // snapshots it replaced, unsent: a Gap each before it
  };
  std::optional<PendingSnapshot> snapshot_;
  int64_t taken_ = 0;  // the highest number moved to head_ or popped
  int64_t dropped_ = 0, overflows_ = 0;
  bool sending_ = false;
  bool end_ = false;
  bool closed_ = false;
  bool cancelled_ = false;
};

}  // namespace dlmfd::server
