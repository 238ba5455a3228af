// The daemon's Watch streams of the jobs one open page follows, fanned into one bounded queue that
// the page's event stream (live_events.h) drains. Each stream is a gRPC callback reactor (no
// thread per job). A stream that breaks (the daemon restarted, the connection dropped) is started
// again after a back-off of 0.2 s doubling to 2 s, from the last sequence number seen, so no
// event the daemon still holds is seen twice; the queue says when the daemon was lost and found
// again. A stream that ends after the job's final state is done; Follow starts it again (a job
// retried later). The queue holds at most `queue_limit` items: past it the oldest progress,
// particle, snapshot or log event is dropped (never a state change or an end) and the drop is
// counted, so the page knows to reload what it shows. Destroying the set cancels every stream and
// waits for each to end: nothing outlives the page.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "daemon_link.h"

namespace dlmfd::web {

struct WatchItem {
  enum class Kind { kEvent, kEnded, kLost, kRestored };
  Kind kind = Kind::kEvent;
  std::string job_id;
  v1::WatchEvent event;  // kEvent
  grpc::Status status;   // kEnded (OK: the job finished; else gone or refused), kLost
};

struct WatchBatch {
  std::vector<WatchItem> items;
  std::int64_t dropped = 0;  // events dropped since the last batch (the page reloads)
};

class JobWatchSet {
 public:
  // include_snapshots: snapshot events (2 x 2 nodes: a notice that a new picture exists).
  JobWatchSet(DaemonLink& link, std::string token, bool include_snapshots,
              std::size_t queue_limit = 512);
  ~JobWatchSet();
  JobWatchSet(const JobWatchSet&) = delete;
  JobWatchSet& operator=(const JobWatchSet&) = delete;

  // Starts a Watch of the job unless one runs or waits to restart, from the events after
  // `from_seq` (the job's last_seq when the page read it: the page loads the state as of then, so
  // the daemon's held events before it are not sent again), or after the last one this set saw.
  void Follow(const std::string& job_id, std::int64_t from_seq);
  bool Follows(const std::string& job_id) const;
  std::size_t Active() const;  // streams open or waiting to restart
  // Watch streams open now in this process, all sets together (/api/status).
  static int OpenStreams();
  // The items queued, waiting up to `wait` for the first; restarts broken streams that are due.
  WatchBatch Next(std::chrono::milliseconds wait);

 private:
  class Reactor;
  struct Stream {
    std::int64_t last_seq = 0;
    Reactor* reactor = nullptr;  // alive until its OnDone
    bool waiting = false;        // broken, restarts at retry_at
    std::chrono::steady_clock::time_point retry_at;
    std::chrono::milliseconds backoff{200};
  };
  // Makes the stream's reactor (counted live); the caller starts it after unlocking.
  Reactor* StartLocked(const std::string& job_id, Stream& stream);
  void Deliver(const std::string& job_id, const v1::WatchEvent& event);
  void Ended(Reactor* reactor, const std::string& job_id, const grpc::Status& status);
  void PushLocked(WatchItem item);

  DaemonLink& link_;
  const std::string token_;
  const bool include_snapshots_;
  const std::size_t queue_limit_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::map<std::string, Stream> streams_;
  std::deque<WatchItem> queue_;
  std::int64_t dropped_ = 0;
  int live_reactors_ = 0;
  bool closing_ = false;
  bool lost_ = false;  // a stream broke and none has delivered since
};

}  // namespace dlmfd::web
