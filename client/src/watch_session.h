// A Watch stream that survives a broken connection: when the stream breaks (daemon restarted,
// network hiccup) it reconnects with back-off and resumes after the last sequence number seen, so
// the handler sees every event the daemon still holds exactly once (or a Gap naming what it lost).
// It ends when the job reaches a final state, when the handler says stop, on SIGINT/SIGTERM, on a
// permanent error (not found, denied, invalid), or after `reconnect_seconds` without a connection.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "connection.h"

namespace dlmfd::cli {

struct WatchOptions {
  std::string job_id;
  std::int64_t from_seq = 0;
  bool include_snapshots = false;
  int snapshot_max_width = 0;
  int snapshot_max_height = 0;
  double reconnect_seconds = 120.0;
};

struct WatchOutcome {
  grpc::Status status;    // the permanent error, or OK
  bool finished = false;  // a final state was seen
  v1::Job job;            // the job as of the latest state change
  std::int64_t last_seq = 0;
  int reconnects = 0;
  bool interrupted = false;  // SIGINT or SIGTERM
  bool stopped = false;      // the handler returned false
};

// `on_event` returns false to stop watching. `on_reconnect` (may be empty) is told of each retry.
WatchOutcome WatchJob(
    Connection& connection, const WatchOptions& options,
    const std::function<bool(const v1::WatchEvent&)>& on_event,
    const std::function<void(const grpc::Status&, double delay)>& on_reconnect = {});

}  // namespace dlmfd::cli
