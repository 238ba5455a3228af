#include "dlmfd/solver/event_file.h"

#include <google/protobuf/io/zero_copy_stream_impl.h>
#include <google/protobuf/util/delimited_message_util.h>

namespace dlmfd::solver {

struct EventFileWriter::Stream {
  explicit Stream(int fd)
      : out(fd) {}
  google::protobuf::io::FileOutputStream out;
};

EventFileWriter::EventFileWriter(int fd)
    : stream_(std::make_unique<Stream>(fd)) {}

EventFileWriter::~EventFileWriter() = default;

bool EventFileWriter::Write(const v1::SolverEvent& event) {
  return google::protobuf::util::SerializeDelimitedToZeroCopyStream(event, &stream_->out) &&
         stream_->out.Flush();
}

struct EventFileReader::Stream {
  explicit Stream(int fd)
      : in(fd) {}
  google::protobuf::io::FileInputStream in;
};

EventFileReader::EventFileReader(int fd)
    : stream_(std::make_unique<Stream>(fd)) {}

EventFileReader::~EventFileReader() = default;

bool EventFileReader::Next(v1::SolverEvent* event) {
  event->Clear();  // parsing merges into the message
  bool clean_eof = false;
  return google::protobuf::util::ParseDelimitedFromZeroCopyStream(event, &stream_->in, &clean_eof);
}

}  // namespace dlmfd::solver
