// The framing of the solver's event stream (proto/dlmfd/v1/events.proto): SolverEvent messages,
// each prefixed by its byte length as a protobuf varint
// (google::protobuf::util::SerializeDelimitedToZeroCopyStream). dlmfd-solve --events FD writes it,
// the daemon reads it from a pipe; this header is the one definition of the format for both.
// Neither class owns the descriptor: whoever opened it closes it.
#pragma once

#include <memory>

#include "dlmfd/v1/events.pb.h"

namespace dlmfd::solver {

class EventFileWriter {
 public:
  explicit EventFileWriter(int fd);
  ~EventFileWriter();
  EventFileWriter(const EventFileWriter&) = delete;
  EventFileWriter& operator=(const EventFileWriter&) = delete;

  // Writes one framed event and flushes it (a reader sees each event as it happens). False when
  // the write failed (the reader went away); the stream is then unusable.
  bool Write(const v1::SolverEvent& event);

 private:
  struct Stream;
  std::unique_ptr<Stream> stream_;
};

class EventFileReader {
 public:
  explicit EventFileReader(int fd);
  ~EventFileReader();
  EventFileReader(const EventFileReader&) = delete;
  EventFileReader& operator=(const EventFileReader&) = delete;

  // Replaces *event by the next one. False at the end of the stream, and at a truncated or
  // malformed message (a writer killed mid-event): nothing after it can be framed.
  bool Next(v1::SolverEvent* event);

 private:
  struct Stream;
  std::unique_ptr<Stream> stream_;
};

}  // namespace dlmfd::solver
