// A job's movie for its page: every field snapshot (at most 300, evenly thinned) drawn as `dlmfd
// movie JOB` draws it (client/src/run_movie.h: viz/ pictures, one colour range, Debian's ffmpeg,
// H.264 MP4 at 10 frames a second), from the snapshots, particles.h5 and scene.toml fetched
// through the daemon's Fetch. Movies are kept in a private directory of this process, at most
// `max_movies` (the oldest removed), keyed by the job and its snapshots (their count, the last one
// and its time of modification), so a running job's movie is made again once it has new frames.
// One movie is drawn at a time. The caller's own ListFiles comes first: a kept movie is never
// served to a user who may not see the job.
#pragma once

#include <cstddef>
#include <list>
#include <mutex>
#include <string>

#include "daemon_link.h"
#include "field_pictures.h"
#include "result_files.h"

namespace dlmfd::web {

class MovieCache {
 public:
  explicit MovieCache(std::size_t max_movies = 8)
      : max_movies_(max_movies) {}
  Picture Movie(DaemonLink& link, const std::string& token, const std::string& job_id);

 private:
  std::size_t max_movies_;
  std::mutex mutex_;  // held while a movie is looked up or drawn
  ScratchDirectory dir_;
  std::list<std::string> kept_;  // file names, newest first
};

}  // namespace dlmfd::web
