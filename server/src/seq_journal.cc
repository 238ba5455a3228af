#include "seq_journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>

namespace dlmfd::server {
namespace fs = std::filesystem;

SeqJournal::SeqJournal(std::string dir)
    : dir_(std::move(dir)) {
  fs::create_directories(dir_);
}

std::string SeqJournal::Path(const std::string& job_id) const {
  return (fs::path(dir_) / job_id).string();
}

bool SeqJournal::Record(const std::string& job_id, int64_t seq) {
  const std::string path = Path(job_id);
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) return false;
  unsigned char bytes[sizeof(seq)];
  std::memcpy(bytes, &seq, sizeof(seq));
  // One write of 8 bytes at offset 0: the file never holds half of one number and half of another.
  const bool written = pwrite(fd, bytes, sizeof(bytes), 0) == static_cast<ssize_t>(sizeof(bytes));
  const bool closed = close(fd) == 0;
  if (written && closed) return true;
  unlink(path.c_str());
  return false;
}

void SeqJournal::Remove(const std::string& job_id) { unlink(Path(job_id).c_str()); }

std::map<std::string, int64_t> SeqJournal::ReadAll() const {
  std::map<std::string, int64_t> out;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dir_, error)) {
    const std::string path = entry.path().string();
    const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) continue;
    unsigned char bytes[sizeof(int64_t)];
    const ssize_t got = pread(fd, bytes, sizeof(bytes), 0);
    close(fd);
    if (got != static_cast<ssize_t>(sizeof(bytes))) continue;
    int64_t seq = 0;
    std::memcpy(&seq, bytes, sizeof(seq));
    if (seq > 0) out[entry.path().filename().string()] = seq;
  }
  return out;
}

}  // namespace dlmfd::server
