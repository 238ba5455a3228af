#include "result_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <system_error>
#include <utility>

#include "service_error.h"

namespace dlmfd::server {
namespace fs = std::filesystem;
namespace {

using grpc::StatusCode;

// The regular files under a results directory, relative paths, sorted. A symbolic link is not a
// file of the job: it is skipped, and a linked directory is not entered (the iterator follows no
// directory link by default).
std::vector<std::pair<std::string, fs::directory_entry>> ResultFiles(const fs::path& root) {
  std::vector<std::pair<std::string, fs::directory_entry>> files;
  std::error_code error;
  // The results directory itself must not be a link either: only the job's own files are served.
  if (!fs::is_directory(fs::symlink_status(root, error))) return files;
  for (auto it = fs::recursive_directory_iterator(root, error);
       !error && it != fs::recursive_directory_iterator(); it.increment(error)) {
    if (fs::is_regular_file(it->symlink_status(error))) {
      files.emplace_back(it->path().lexically_relative(root).generic_string(), *it);
    }
  }
  std::sort(files.begin(), files.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  return files;
}

}  // namespace

std::vector<std::string> ResultFilePaths(const fs::path& root) {
  std::vector<std::string> paths;
  for (auto& [path, entry] : ResultFiles(root)) paths.push_back(path);
  return paths;
}

void DescribeResultFiles(const fs::path& root, v1::ListFilesResponse* reply) {
  for (auto& [path, entry] : ResultFiles(root)) {
    std::error_code error;
    auto* info = reply->add_files();
    info->set_path(path);
    info->set_size(static_cast<int64_t>(entry.file_size(error)));
    const auto modified = entry.last_write_time(error);
    const auto system = std::chrono::time_point_cast<std::chrono::system_clock::duration>(
        modified - fs::file_time_type::clock::now() + std::chrono::system_clock::now());
    info->set_modified_time(std::chrono::duration<double>(system.time_since_epoch()).count());
  }
}

std::string CheckedResultPath(const fs::path& root, const std::string& path) {
  RequireNoNul("path", path);
  const fs::path wanted(path);
  Require(wanted.is_relative(), "path: must be relative to the results directory");
  Require(
      path.empty() || path.back() != '/',
      "path: " + CutForMessage(path) + " ends with '/': expected a file of the results directory");
  for (const auto& part : wanted) {
    Require(part != "..", "path: must not contain \"..\"");
  }
  const std::string normal = wanted.lexically_normal().generic_string();
  close(OpenResultFile(root, normal));
  return normal;
}

int OpenResultFile(const fs::path& root, const std::string& path) {
  const auto refuse_link = [&](const std::string& part) {
    return ServiceError(StatusCode::INVALID_ARGUMENT,
                        "path: " + CutForMessage(part) +
                            " is a symbolic link or not a directory; only the files inside the "
                            "job's results directory are served");
  };
  const auto not_found = [&] {
    return ServiceError(StatusCode::NOT_FOUND, "file " + CutForMessage(path) + " not found");
  };
  int fd = open(root.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ELOOP || errno == ENOTDIR) throw refuse_link("the results directory");
    throw not_found();
  }
  std::vector<std::string> parts;
  for (const auto& part : fs::path(path)) {
    if (!part.empty() && part != ".") parts.push_back(part.string());
  }
  std::string walked;
  for (size_t i = 0; i < parts.size(); ++i) {
    walked += (walked.empty() ? "" : "/") + parts[i];
    const bool last = i + 1 == parts.size();
    const int flags = O_RDONLY | O_NOFOLLOW | O_CLOEXEC | (last ? O_NONBLOCK : O_DIRECTORY);
    const int next = openat(fd, parts[i].c_str(), flags);
    const int error = errno;
    close(fd);
    if (next < 0) {
      // O_NOFOLLOW: a link fails with ELOOP; O_DIRECTORY: a file on the way with ENOTDIR.
      if (error == ELOOP || error == ENOTDIR) throw refuse_link(walked);
      throw not_found();
    }
    fd = next;
  }
  struct stat info {};
  if (parts.empty() || fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    close(fd);
    throw not_found();
  }
  return fd;
}

FetchReactor::FetchReactor(fs::path root, std::vector<std::string> files)
    : root_(std::move(root)),
      files_(std::move(files)) {
  Next();
}

FetchReactor::~FetchReactor() {
  if (fd_ >= 0) close(fd_);
}

void FetchReactor::OnWriteDone(bool ok) {
  if (!ok) {
    Finish(grpc::Status(StatusCode::CANCELLED, "fetch cancelled"));
    return;
  }
  Next();
}

void FetchReactor::Next() {
  grpc::Status status = Guarded([&] {
    while (true) {
      if (fd_ < 0) {
        if (index_ >= files_.size()) {
          done_ = true;
          return;
        }
        // Opened again here, link by link: what was listed may have been replaced since.
        fd_ = OpenResultFile(root_, files_[index_]);
        struct stat info {};
        size_ = fstat(fd_, &info) == 0 ? static_cast<int64_t>(info.st_size) : 0;
        offset_ = 0;
      }
      const int64_t length = std::min<int64_t>(kChunkBytes, std::max<int64_t>(size_ - offset_, 0));
      chunk_.Clear();
      chunk_.set_path(files_[index_]);
      chunk_.set_offset(offset_);
      chunk_.set_size(size_);
      std::string* data = chunk_.mutable_data();
      data->resize(static_cast<size_t>(length));
      ssize_t got = 0;
      while (length > 0 &&
             (got = pread(fd_, data->data(), static_cast<size_t>(length), offset_)) < 0 &&
             errno == EINTR) {}
      if (got < 0) {
        throw ServiceError(StatusCode::INTERNAL, files_[index_] + ": cannot be read");
      }
      data->resize(static_cast<size_t>(got));
      offset_ += static_cast<int64_t>(data->size());
      const bool last = offset_ >= size_ || data->empty();
      chunk_.set_last(last);
      if (last) {
        close(fd_);
        fd_ = -1;
        ++index_;
      }
      return;
    }
  });
  if (!status.ok()) {
    Finish(status);
  } else if (done_) {
    Finish(grpc::Status::OK);
  } else {
    StartWrite(&chunk_);
  }
}

}  // namespace dlmfd::server
