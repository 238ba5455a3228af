// A movie file from pictures: Debian's ffmpeg run as a child process, frames piped to its stdin as
// raw 8-bit RGB (design.md 2: a well-kept tool, not our own encoder).
//
// Method: `ffmpeg -f rawvideo -pix_fmt rgb24 -s WxH -framerate F -i -` and, for .mp4, .mkv and
// .mov, H.264 (libx264, yuv420p, which needs even sides: the frame size must be even; constant
// rate factor 20, +faststart so a browser plays it while loading); .gif and .webm use ffmpeg's
// default encoder for the container. Every frame must have the size of the first. The movie is
// written under a temporary name in the target's folder (keeping its extension, which ffmpeg reads)
// and renamed when ffmpeg has exited with status 0 (design.md 3.2). SIGPIPE is ignored while
// writing so that an ffmpeg that dies makes a write fail with an error, not kill the caller.
// Not supported: audio, variable frame rates.
#pragma once

#include <sys/types.h>

#include <string>

#include "dlmfd/viz/canvas.h"

namespace dlmfd {

class MovieEncoder {
 public:
  // Starts `ffmpeg` (a path or a name looked up in PATH). Throws InvalidParameter for an
  // unsupported extension, an odd or empty frame size or a rate outside (0, 240], dlmfd::Error when
  // ffmpeg cannot be started.
  MovieEncoder(const std::string& path, int width, int height, double frames_per_second,
               const std::string& ffmpeg = "ffmpeg");
  ~MovieEncoder();  // an unfinished movie is abandoned: ffmpeg stopped, the temporary removed
  MovieEncoder(const MovieEncoder&) = delete;
  MovieEncoder& operator=(const MovieEncoder&) = delete;

  // Throws InvalidParameter when the frame's size differs, dlmfd::Error when ffmpeg has gone.
  void AddFrame(const RgbImage& frame);
  // Closes the pipe, waits for ffmpeg and renames the movie into place; throws dlmfd::Error with
  // ffmpeg's last words (its stderr) when it failed. Returns the number of frames written.
  long Finish();

 private:
  void Abandon();

  std::string path_;
  std::string temporary_;
  std::string log_path_;
  int width_;
  int height_;
  pid_t child_ = -1;
  int pipe_ = -1;
  long frames_ = 0;
};

}  // namespace dlmfd
