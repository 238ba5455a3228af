// The dashboard's pictures, drawn by viz/ as the CLI draws them (same colour maps, captions and
// charts): a job's latest field snapshot (`dlmfd plot` of the fetched results: trA for an
// Oldroyd-B run, else the speed, with the particles), full size or as a thumbnail, and a study's
// chart of a result against a parameter (`dlmfd chart --study`). The snapshot and particles.h5 come
// through the daemon's Fetch into a scratch directory. Field pictures are kept in a small cache
// keyed by the job, the snapshot file, its time of modification and the size asked; the caller's
// own ListFiles comes first, so a cached picture is never shown to a user who may not see the job.
#pragma once

#include <cstddef>
#include <list>
#include <mutex>
#include <string>
#include <utility>

#include "daemon_link.h"

namespace dlmfd::web {

// Least recently used PNGs, at most `max_entries`.
class PictureCache {
 public:
  explicit PictureCache(std::size_t max_entries = 128)
      : max_entries_(max_entries) {}
  bool Get(const std::string& key, std::string* png);
  void Put(const std::string& key, const std::string& png);

 private:
  std::size_t max_entries_;
  std::mutex mutex_;
  std::list<std::pair<std::string, std::string>> entries_;  // most recent first
};

struct PictureSize {
  int width = 900;
  int height = 900;
  bool caption = true;  // the job's name, overrides, quantity, time and step above the field
};

// The outcome of drawing: a PNG (or a movie), or an HTTP status and message.
struct Picture {
  int status = 200;
  std::string message;
  std::string data;  // the file's bytes
};

Picture LatestFieldPicture(DaemonLink& link, const std::string& token, const std::string& job_id,
                           const PictureSize& size, PictureCache& cache);

struct ChartRequest {
  std::string x, y, group;
  bool log_x = false, log_y = false;
  int width = 900, height = 600;
};
Picture StudyChartPicture(DaemonLink& link, const std::string& token, const std::string& study_id,
                          const ChartRequest& request);

}  // namespace dlmfd::web
