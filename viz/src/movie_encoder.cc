// MovieEncoder: fork + exec of ffmpeg with a pipe on its stdin and its stderr in a log file.
#include "dlmfd/viz/movie_encoder.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "dlmfd/core/errors.h"
#include "dlmfd/viz/field_picture.h"

namespace dlmfd {
namespace {

namespace fs = std::filesystem;

std::string Extension(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

std::string LastLines(const std::string& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  std::string all = text.str();
  while (!all.empty() && (all.back() == '\n' || all.back() == '\r')) all.pop_back();
  const std::size_t cut = all.size() > 600 ? all.size() - 600 : 0;
  return all.substr(cut);
}

// Writes all of `size` bytes, retrying after signals; false when the pipe is broken.
bool WriteAll(int fd, const std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= std::size_t(n);
  }
  return true;
}

}  // namespace

MovieEncoder::MovieEncoder(const std::string& path, int width, int height, double frames_per_second,
                           const std::string& ffmpeg)
    : path_(path),
      width_(width),
      height_(height) {
  const std::string extension = Extension(path);
  const bool h264 = extension == ".mp4" || extension == ".mkv" || extension == ".mov";
  if (!h264 && extension != ".gif" && extension != ".webm") {
    throw InvalidParameter("movie file", path, "a name ending in .mp4, .mkv, .mov, .webm or .gif");
  }
  if (width < 2 || height < 2 || width % 2 != 0 || height % 2 != 0) {
    throw InvalidParameter("movie frame size", std::to_string(width) + "x" + std::to_string(height),
                           "even sides of at least 2 pixels");
  }
  if (!(frames_per_second > 0.0 && frames_per_second <= 240.0)) {
    throw InvalidParameter("frames per second", FormatLabel(frames_per_second), "in (0, 240]");
  }
  const fs::path target(path);
  const std::string stem = "." + target.stem().string() + ".partial";
  temporary_ = (target.parent_path() / (stem + extension)).string();
  log_path_ = (target.parent_path() / (stem + ".log")).string();

  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  std::vector<std::string> args = {ffmpeg, "-y",       "-loglevel",  "error",
                                   "-f",   "rawvideo", "-pix_fmt",   "rgb24",
                                   "-s",   size,       "-framerate", FormatLabel(frames_per_second),
                                   "-i",   "-"};
  if (h264) {
    args.insert(args.end(), {"-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "20", "-movflags",
                             "+faststart"});
  }
  args.push_back(temporary_);

  int fds[2];
  if (::pipe(fds) != 0)
    throw Error(std::string("cannot create a pipe for ffmpeg: ") + std::strerror(errno));
  const int log = ::open(log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error("cannot write " + log_path_ + ": " + std::strerror(errno));
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  child_ = ::fork();
  if (child_ == 0) {
    ::dup2(fds[0], STDIN_FILENO);
    ::dup2(log, STDERR_FILENO);
    ::dup2(log, STDOUT_FILENO);
    ::close(fds[0]);
    ::close(fds[1]);
    ::execvp(argv[0], argv.data());
    const char message[] = "cannot start ffmpeg\n";
    (void)!::write(STDERR_FILENO, message, sizeof(message) - 1);
    ::_exit(127);
  }
  ::close(fds[0]);
  ::close(log);
  if (child_ < 0) {
    ::close(fds[1]);
    throw Error(std::string("cannot start ffmpeg: ") + std::strerror(errno));
  }
  pipe_ = fds[1];
  ::fcntl(pipe_, F_SETFD, FD_CLOEXEC);
}

MovieEncoder::~MovieEncoder() { Abandon(); }

void MovieEncoder::Abandon() {
  if (pipe_ >= 0) ::close(pipe_);
  pipe_ = -1;
  if (child_ > 0) {
    ::kill(child_, SIGTERM);
    int status = 0;
    ::waitpid(child_, &status, 0);
    child_ = -1;
    std::error_code ec;
    fs::remove(temporary_, ec);
    fs::remove(log_path_, ec);
  }
}

void MovieEncoder::AddFrame(const RgbImage& frame) {
  if (frame.width != width_ || frame.height != height_) {
    throw InvalidParameter(
        "movie frame " + std::to_string(frames_),
        std::to_string(frame.width) + "x" + std::to_string(frame.height),
        "the size of the first frame, " + std::to_string(width_) + "x" + std::to_string(height_));
  }
  if (pipe_ < 0) throw Error("the movie " + path_ + " is already finished");
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &previous);
  const bool written = WriteAll(pipe_, frame.rgb.data(), frame.rgb.size());
  ::sigaction(SIGPIPE, &previous, nullptr);
  if (!written) {
    const std::string words = LastLines(log_path_);
    Abandon();
    throw Error("ffmpeg stopped taking frames for " + path_ + ": " + words);
  }
  ++frames_;
}

long MovieEncoder::Finish() {
  if (pipe_ < 0) throw Error("the movie " + path_ + " is already finished");
  ::close(pipe_);
  pipe_ = -1;
  int status = 0;
  while (::waitpid(child_, &status, 0) < 0 && errno == EINTR) {}
  child_ = -1;
  std::error_code ec;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string words = LastLines(log_path_);
    fs::remove(temporary_, ec);
    fs::remove(log_path_, ec);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
      throw Error("cannot start ffmpeg (install Debian's ffmpeg: scripts/setup.sh): " + words);
    throw Error("ffmpeg failed to write " + path_ + ": " + words);
  }
  fs::remove(log_path_, ec);
  fs::rename(temporary_, path_, ec);
  if (ec) throw Error("cannot rename " + temporary_ + " to " + path_ + ": " + ec.message());
  return frames_;
}

}  // namespace dlmfd
