// WatchLog: every watch event of one job, on disk, in the order of its sequence numbers.
//
// JOB_DIR/watch.log holds one WatchLogRecord per event (proto/dlmfd/v1/watch_log.proto), framed
// as the solver's events are (a varint length, then the message) and appended with one write(2)
// each: in the kernel's page cache as soon as the call returns, so a daemon killed with SIGKILL
// loses no event it issued (a power cut may lose the tail; a torn last record is cut off when the
// log is next opened). A snapshot's values go to JOB_DIR/watch.snapshots (one framed WatchEvent
// each) and its record keeps the event without them, so that a watcher that does not want
// snapshots reads only the small records. The EventHub appends each event here before any
// watcher sees it; a watcher that reconnects, falls behind or watches a finished job reads what
// it missed from here (Reader), so it gets every event once. The log lives as long as the job
// directory (Delete removes it) and counts toward the user's disk.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "clock.h"
#include "dlmfd/v1/jobs.pb.h"
#include "dlmfd/v1/watch_log.pb.h"

namespace dlmfd::server {

// What a solver event's record carries besides the event (watch_log.proto).
struct LogOrigin {
  std::string lane;  // empty: not ordered by step (state changes, log lines)
  int64_t step = 0;
  std::string source;  // empty: not from a file the daemon may read again
  int64_t source_offset = 0;
};

// What a scan of the whole log finds.
struct WatchLogState {
  int64_t last_seq = 0;                          // 0: an empty or missing log
  std::map<std::string, int64_t> high_water;     // lane -> its last step since the last timeline
  std::map<std::string, int64_t> source_offset;  // source -> offset past its last event logged
};

class WatchLog {
 public:
  static constexpr char kFile[] = "watch.log";
  static constexpr char kSnapshots[] = "watch.snapshots";

  explicit WatchLog(std::string job_dir)
      : dir_(std::move(job_dir)) {}

  // Appends the event (its seq set); false when it cannot be written.
  bool Append(const v1::WatchEvent& event, const LogOrigin& origin, bool new_timeline) const;
  // Reads the whole log; a torn last record (a write cut short) is cut off the file.
  WatchLogState Recover() const;
  // The last sequence number logged (0 when none), reading only as far as needed.
  int64_t LastSeq() const { return Recover().last_seq; }

  // Reads the events with seq in (after, upto] in order. A sequence number the log lacks (written
  // before logs were kept, or lost to an I/O error) comes as a Gap naming the missing run.
  // Snapshots only when asked for (then whole, from watch.snapshots); the numbers of the others
  // are simply not a watcher's concern.
  class Reader {
   public:
    // clock: the wall_time of the Gaps it makes (clock.h).
    Reader(std::string dir, int64_t after, int64_t upto, bool snapshots,
           Clock& clock = SystemClock());
    ~Reader();
    Reader(const Reader&) = delete;
    Reader& operator=(const Reader&) = delete;
    // Appends up to `max` events (Gaps included) to out; false when the range is done.
    bool Next(size_t max, std::vector<v1::WatchEvent>& out);
    // Lets the range grow: events up to `upto` (appended since) are read too.
    void ExtendTo(int64_t upto) { upto_ = std::max(upto_, upto); }
    int64_t position() const { return expected_ - 1; }  // the last number delivered

   private:
    bool ReadRecord(v1::WatchLogRecord& record);
    void PushGap(int64_t to, std::vector<v1::WatchEvent>& out);
    std::string dir_;
    int64_t expected_;  // the next number to deliver
    int64_t upto_;
    bool snapshots_;
    Clock& clock_;
    int fd_ = -1;
    int64_t read_pos_ = 0;  // the file offset the next read starts at
    std::string buffer_;    // bytes read, the first parsed_ of them parsed
    size_t parsed_ = 0;
  };

 private:
  std::string dir_;
};

}  // namespace dlmfd::server
