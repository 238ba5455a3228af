#include "event_file_tail.h"

#include <fcntl.h>
#include <google/protobuf/io/coded_stream.h>
#include <unistd.h>

#include "dlmfd/solver/event_file.h"

namespace dlmfd::server {

int EventFileTail::ReadNew(const std::function<void(const v1::SolverEvent&)>& on_event) {
  const int fd = open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  int count = 0;
  if (lseek(fd, offset_, SEEK_SET) == offset_) {
    solver::EventFileReader reader(fd);
    v1::SolverEvent event;
    while (reader.Next(&event)) {
      const size_t size = event.ByteSizeLong();
      offset_ += static_cast<off_t>(
          google::protobuf::io::CodedOutputStream::VarintSize32(static_cast<uint32_t>(size)) +
          size);
      on_event(event);
      ++count;
    }
  }
  close(fd);
  return count;
}

}  // namespace dlmfd::server
