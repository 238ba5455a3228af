// Result-file serving: what Fetch and ListFiles (jobs.proto) read from a job's results directory.
//
// Paths are relative to the results directory, '/'-separated, sorted. Only the job's own files are
// served: a symbolic link is neither listed nor followed, whether it points out of the directory or
// into it. A requested path must be relative, free of NUL bytes and ".."; every file is opened one
// path component at a time with O_NOFOLLOW (openat), so a link put in place between the listing or
// the check and the read leads nowhere. Files are read as they are at the moment: the solver
// replaces the files others may read by rename, so a reader sees an old or a new file, never half
// of one.
#pragma once

#include <grpcpp/support/server_callback.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "dlmfd/v1/jobs.pb.h"

namespace dlmfd::server {

// The largest FileChunk's data (jobs.proto: at most 1 MiB).
inline constexpr int64_t kChunkBytes = 1 << 20;

// Every regular file under root (none when root is not a directory).
std::vector<std::string> ResultFilePaths(const std::filesystem::path& root);
// The ListFiles reply for root: path, size and modification time of each file.
void DescribeResultFiles(const std::filesystem::path& root, v1::ListFilesResponse* reply);
// The normalised relative path of one requested file. Throws ServiceError INVALID_ARGUMENT (an
// absolute path, "..", a NUL byte, a symbolic link on the way) or NOT_FOUND (no such regular
// file).
std::string CheckedResultPath(const std::filesystem::path& root, const std::string& path);
// A read-only descriptor of root/path (a normalised relative path), opened without following any
// symbolic link; the caller closes it. Throws as CheckedResultPath.
int OpenResultFile(const std::filesystem::path& root, const std::string& path);

// Streams the given files (relative to root) in chunks of at most kChunkBytes; deletes itself.
class FetchReactor final : public grpc::ServerWriteReactor<v1::FileChunk> {
 public:
  FetchReactor(std::filesystem::path root, std::vector<std::string> files);
  ~FetchReactor() override;
  void OnWriteDone(bool ok) override;
  void OnDone() override { delete this; }

 private:
  // Writes the next chunk, or finishes the stream (OK after the last file, the error otherwise).
  void Next();

  const std::filesystem::path root_;
  const std::vector<std::string> files_;
  size_t index_ = 0;
  int fd_ = -1;  // the file being sent
  int64_t size_ = 0, offset_ = 0;
  bool done_ = false;
  v1::FileChunk chunk_;
};

}  // namespace dlmfd::server
