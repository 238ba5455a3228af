#include "watch_log.h"

#include <fcntl.h>
#include <google/protobuf/io/coded_stream.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>

#include "job_proto.h"

namespace dlmfd::server {
namespace fs = std::filesystem;
namespace {

using google::protobuf::io::CodedInputStream;
using google::protobuf::io::CodedOutputStream;

constexpr size_t kReadChunk = 64 * 1024;
constexpr uint32_t kMaxRecordBytes = 1u << 30;

std::string Framed(const google::protobuf::MessageLite& message) {
  const size_t size = message.ByteSizeLong();
  std::string out;
  out.reserve(size + 5);
  {
    google::protobuf::io::StringOutputStream stream(&out);
    CodedOutputStream coded(&stream);
    coded.WriteVarint32(static_cast<uint32_t>(size));
    message.SerializeWithCachedSizes(&coded);
  }
  return out;
}

// Appends bytes with one write(2); returns the file's offset where they start, or -1. The job's
// directory is made when missing (a job's first event, its start, comes before its solver's
// directory).
int64_t AppendBytes(const std::string& path, const std::string& bytes) {
  int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0 && errno == ENOENT) {
    std::error_code error;
    fs::create_directories(fs::path(path).parent_path(), error);
    fd = open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  }
  if (fd < 0) return -1;
  struct stat info {};
  int64_t start = fstat(fd, &info) == 0 ? static_cast<int64_t>(info.st_size) : -1;
  const ssize_t written = write(fd, bytes.data(), bytes.size());
  if (close(fd) != 0 || written != static_cast<ssize_t>(bytes.size())) start = -1;
  return start;
}

// The framed message at the start of data[0, size): its length in *used, 0 when the bytes end
// inside it. False when the bytes cannot be a record (a corrupt length or message).
bool ParseFramed(const char* data, size_t size, google::protobuf::MessageLite& message,
                 size_t* used) {
  *used = 0;
  CodedInputStream input(reinterpret_cast<const uint8_t*>(data),
                         static_cast<int>(std::min<size_t>(size, INT32_MAX)));
  uint32_t length = 0;
  if (!input.ReadVarint32(&length)) return size < 5;  // a varint cut short, or corrupt
  if (length > kMaxRecordBytes) return false;
  const size_t header = static_cast<size_t>(input.CurrentPosition());
  if (size < header + length) return true;
  if (!message.ParseFromArray(data + header, static_cast<int>(length))) return false;
  *used = header + length;
  return true;
}

// The whole snapshot event at `offset` of the snapshot file; false when it cannot be read.
bool ReadSnapshotAt(const std::string& path, int64_t offset, v1::WatchEvent& event) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  std::string head(10, '\0');
  ssize_t got = pread(fd, head.data(), head.size(), offset);
  bool ok = false;
  if (got > 0) {
    head.resize(static_cast<size_t>(got));
    CodedInputStream input(reinterpret_cast<const uint8_t*>(head.data()),
                           static_cast<int>(head.size()));
    uint32_t size = 0;
    if (input.ReadVarint32(&size) && size <= kMaxRecordBytes) {
      std::string body(size, '\0');
      got = pread(fd, body.data(), size, offset + input.CurrentPosition());
      ok = got == static_cast<ssize_t>(size) && event.ParseFromString(body);
    }
  }
  close(fd);
  return ok;
}

}  // namespace

bool WatchLog::Append(const v1::WatchEvent& event, const LogOrigin& origin,
                      bool new_timeline) const {
  v1::WatchLogRecord record;
  *record.mutable_event() = event;
  if (event.has_snapshot()) {
    const int64_t at = AppendBytes((fs::path(dir_) / kSnapshots).string(), Framed(event));
    if (at < 0) return false;
    record.set_snapshot_offset(at);
    record.mutable_event()->mutable_snapshot()->clear_values();
  }
  record.set_lane(origin.lane);
  record.set_step(origin.step);
  record.set_source(origin.source);
  record.set_source_offset(origin.source_offset);
  record.set_new_timeline(new_timeline);
  return AppendBytes((fs::path(dir_) / kFile).string(), Framed(record)) >= 0;
}

WatchLogState WatchLog::Recover() const {
  WatchLogState state;
  const std::string path = (fs::path(dir_) / kFile).string();
  const int fd = open(path.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return state;
  std::string buffer;
  int64_t parsed_end = 0;  // offset just past the last whole record
  bool corrupt = false;
  char chunk[kReadChunk];
  ssize_t got;
  while (!corrupt && (got = read(fd, chunk, sizeof chunk)) > 0) {
    buffer.append(chunk, static_cast<size_t>(got));
    size_t start = 0;
    while (true) {
      v1::WatchLogRecord record;
      size_t used = 0;
      if (!ParseFramed(buffer.data() + start, buffer.size() - start, record, &used)) {
        corrupt = true;
        break;
      }
      if (used == 0) break;
      start += used;
      parsed_end += static_cast<int64_t>(used);
      if (record.new_timeline()) state.high_water.clear();
      state.last_seq = std::max(state.last_seq, record.event().seq());
      if (!record.lane().empty()) state.high_water[record.lane()] = record.step();
      if (!record.source().empty()) state.source_offset[record.source()] = record.source_offset();
    }
    buffer.erase(0, start);
  }
  struct stat info {};
  if (fstat(fd, &info) == 0 && info.st_size > parsed_end) {
    // A record cut short by a crash (or bytes that cannot be one): later appends must not follow
    // it, or nothing after it could be read.
    [[maybe_unused]] const int cut = ftruncate(fd, parsed_end);
  }
  close(fd);
  return state;
}

WatchLog::Reader::Reader(std::string dir, int64_t after, int64_t upto, bool snapshots, Clock& clock)
    : dir_(std::move(dir)),
      expected_(after + 1),
      upto_(upto),
      snapshots_(snapshots),
      clock_(clock) {
  fd_ = open((fs::path(dir_) / kFile).c_str(), O_RDONLY | O_CLOEXEC);
}

WatchLog::Reader::~Reader() {
  if (fd_ >= 0) close(fd_);
}

bool WatchLog::Reader::ReadRecord(v1::WatchLogRecord& record) {
  while (fd_ >= 0) {
    size_t used = 0;
    if (!ParseFramed(buffer_.data() + parsed_, buffer_.size() - parsed_, record, &used)) {
      return false;
    }
    if (used > 0) {
      parsed_ += used;
      if (parsed_ > kReadChunk) {
        buffer_.erase(0, parsed_);
        parsed_ = 0;
      }
      return true;
    }
    char chunk[kReadChunk];
    const ssize_t got = pread(fd_, chunk, sizeof chunk, read_pos_);
    if (got <= 0) return false;
    read_pos_ += got;
    buffer_.append(chunk, static_cast<size_t>(got));
  }
  return false;
}

void WatchLog::Reader::PushGap(int64_t to, std::vector<v1::WatchEvent>& out) {
  v1::WatchEvent gap;
  gap.set_wall_time(clock_.Now());
  gap.mutable_gap()->set_from_seq(expected_);
  gap.mutable_gap()->set_to_seq(to);
  gap.mutable_gap()->set_reason("not in the job's watch log (issued before the daemon kept one)");
  out.push_back(std::move(gap));
  expected_ = to + 1;
}

bool WatchLog::Reader::Next(size_t max, std::vector<v1::WatchEvent>& out) {
  const size_t before = out.size();
  while (expected_ <= upto_ && out.size() - before < max) {
    v1::WatchLogRecord record;
    if (!ReadRecord(record)) {
      // The log ends before the range does: those numbers are not held.
      PushGap(upto_, out);
      break;
    }
    const int64_t seq = record.event().seq();
    if (seq < expected_) continue;
    if (seq > upto_) {
      PushGap(upto_, out);
      break;
    }
    if (seq > expected_) PushGap(seq - 1, out);
    expected_ = seq + 1;
    if (record.event().has_snapshot()) {
      if (!snapshots_) continue;
      v1::WatchEvent whole;
      if (ReadSnapshotAt((fs::path(dir_) / kSnapshots).string(), record.snapshot_offset(), whole) &&
          whole.seq() == seq) {
        out.push_back(std::move(whole));
      } else {
        expected_ = seq;
        PushGap(seq, out);
      }
      continue;
    }
    out.push_back(std::move(*record.mutable_event()));
  }
  return expected_ <= upto_;
}

}  // namespace dlmfd::server
