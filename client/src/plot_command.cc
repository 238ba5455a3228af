// dlmfd plot RESULTS_DIR [--snapshot STEP] [--quantity trA|speed] [--out FILE] [--width W]
// [--height H]
//            [--log] [--window X0,Y0,X1,Y1]
// dlmfd plot --job JOB [--out FILE] ...      (the next trA snapshot a running job streams)
// Writes a PNG of trA (the speed for a Newtonian run) with the particles, prints its path.
// --log colours by log10 of the value; --window draws only that part of the domain (a close-up).
#include <cmath>
#include <filesystem>
#include <iostream>

#include "command.h"
#include "connection.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/viz/field_picture.h"
#include "dlmfd/viz/png_file.h"
#include "dlmfd/viz/results_frame.h"
#include "exit_codes.h"
#include "rpc_status.h"
#include "watch_session.h"

namespace dlmfd::cli {
namespace {

std::string Caption(const std::string& quantity, double time, long step) {
  return quantity + "  t = " + FormatLabel(time) + "  step " + std::to_string(step);
}

// A streamed snapshot as a node field on square cells. The daemon may downsample x and y by
// different factors; the values are then resampled bilinearly onto cells of the x spacing.
NodeField FieldOfSnapshot(const v1::Snapshot& s) {
  if (s.nx() < 1 || s.ny() < 1 || !(s.width() > 0) || !(s.height() > 0) ||
      s.values_size() != (s.nx() + 1) * (s.ny() + 1)) {
    throw Error("the streamed snapshot is malformed (" + std::to_string(s.values_size()) +
                " values for " + std::to_string(s.nx()) + "x" + std::to_string(s.ny()) + " cells)");
  }
  const double hx = s.width() / s.nx();
  const double hy = s.height() / s.ny();
  NodeField field;
  field.quantity = s.quantity().empty() ? "trA" : s.quantity();
  if (std::abs(hx - hy) <= 1e-9 * hx) {
    field.grid = Grid{s.nx(), s.ny(), hx, 0.0, 0.0};
    field.values.assign(s.values().begin(), s.values().end());
    return field;
  }
  const int ny = std::max(1, int(std::lround(s.height() / hx)));
  field.grid = Grid{s.nx(), ny, hx, 0.0, 0.0};
  field.values.resize(field.grid.NodeCount());
  for (int j = 0; j <= ny; ++j) {
    const double t = std::min(double(s.ny()), j * hx / hy);
    const int j0 = std::min(int(t), s.ny() - 1);
    const double b = t - j0;
    for (int i = 0; i <= s.nx(); ++i) {
      const float lower = s.values(j0 * (s.nx() + 1) + i);
      const float upper = s.values((j0 + 1) * (s.nx() + 1) + i);
      field.values[field.grid.Index(i, j)] = (1.0 - b) * lower + b * upper;
    }
  }
  return field;
}

// The field inside the window, or the whole field when no window was given.
NodeField Windowed(const NodeField& field, const std::vector<double>& window) {
  if (window.empty()) return field;
  return CropField(field, window[0], window[1], window[2], window[3]);
}

int PlotJob(const ConnectionFlags& flags, const std::string& job_id, const PictureOptions& base,
            const std::vector<double>& window, const std::string& out) {
  Connection connection(flags);
  WatchOptions options;
  options.job_id = job_id;
  options.include_snapshots = true;
  options.snapshot_max_width = base.max_width;
  options.snapshot_max_height = base.max_height;
  std::vector<DiskOutline> disks;
  v1::Snapshot snapshot;
  bool have_snapshot = false;
  const WatchOutcome outcome = WatchJob(connection, options, [&](const v1::WatchEvent& e) {
    if (e.has_particles()) {
      disks.clear();
      for (const auto& p : e.particles().particles()) disks.push_back({p.x(), p.y(), p.radius()});
    }
    if (e.has_snapshot()) {
      snapshot = e.snapshot();
      have_snapshot = true;
      return false;
    }
    return true;
  });
  if (outcome.interrupted) return kExitInterrupted;
  if (!outcome.status.ok()) return ReportRpcError("plot", outcome.status);
  if (!have_snapshot) {
    return ReportError("plot",
                       "job " + job_id +
                           " streamed no snapshot before it ended; fetch its results " +
                           "(dlmfd fetch " + job_id + ") and plot the directory",
                       kExitNotFound);
  }
  PictureOptions picture_options = base;
  const NodeField field = Windowed(FieldOfSnapshot(snapshot), window);
  if (picture_options.caption.empty())
    picture_options.caption = Caption(field.quantity, snapshot.time(), snapshot.step());
  const std::string path =
      out.empty() ? job_id + "_" + field.quantity + "_" + std::to_string(snapshot.step()) + ".png"
                  : out;
  WritePng(DrawFieldPicture(field, disks, picture_options).image, path);
  std::cout << path << "\n";
  return kExitOk;
}

}  // namespace

int RunPlot(int argc, char** argv) {
  CLI::App app{"Draw trA (or the speed) with the particles as a PNG."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string results_dir, job_id, quantity, out;
  long snapshot = -1;
  PictureOptions options;
  options.max_width = 1000;
  options.max_height = 1000;
  auto* dir_option =
      app.add_option("results", results_dir, "a results directory (dlmfd-solve --out, or fetched)");
  auto* job_option =
      app.add_option("--job", job_id, "a running job: draw the next snapshot it streams");
  dir_option->excludes(job_option);
  app.add_option("--snapshot", snapshot, "the snapshot's step (default: the latest)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--quantity", quantity, "trA or speed (default: trA when present)")
      ->check(CLI::IsMember({"trA", "speed"}));
  app.add_option("--out,-o", out, "PNG file to write");
  app.add_option("--width", options.max_width, "largest image width in pixels")
      ->check(CLI::Range(64, 8192));
  app.add_option("--height", options.max_height, "largest image height in pixels")
      ->check(CLI::Range(64, 8192));
  app.add_option("--caption", options.caption,
                 "text above the picture (default: quantity, time, step)");
  app.add_flag("--log", options.log_colours,
               "colour by log10 of the value (trA spans decades near particles)");
  std::vector<double> window;
  app.add_option("--window", window, "draw only [X0, X1] x [Y0, Y1] of the domain: X0,Y0,X1,Y1")
      ->expected(4)
      ->delimiter(',');
  if (auto code = ParseArgs(app, argc, argv)) return *code;
  if (results_dir.empty() == job_id.empty()) {
    return ReportError("plot", "name a results directory or --job JOB", kExitUsage);
  }

  return Guarded("plot", [&] {
    try {
      if (!job_id.empty()) return PlotJob(connection_flags, job_id, options, window, out);
      ResultsFrame frame = LoadResultsFrame(results_dir, snapshot, quantity);
      frame.field = Windowed(frame.field, window);
      if (options.caption.empty())
        options.caption = Caption(frame.field.quantity, frame.time, frame.step);
      const std::string path =
          out.empty() ? (std::filesystem::path(results_dir) /
                         (frame.field.quantity + "_" + std::to_string(frame.step) + ".png"))
                            .string()
                      : out;
      try {
        WritePng(DrawFieldPicture(frame.field, frame.disks, options).image, path);
      } catch (const InvalidParameter&) {
        throw;
      } catch (const Error& e) {
        return ReportError("plot", e.what(), kExitLocalIo);
      }
      std::cout << path << "\n";
      return kExitOk;
    } catch (const InvalidParameter& e) {
      throw UsageError(e.what());
    }
  });
}

}  // namespace dlmfd::cli
