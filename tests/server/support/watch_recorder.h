// Test support: watchers that reconnect as a client should (from the last number they saw) across
// daemon restarts, and the check that each got every event exactly once (issue 38, docs/api.md
// "Watch streams").
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "dlmfd/v1/jobs.grpc.pb.h"

namespace dlmfd::testing {

class ReconnectingWatcher {
 public:
  // Watches job_id at address (host:port) from from_seq on a thread of its own until it has seen
  // the job's final state, reconnecting whenever the stream breaks.
  ReconnectingWatcher(std::string address, std::string job_id, bool snapshots,
                      int64_t from_seq = 0);
  ~ReconnectingWatcher();
  ReconnectingWatcher(const ReconnectingWatcher&) = delete;
  ReconnectingWatcher& operator=(const ReconnectingWatcher&) = delete;

  // Waits until the final state was seen (or ten minutes passed: a test failure).
  void Join();
  // The numbered events and the Gaps, in the order received (the summaries, seq 0, left out).
  std::vector<v1::WatchEvent> Events() const;
  int Connections() const { return connections_.load(); }
  // Numbered events seen so far.
  size_t Count() const;
  const std::string& job_id() const { return job_id_; }
  int64_t from_seq() const { return from_seq_; }
  bool snapshots() const { return snapshots_; }

 private:
  void Run();

  const std::string address_, job_id_;
  const bool snapshots_;
  const int64_t from_seq_;
  mutable std::mutex mutex_;
  std::vector<v1::WatchEvent> events_;
  std::atomic<int> connections_{0};
  std::atomic<bool> done_{false}, stop_{false};
  std::thread thread_;
};

// Every event of a finished job, read at once from number 0 (no Gap expected: the log holds them
// all), checked for what a watch promises: numbers 1, 2, ... with none missing, particle states
// and progress of strictly increasing steps (a resumed solver's repeated steps are not sent
// again), each state event's job naming its own number.
std::vector<v1::WatchEvent> ReferenceEvents(v1::Jobs::Stub& stub, const std::string& job_id);

// Expects `watcher` to have received each event of `reference` after its from_seq exactly once,
// in order and equal to it; the only Gaps allowed name snapshots that a newer one replaced (a
// watcher with snapshots); a watcher without snapshots gets none of them.
void ExpectExactlyOnce(const std::vector<v1::WatchEvent>& reference,
                       const ReconnectingWatcher& watcher);

using Watchers = std::vector<std::unique_ptr<ReconnectingWatcher>>;

// Two watchers of each job at address from number 0: one without snapshots, one with.
Watchers WatchersOf(const std::string& address, const std::vector<std::string>& job_ids);
// The numbered events all the watchers have seen so far.
size_t EventsSeen(const Watchers& watchers);
// ExpectExactlyOnce for each of the watchers of job_id.
void ExpectExactlyOnce(const std::vector<v1::WatchEvent>& reference, const Watchers& watchers,
                       const std::string& job_id);
// How many of the watchers reconnected at least once.
size_t Reconnected(const Watchers& watchers);

}  // namespace dlmfd::testing
