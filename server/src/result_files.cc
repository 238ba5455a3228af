#include "result_files.h"

#include <algorithm>
#include <chrono>
#include <system_error>
#include <utility>

#include "service_error.h"

namespace dlmfd::server {
namespace fs = std::filesystem;
namespace {

using grpc::StatusCode;

// The files under a results directory, relative paths, sorted.
std::vector<std::pair<std::string, fs::directory_entry>> ResultFiles(const fs::path& root) {
  std::vector<std::pair<std::string, fs::directory_entry>> files;
  std::error_code error;
  if (!fs::is_directory(root, error)) return files;
  for (auto it = fs::recursive_directory_iterator(root, error);
       !error && it != fs::recursive_directory_iterator(); it.increment(error)) {
    if (it->is_regular_file(error)) {
      files.emplace_back(fs::relative(it->path(), root, error).generic_string(), *it);
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
  const fs::path wanted(path);
  Require(wanted.is_relative(), "path: must be relative to the results directory");
  for (const auto& part : wanted) {
    Require(part != "..", "path: must not contain \"..\"");
  }
  std::error_code error;
  const fs::path full = fs::weakly_canonical(root / wanted, error);
  const fs::path base = fs::weakly_canonical(root, error);
  const std::string full_text = full.string(), base_text = base.string() + "/";
  Require(!error && full_text.compare(0, base_text.size(), base_text) == 0,
          "path: leaves the results directory");
  if (!fs::is_regular_file(full, error)) {
    throw ServiceError(StatusCode::NOT_FOUND, "file " + path + " not found");
  }
  return wanted.lexically_normal().generic_string();
}

FetchReactor::FetchReactor(fs::path root, std::vector<std::string> files)
    : root_(std::move(root)),
      files_(std::move(files)) {
  Next();
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
      if (!in_.is_open()) {
        if (index_ >= files_.size()) {
          done_ = true;
          return;
        }
        const fs::path path = root_ / files_[index_];
        in_.open(path, std::ios::binary);
        if (!in_) throw ServiceError(StatusCode::NOT_FOUND, files_[index_] + ": cannot be read");
        std::error_code error;
        size_ = static_cast<int64_t>(fs::file_size(path, error));
        offset_ = 0;
      }
      const int64_t length = std::min<int64_t>(kChunkBytes, std::max<int64_t>(size_ - offset_, 0));
      chunk_.Clear();
      chunk_.set_path(files_[index_]);
      chunk_.set_offset(offset_);
      chunk_.set_size(size_);
      std::string* data = chunk_.mutable_data();
      data->resize(static_cast<size_t>(length));
      in_.read(data->data(), length);
      data->resize(static_cast<size_t>(in_.gcount()));
      offset_ += static_cast<int64_t>(data->size());
      const bool last = offset_ >= size_ || data->empty();
      chunk_.set_last(last);
      if (last) {
        in_.close();
        in_.clear();
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
