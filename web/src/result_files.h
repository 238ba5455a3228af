// A job's result files through the daemon's Fetch and ListFiles only (the daemon checks that a path
// stays inside the job and follows no link; this process never opens a path of the daemon's
// machine). The dashboard's downloads stream them; its pictures fetch the few files they draw into
// a private temporary directory that is removed afterwards.
#pragma once

#include <filesystem>
#include <string>

#include "daemon_link.h"

namespace dlmfd::web {

// A relative path of a job's results: no empty, ".", ".." or absolute part, no NUL, backslash or
// control byte, at most 4096 bytes. On false, *why says what is wrong.
bool SafeResultPath(const std::string& path, std::string* why);

// Writes the file `path` of the job to `destination` (its folders made).
grpc::Status FetchFileTo(DaemonLink& link, const std::string& token, const std::string& job_id,
                         const std::string& path, const std::filesystem::path& destination);

// A private temporary directory (mode 0700 under $TMPDIR or /tmp), removed with its contents when
// this goes.
class ScratchDirectory {
 public:
  ScratchDirectory();
  ~ScratchDirectory();
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace dlmfd::web
