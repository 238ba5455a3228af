#include "field_pictures.h"

#include <fstream>
#include <iterator>
#include <sstream>

#include "connection.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/viz/field_picture.h"
#include "dlmfd/viz/results_frame.h"
#include "http_reply.h"
#include "plot_options.h"
#include "result_files.h"
#include "study_chart.h"
#include "study_table.h"

namespace dlmfd::web {

bool PictureCache::Get(const std::string& key, std::string* png) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = entries_.begin(); it != entries_.end(); ++it) {
    if (it->first != key) continue;
    entries_.splice(entries_.begin(), entries_, it);
    *png = entries_.front().second;
    return true;
  }
  return false;
}

void PictureCache::Put(const std::string& key, const std::string& png) {
  std::lock_guard<std::mutex> lock(mutex_);
  entries_.emplace_front(key, png);
  while (entries_.size() > max_entries_) entries_.pop_back();
}

namespace {

Picture Failure(int status, const std::string& message) { return {status, message, {}}; }

Picture RpcFailure(const grpc::Status& status) {
  return Failure(HttpStatusOf(status.error_code()), "daemon: " + status.error_message());
}

std::string ReadWhole(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Drawing takes a core for a moment; one picture at a time keeps the machine's other work going.
std::mutex& DrawingMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

Picture LatestFieldPicture(DaemonLink& link, const std::string& token, const std::string& job_id,
                           const PictureSize& size, PictureCache& cache) {
  v1::ListFilesRequest list_request;
  list_request.set_job_id(job_id);
  v1::ListFilesResponse files;
  grpc::Status status = link.jobs().ListFiles(link.Unary(token).get(), list_request, &files);
  if (!status.ok()) return RpcFailure(status);
  const v1::FileInfo* snapshot = nullptr;
  bool has_particles = false, has_scene = false;
  for (const v1::FileInfo& file : files.files()) {
    const std::string& path = file.path();
    if (path.rfind("fields/snap_", 0) == 0 && path.size() > 3 &&
        path.compare(path.size() - 3, 3, ".h5") == 0 &&
        (snapshot == nullptr || path > snapshot->path())) {
      snapshot = &file;
    }
    has_particles |= path == "particles.h5";
    has_scene |= path == "scene.toml";
  }
  if (snapshot == nullptr) {
    return Failure(404, "job " + job_id + " has no field snapshot yet");
  }
  std::ostringstream key;
  key << job_id << '|' << snapshot->path() << '|' << snapshot->size() << '|'
      << snapshot->modified_time() << '|' << size.width << 'x' << size.height << '|'
      << size.caption;
  Picture picture;
  if (cache.Get(key.str(), &picture.data)) return picture;

  v1::GetRequest get_request;
  get_request.set_job_id(job_id);
  v1::Job job;
  status = link.jobs().Get(link.Unary(token).get(), get_request, &job);
  if (!status.ok()) return RpcFailure(status);
  ScratchDirectory scratch;
  status = FetchFileTo(link, token, job_id, snapshot->path(), scratch.path() / snapshot->path());
  if (status.ok() && has_particles) {
    status = FetchFileTo(link, token, job_id, "particles.h5", scratch.path() / "particles.h5");
  }
  if (status.ok() && has_scene) {
    status = FetchFileTo(link, token, job_id, "scene.toml", scratch.path() / "scene.toml");
  }
  if (!status.ok()) return RpcFailure(status);
  try {
    std::lock_guard<std::mutex> lock(DrawingMutex());
    const ResultsFrame frame = LoadResultsFrame(scratch.path().string());
    PictureOptions options;
    options.max_width = size.width;
    options.max_height = size.height;
    options.diverging = cli::DrawsDiverging(frame.field.quantity, options);
    if (size.caption) {
      options.caption = cli::JobCaption(job) + "\n" +
                        cli::FrameCaption(frame.field.quantity, frame.time, frame.step);
    }
    const std::filesystem::path png = scratch.path() / "picture.png";
    DrawFieldPicture(frame.field, frame.disks, options).image.Write(png.string());
    picture.data = ReadWhole(png);
  } catch (const InvalidParameter& e) {
    return Failure(400, e.what());  // a size with no room for the picture
  } catch (const Error& e) {
    return Failure(500, std::string("cannot draw the snapshot: ") + e.what());
  }
  cache.Put(key.str(), picture.data);
  return picture;
}

Picture StudyChartPicture(DaemonLink& link, const std::string& token, const std::string& study_id,
                          const ChartRequest& request) {
  v1::TableRequest table_request;
  table_request.set_study_id(study_id);
  v1::TableResponse rows;
  const grpc::Status status = link.jobs().Table(link.Unary(token).get(), table_request, &rows);
  if (!status.ok()) return RpcFailure(status);
  cli::StudyChartSpec spec;
  spec.study_id = study_id;
  spec.x = request.x;
  spec.y = request.y;
  spec.group = request.group;
  spec.log_x = request.log_x;
  spec.log_y = request.log_y;
  spec.options.width = request.width;
  spec.options.height = request.height;
  try {
    std::lock_guard<std::mutex> lock(DrawingMutex());
    cli::StudyChart chart = cli::DrawStudyChart(cli::FlattenTable(rows), spec);
    ScratchDirectory scratch;
    const std::filesystem::path png = scratch.path() / "chart.png";
    chart.picture.image.Write(png.string());
    return {200, "", ReadWhole(png)};
  } catch (const cli::UsageError& e) {
    return Failure(400, e.what());
  } catch (const InvalidParameter& e) {
    return Failure(400, e.what());
  } catch (const Error& e) {
    return Failure(500, std::string("cannot draw the chart: ") + e.what());
  }
}

}  // namespace dlmfd::web
