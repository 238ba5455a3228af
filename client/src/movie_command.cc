// dlmfd movie JOB | RESULTS_DIR [--quantity Q] [--out FILE.mp4] [--fps F] [--every K]
//             [--from T] [--to T] [--keep DIR] [--ffmpeg PATH] [plot's drawing flags]
// A movie of a run from its field snapshots (design.md 3.2): one frame per snapshot, each a field
// picture (viz/field_picture.h) with the particles, the time and the colour bar, encoded by
// Debian's ffmpeg (viz/movie_encoder.h). The colour range is the same in every frame: --range, or
// the union of the frames' own ranges (inside --window; their extremes, or their percentiles for a
// signed quantity, [-m, m] on the diverging map: CommonRange), so colours compare across time. The
// frame size is the first frame's, rounded up to even sides (H.264 needs them).
// JOB (not an existing directory) is a job of the daemon: its scene.toml, particles.h5 and
// snapshots are fetched first (into --keep DIR, or a temporary folder removed afterwards), and the
// caption names the job and its overrides.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <vector>

#include "command.h"
#include "connection.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/io/field_snapshot.h"
#include "dlmfd/viz/results_frame.h"
#include "exit_codes.h"
#include "plot_options.h"
#include "rpc_status.h"
#include "run_movie.h"

namespace dlmfd::cli {
namespace {

namespace fs = std::filesystem;

struct MovieFlags {
  std::string source;
  std::string out;
  double fps = 10.0;
  int every = 1;
  double from = -HUGE_VAL;
  double to = HUGE_VAL;
  std::string keep;
  std::string ffmpeg = "ffmpeg";
};

// Fetches what a movie needs of job `job_id` into `dir` (dlmfd fetch, one --path per file) and
// sets the job's caption line; returns the status of an rpc that failed (its exit code is the
// status's, docs/cli.md), else OK.
grpc::Status FetchJob(const ConnectionFlags& flags, const std::string& job_id, const fs::path& dir,
                      std::string* caption) {
  Connection connection(flags);
  v1::Job job;
  {
    v1::GetRequest request;
    request.set_job_id(job_id);
    auto context = connection.UnaryContext();
    const grpc::Status status = connection.jobs().Get(context.get(), request, &job);
    if (!status.ok()) return status;
  }
  v1::ListFilesRequest request;
  request.set_job_id(job_id);
  v1::ListFilesResponse files;
  auto context = connection.UnaryContext();
  const grpc::Status status = connection.jobs().ListFiles(context.get(), request, &files);
  if (!status.ok()) return status;
  std::vector<std::string> args = {"dlmfd fetch", job_id, "--out", dir.string()};
  if (!flags.server.empty()) args.insert(args.end(), {"--server", flags.server});
  if (!flags.token.empty()) args.insert(args.end(), {"--token", flags.token});
  int snapshots = 0;
  for (const v1::FileInfo& f : files.files()) {
    const bool snapshot = f.path().rfind("fields/snap_", 0) == 0;
    if (snapshot || f.path() == "particles.h5" || f.path() == "scene.toml") {
      args.insert(args.end(), {"--path", f.path()});
      snapshots += snapshot;
    }
  }
  if (snapshots == 0) {
    throw UsageError("job " + job_id +
                     " has no field snapshots (output.fields_every = 0, or no "
                     "snapshot written yet)");
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  if (RunFetch(int(args.size()), argv.data()) != kExitOk)
    throw Error("fetching the snapshots of job " + job_id + " failed (see above)");
  *caption = JobCaption(job);
  return grpc::Status::OK;
}

// The steps of the snapshots inside [from, to], every k-th.
std::vector<long> ChosenSteps(const std::string& dir, const MovieFlags& m) {
  std::vector<long> chosen;
  std::size_t seen = 0;
  for (const long step : SnapshotSteps(dir)) {
    const double time =
        ReadFieldSnapshot((fs::path(dir) / "fields" / SnapshotFileName(step)).string()).time;
    if (time < m.from || time > m.to) continue;
    if (seen++ % std::size_t(m.every) == 0) chosen.push_back(step);
  }
  return chosen;
}

int MakeMovie(const std::string& dir, const std::string& run_caption, MovieFlags& m,
              PlotFlags& plot) {
  const std::vector<long> steps = ChosenSteps(dir, m);
  if (steps.empty()) {
    throw UsageError(dir + " has no field snapshots" +
                     (std::isfinite(m.from) || std::isfinite(m.to) ? " inside --from/--to" : "") +
                     " (output.fields_every > 0 writes them)");
  }
  const MovieSummary movie = WriteRunMovie(dir, steps, run_caption, plot, m.out, m.fps, m.ffmpeg);
  const long frames = movie.frames;
  std::cout << m.out << "\n";
  std::cerr << "movie: " << frames << " frames, " << plot.options.exact_width << "x"
            << plot.options.exact_height << ", " << FormatLabel(frames / m.fps) << " s at "
            << FormatLabel(m.fps) << " frames/s\n";
  return kExitOk;
}

}  // namespace

int RunMovie(int argc, char** argv) {
  CLI::App app{
      "Make a movie of a run from its field snapshots (ffmpeg): particles, time, colour bar."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  MovieFlags m;
  PlotFlags plot;
  app.add_option("source", m.source, "a results directory, or a job id of the daemon")->required();
  app.add_option("--out,-o", m.out,
                 "movie file: .mp4 (default <source>_<quantity>.mp4), .mkv, "
                 ".mov, .webm or .gif");
  app.add_option("--fps", m.fps, "frames per second (default 10)")->check(CLI::Range(0.1, 240.0));
  app.add_option("--every", m.every, "use every k-th snapshot (default 1)")
      ->check(CLI::PositiveNumber);
  app.add_option("--from", m.from, "first simulated time drawn (default: the first snapshot)");
  app.add_option("--to", m.to, "last simulated time drawn (default: the last snapshot)");
  app.add_option("--keep", m.keep, "for a job: fetch its snapshots into this folder and keep them");
  app.add_option("--ffmpeg", m.ffmpeg, "the ffmpeg program (default: ffmpeg from PATH)");
  AddPlotFlags(app, plot);
  plot.options.max_width = 800;
  plot.options.max_height = 800;
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("movie", [&] {
    try {
      CheckPlotFlags(plot, app);
      std::error_code ec;
      const bool local = fs::is_directory(m.source, ec);
      if (m.out.empty()) {
        std::string stem = fs::path(m.source).lexically_normal().filename().string();
        if (stem.empty() || stem == ".") stem = "movie";
        m.out = stem + "_" + FileStemOf(plot.quantity.empty() ? "trA" : plot.quantity) + ".mp4";
      }
      if (local) {
        const std::string caption = DirectoryCaption(m.source);
        return MakeMovie(m.source, caption, m, plot);
      }
      const bool temporary = m.keep.empty();
      const fs::path dir =
          temporary ? fs::temp_directory_path() / ("dlmfd_movie_" + std::to_string(::getpid()))
                    : fs::path(m.keep);
      struct Cleanup {
        fs::path dir;
        ~Cleanup() {
          std::error_code ignored;
          if (!dir.empty()) fs::remove_all(dir, ignored);
        }
      } cleanup{temporary ? dir : fs::path()};
      std::string caption;
      const grpc::Status status = FetchJob(connection_flags, m.source, dir, &caption);
      if (!status.ok()) return ReportRpcError("movie", status);
      return MakeMovie(dir.string(), caption, m, plot);
    } catch (const InvalidParameter& e) {
      throw UsageError(e.what());
    }
  });
}

}  // namespace dlmfd::cli
