#include "job_movie.h"

#include <algorithm>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <vector>

#include "dlmfd/core/errors.h"
#include "dlmfd/io/field_snapshot.h"
#include "http_reply.h"
#include "plot_options.h"
#include "run_movie.h"

namespace dlmfd::web {
namespace {

constexpr std::size_t kMaxFrames = 300;

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

Picture MovieCache::Movie(DaemonLink& link, const std::string& token, const std::string& job_id) {
  v1::ListFilesRequest list_request;
  list_request.set_job_id(job_id);
  v1::ListFilesResponse files;
  grpc::Status status = link.jobs().ListFiles(link.Unary(token).get(), list_request, &files);
  if (!status.ok()) {
    return {HttpStatusOf(status.error_code()), "daemon: " + status.error_message(), {}};
  }
  std::vector<const v1::FileInfo*> snapshots;
  std::vector<std::string> others;
  for (const v1::FileInfo& file : files.files()) {
    const std::string& path = file.path();
    if (path.rfind("fields/snap_", 0) == 0) snapshots.push_back(&file);
    if (path == "particles.h5" || path == "scene.toml") others.push_back(path);
  }
  if (snapshots.empty()) return {404, "job " + job_id + " has no field snapshot yet", {}};
  std::sort(snapshots.begin(), snapshots.end(),
            [](const v1::FileInfo* a, const v1::FileInfo* b) { return a->path() < b->path(); });
  std::ostringstream key;
  key << job_id << '|' << snapshots.size() << '|' << snapshots.back()->path() << '|'
      << snapshots.back()->modified_time();
  const std::string name =
      job_id + "-" + std::to_string(std::hash<std::string>()(key.str())) + ".mp4";

  std::lock_guard<std::mutex> lock(mutex_);
  if (std::find(kept_.begin(), kept_.end(), name) != kept_.end()) {
    return {200, "", ReadFile(dir_.path() / name)};
  }
  v1::GetRequest get_request;
  get_request.set_job_id(job_id);
  v1::Job job;
  status = link.jobs().Get(link.Unary(token).get(), get_request, &job);
  if (!status.ok())
    return {HttpStatusOf(status.error_code()), "daemon: " + status.error_message(), {}};
  ScratchDirectory scratch;
  const std::size_t stride = (snapshots.size() + kMaxFrames - 1) / kMaxFrames;
  for (std::size_t k = 0; k < snapshots.size(); ++k) {
    if (k % stride != 0 && k + 1 != snapshots.size()) continue;
    others.push_back(snapshots[k]->path());
  }
  for (const std::string& path : others) {
    status = FetchFileTo(link, token, job_id, path, scratch.path() / path);
    if (!status.ok())
      return {HttpStatusOf(status.error_code()), "daemon: " + status.error_message(), {}};
  }
  try {
    cli::PlotFlags plot;
    plot.options.max_width = 800;
    plot.options.max_height = 800;
    cli::WriteRunMovie(scratch.path().string(), SnapshotSteps(scratch.path().string()),
                       cli::JobCaption(job), plot, (dir_.path() / name).string(), 10.0, "ffmpeg");
  } catch (const Error& e) {
    return {500, std::string("cannot make the movie: ") + e.what(), {}};
  }
  kept_.push_front(name);
  while (kept_.size() > max_movies_) {
    std::error_code ignored;
    std::filesystem::remove(dir_.path() / kept_.back(), ignored);
    kept_.pop_back();
  }
  return {200, "", ReadFile(dir_.path() / name)};
}

}  // namespace dlmfd::web
