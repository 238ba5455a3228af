#include "result_files.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace dlmfd::web {

namespace {

// The reason a path is refused, or "" for a safe one.
std::string UnsafePathReason(const std::string& path) {
  if (path.empty()) return "the path is empty";
  if (path.size() > 4096) return "the path is longer than 4096 bytes";
  if (path.front() == '/') return "the path is absolute";
  for (char c : path) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == '\\') {
      return "the path holds a control byte or a backslash";
    }
  }
  for (size_t start = 0; start <= path.size();) {
    const size_t end = std::min(path.find('/', start), path.size());
    const std::string part = path.substr(start, end - start);
    if (part.empty() || part == "." || part == "..") {
      return "the path has an empty, '.' or '..' part (only files inside the job's results are "
             "served)";
    }
    start = end + 1;
  }
  return "";
}

}  // namespace

bool SafeResultPath(const std::string& path, std::string* why) {
  *why = UnsafePathReason(path);
  return why->empty();
}

grpc::Status FetchFileTo(DaemonLink& link, const std::string& token, const std::string& job_id,
                         const std::string& path, const std::filesystem::path& destination) {
  std::filesystem::create_directories(destination.parent_path());
  std::ofstream out(destination, std::ios::binary | std::ios::trunc);
  if (!out) return grpc::Status(grpc::StatusCode::INTERNAL, "cannot write " + destination.string());
  auto context = link.Stream(token);
  v1::FetchRequest request;
  request.set_job_id(job_id);
  request.set_path(path);
  auto reader = link.jobs().Fetch(context.get(), request);
  v1::FileChunk chunk;
  while (reader->Read(&chunk)) out.write(chunk.data().data(), std::streamsize(chunk.data().size()));
  grpc::Status status = reader->Finish();
  if (status.ok() && !out.flush()) {
    return grpc::Status(grpc::StatusCode::INTERNAL, "cannot write " + destination.string());
  }
  return status;
}

ScratchDirectory::ScratchDirectory() {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern =
      std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/dlmfd-web-XXXXXX";
  std::vector<char> text(pattern.begin(), pattern.end());
  text.push_back('\0');
  if (mkdtemp(text.data()) == nullptr) {
    throw std::runtime_error("cannot make a temporary directory like " + pattern);
  }
  path_ = text.data();
}

ScratchDirectory::~ScratchDirectory() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace dlmfd::web
