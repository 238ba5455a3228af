// EventFileTail: follows a solver event stream that another machine appends to a file (the slurm
// executor's job directory on a shared filesystem), delivering each complete event once.
//
// Each call opens the file, seeks to the end of the last complete event, reads with the solver's
// own reader (dlmfd/solver/event_file.h, the one definition of the framing) and advances by each
// event's framed size (varint length + message). An event still being written (a truncated
// message at the end) is left for the next call. Not supported: a file truncated or replaced
// while followed (the executor removes it before each attempt, before following it).
#pragma once

#include <sys/types.h>

#include <functional>
#include <string>

#include "dlmfd/v1/events.pb.h"

namespace dlmfd::server {

class EventFileTail {
 public:
  // start: the offset of the first event to deliver (one a reader before stopped at).
  explicit EventFileTail(std::string path, off_t start = 0)
      : path_(std::move(path)),
        offset_(start) {}
  // Delivers the complete events appended since the last call; returns how many. A missing file
  // has none yet. During on_event, offset() is the offset just past the event.
  int ReadNew(const std::function<void(const v1::SolverEvent&)>& on_event);
  off_t offset() const { return offset_; }

 private:
  std::string path_;
  off_t offset_;
};

}  // namespace dlmfd::server
