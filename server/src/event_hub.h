// EventHub: per job, the recent events with their sequence numbers, fanned out to watchers.
//
// Each unfinished job that is running or watched has a channel: a ring of the last `ring_size`
// events (snapshots excluded), the latest snapshot (a newer one replaces it), the job as of its
// last state change, and the attached WatcherQueues. Publishing assigns the next sequence number
// and pushes to every watcher without blocking. Sequence numbers are reserved in the store in
// blocks of kSeqBlock, so they keep increasing across daemon restarts, and each number issued is
// written to the SeqJournal before any watcher sees it. The store holds the last number issued
// once a job finishes and after a clean shutdown (RecordIssued); after a kill -9 the next daemon
// learns it from the journal (Recover, before it serves). Either way numbers resume right after the
// last one issued and a reconnecting watcher's Gap names only numbers that were issued. A job's
// last_seq (Get, List, Watch) is always the last number issued. A job's final state change
// ends every watch and drops the channel; a later Watch of a finished job replays the final state
// from the store.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "dlmfd/v1/jobs.pb.h"
#include "job_store.h"
#include "seq_journal.h"
#include "watcher_queue.h"

namespace dlmfd::server {

class EventHub {
 public:
  static constexpr int64_t kSeqBlock = 1000;

  EventHub(JobStore& store, SeqJournal& journal, size_t ring_size)
      : store_(store),
        journal_(journal),
        ring_size_(ring_size) {}

  // At start, before any event: the store takes each job's last number issued from the journal
  // that an earlier daemon left (after a kill -9 the store holds a reserved block's end).
  void Recover();

  // A state change of a job (the record as now in the store). A finished state ends the watches.
  void PublishState(const JobRecord& job);
  // A progress, particles, snapshot or log event; ignored when the job has no channel.
  void Publish(const std::string& job_id, v1::WatchEvent event);

  // Attaches a watcher: queues the current state, then the held events with seq > from_seq (a Gap
  // first if some of those are no longer held). Returns true when the caller took the send token.
  bool Attach(const JobRecord& job, int64_t from_seq, const std::shared_ptr<WatcherQueue>& watcher);
  void Detach(const std::string& job_id, const WatcherQueue* watcher);

  // Writes each channel's last issued number to the store (at shutdown, after the solvers stop).
  void RecordIssued();
  // The last number issued for a job with a channel (the store may hold a reserved block's end).
  std::optional<int64_t> LastIssued(const std::string& job_id);
  // The last_seq to report with a record read from the store: the last number issued, counting a
  // finished record's final state event even while that event is being delivered.
  int64_t ReportedLastSeq(const JobRecord& job);

  size_t ChannelCount();
  size_t WatcherCount(const std::string& job_id);

 private:
  struct Channel;
  std::shared_ptr<Channel> Find(const std::string& job_id);
  std::shared_ptr<Channel> FindOrCreate(const JobRecord& job);
  using WakeList = std::vector<std::shared_ptr<WatcherQueue>>;
  void Deliver(Channel& channel, v1::WatchEvent event, WakeList& wake);

  JobStore& store_;
  SeqJournal& journal_;
  const size_t ring_size_;
  std::mutex mutex_;  // guards channels_ and serialises channel creation with final state changes
  std::map<std::string, std::shared_ptr<Channel>> channels_;
};

}  // namespace dlmfd::server
