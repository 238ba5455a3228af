// EventHub: per job, the watch events with their sequence numbers, logged and fanned out.
//
// Each unfinished job that is running or watched has a channel: the job as of its last state
// change, the last number issued, and the attached WatcherQueues. Publishing assigns the next
// number, appends the event to the job's watch log (watch_log.h) and only then pushes it to every
// watcher, without blocking. The log is the record: numbers keep increasing across daemon
// restarts (a channel opens at the log's last number), a watcher that reconnects with the last
// number it saw, falls behind, or watches a finished job reads what it missed from the log, so it
// receives every later event once, in order (issue 38). A job's last_seq (Get, List, Watch) is
// always the last number issued; the store holds it once the job has finished and after a clean
// shutdown (RecordIssued), and Recover takes it from the logs at start after a kill.
//
// Exactly once also across solver restarts: a solver resumed from its checkpoint (after a daemon
// restart, a cancel and retry, a Slurm requeue) runs the steps since that checkpoint again, and a
// daemon that adopts a Slurm job reads its event file again. Each solver event is published with
// its lane (progress, particles, snapshot, checkpoint) and step: an event whose step is not above
// the last logged in its lane is not published again; and with its source (the file and the
// offset just past it), so that an adopting daemon reads on from there (SourceOffset). A retry
// that starts afresh begins a new timeline (PublishState's new_timeline): the steps count again.
//
// A job's final state change ends every watch and drops the channel; a later Watch of a finished
// job reads the log.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "clock.h"
#include "dlmfd/v1/jobs.pb.h"
#include "job_store.h"
#include "watch_log.h"
#include "watcher_queue.h"

namespace dlmfd::server {

class EventHub {
 public:
  // The directory of a job, where its watch log lives.
  using JobDirectory = std::function<std::string(const std::string& job_id)>;

  // clock: the wall_time of the events it stamps (clock.h).
  EventHub(JobStore& store, JobDirectory job_dir, Clock& clock = SystemClock())
      : store_(store),
        job_dir_(std::move(job_dir)),
        clock_(clock) {}

  // At start, before any event: every unfinished job's last_seq from its watch log (a daemon
  // killed with SIGKILL did not store it), and the numbers a daemon of an older version left in
  // `legacy_journal_dir` (DATA/watch_seq), which is then removed.
  void Recover(const std::string& legacy_journal_dir);

  // A state change of a job (the record as now in the store). A finished state ends the watches.
  // new_timeline: a retry that starts the job afresh (its steps count from 0 again).
  void PublishState(const JobRecord& job, bool new_timeline = false);
  // A progress, particles, snapshot or log event; false when it was not published: the job has
  // no channel, or its lane already has an event at or after its step.
  bool Publish(const std::string& job_id, v1::WatchEvent event, const LogOrigin& origin = {});

  // Attaches a watcher: its head is the current state (a summary with seq 0, not an event of the
  // sequence), then the events with seq > from_seq from the log, then the live ones. Returns true
  // when the caller took the send token.
  bool Attach(const JobRecord& job, int64_t from_seq, const std::shared_ptr<WatcherQueue>& watcher);
  void Detach(const std::string& job_id, const WatcherQueue* watcher);

  // The offset of `source` (a solver event file) just past the last of its events logged for the
  // job; nothing when none was.
  std::optional<int64_t> SourceOffset(const JobRecord& job, const std::string& source);

  // Writes each channel's last issued number to the store (at shutdown, after the solvers stop).
  void RecordIssued();
  // The last number issued for a job with a channel.
  std::optional<int64_t> LastIssued(const std::string& job_id);
  // The last_seq to report with a record read from the store: the last number issued, counting a
  // finished record's final state event even while that event is being delivered.
  int64_t ReportedLastSeq(const JobRecord& job);
  // The directory of the job's watch log.
  std::string LogDirectory(const std::string& job_id) const { return job_dir_(job_id); }

  size_t ChannelCount();
  size_t WatcherCount(const std::string& job_id);

 private:
  struct Channel;
  std::shared_ptr<Channel> Find(const std::string& job_id);
  std::shared_ptr<Channel> FindOrCreate(const JobRecord& job);
  using WakeList = std::vector<std::shared_ptr<WatcherQueue>>;
  void Deliver(Channel& channel, v1::WatchEvent event, const LogOrigin& origin, bool new_timeline,
               WakeList& wake);

  JobStore& store_;
  const JobDirectory job_dir_;
  Clock& clock_;
  std::mutex mutex_;  // guards channels_ and serialises channel creation with final state changes
  std::map<std::string, std::shared_ptr<Channel>> channels_;
};

}  // namespace dlmfd::server
