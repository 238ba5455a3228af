// dlmfd plot RESULTS_DIR [--snapshot STEP] [--quantity Q] [--out FILE.png|.svg|.pdf]
//            [--width W] [--height H] [--log] [--range MIN,MAX] [--window X0,Y0,X1,Y1]
//            [--isolines N] [--lines-only] [--arrows N] [--streamlines N] [--caption TEXT]
//            [--no-caption] [--size W,H --dpi D --font-size PT] [--units cgs|si] [--percentile P]
// dlmfd plot --job JOB [--out FILE] ...      (the next snapshot a running job streams)
// Draws a field of a snapshot (viz/field_picture.h) with axes, a colour bar, the particles and a
// caption naming the run (scene title, directory or job name and its overrides), quantity, time
// and step; prints the file's path. The format follows the file's extension.
#include <cmath>
#include <filesystem>
#include <iostream>

#include "command.h"
#include "connection.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/viz/field_picture.h"
#include "dlmfd/viz/node_quantities.h"
#include "dlmfd/viz/results_frame.h"
#include "exit_codes.h"
#include "figure_panel.h"
#include "plot_options.h"
#include "rpc_status.h"
#include "watch_session.h"

namespace dlmfd::cli {
namespace {

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

int PlotJob(const ConnectionFlags& flags, const std::string& job_id, const PlotFlags& plot,
            const std::string& out) {
  if (!plot.quantity.empty() && plot.quantity != "trA" && plot.quantity != "speed") {
    throw UsageError(
        "--job streams trA (or the speed of a Newtonian run) only; fetch the results "
        "(dlmfd fetch " +
        job_id + ") to draw " + plot.quantity);
  }
  if (plot.options.arrows > 0 || plot.options.streamlines > 0) {
    throw UsageError(
        "--arrows and --streamlines need the velocity: fetch the results (dlmfd fetch " + job_id +
        ")");
  }
  Connection connection(flags);
  WatchOptions options;
  options.job_id = job_id;
  options.include_snapshots = true;
  options.snapshot_max_width = plot.options.max_width;
  options.snapshot_max_height = plot.options.max_height;
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
  const NodeField field = Windowed(FieldOfSnapshot(snapshot), plot.window);
  v1::Job job = outcome.job;  // as of its latest state change; the id at least
  if (job.id().empty()) job.set_id(job_id);
  PictureOptions picture_options =
      FrameOptions(plot, field.quantity, JobCaption(job),
                   FrameCaption(field.quantity, snapshot.time(), snapshot.step()));
  picture_options.diverging = DrawsDiverging(field.quantity, picture_options);
  const std::string path =
      out.empty() ? job_id + "_" + field.quantity + "_" + std::to_string(snapshot.step()) + ".png"
                  : out;
  FieldPicture picture = DrawFieldPicture(field, disks, picture_options);
  picture.image.SetResolution(OutputDpi(plot));
  picture.image.Write(path);
  std::cout << path << "\n";
  return kExitOk;
}

}  // namespace

int RunPlotCommand(int argc, char** argv, const PanelRequest* panel) {
  CLI::App app{"Draw a field of a snapshot with axes, colour bar and particles (PNG, SVG or PDF)."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string results_dir, job_id, out;
  long snapshot = -1;
  PlotFlags plot;
  auto* dir_option =
      app.add_option("results", results_dir, "a results directory (dlmfd-solve --out, or fetched)");
  auto* job_option =
      app.add_option("--job", job_id, "a running job: draw the next snapshot it streams");
  dir_option->excludes(job_option);
  app.add_option("--snapshot", snapshot, "the snapshot's step (default: the latest)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--out,-o", out, "file to write: .png, .svg or .pdf");
  AddPlotFlags(app, plot);
  if (auto code = ParseArgs(app, argc, argv)) return *code;
  if (results_dir.empty() == job_id.empty()) {
    return ReportError("plot", "name a results directory or --job JOB", kExitUsage);
  }

  return Guarded("plot", [&] {
    try {
      if (panel != nullptr) {
        for (const char* flag :
             {"--width", "--height", "--size", "--dpi", "--font-size", "--out"}) {
          if (app.count(flag) > 0)
            throw UsageError(std::string(flag) + " is the figure's, not a panel's");
        }
        if (!job_id.empty())
          throw UsageError("a figure's panel draws a results directory, not --job");
        plot.options.exact_width = panel->width;
        plot.options.exact_height = panel->height;
        plot.options.max_width = panel->width;
        plot.options.max_height = panel->height;
      }
      CheckPlotFlags(plot, app);
      if (panel != nullptr) plot.options.font_size = panel->font_size;
      if (!out.empty()) FormatOfPath(out);
      if (!job_id.empty()) return PlotJob(connection_flags, job_id, plot, out);
      ResultsFrame frame = LoadResultsFrame(results_dir, snapshot, plot.quantity);
      if (!frame.particles_note.empty())
        std::cerr << "dlmfd plot: " << frame.particles_note << "\n";
      const PictureOptions options =
          FrameOptions(plot, frame.field.quantity,
                       plot.no_caption || plot.caption_given ? "" : DirectoryCaption(results_dir),
                       FrameCaption(frame.field.quantity, frame.time, frame.step));
      const std::string path =
          out.empty()
              ? (std::filesystem::path(results_dir) /
                 (FileStemOf(frame.field.quantity) + "_" + std::to_string(frame.step) + ".png"))
                    .string()
              : out;
      if (panel != nullptr) {
        *panel->result = std::move(DrawFrame(frame, plot, options).image);
        return kExitOk;
      }
      try {
        FieldPicture picture = DrawFrame(frame, plot, options);
        picture.image.SetResolution(OutputDpi(plot));
        picture.image.Write(path);
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

int RunPlot(int argc, char** argv) { return RunPlotCommand(argc, argv, nullptr); }

int RunPlotPanel(int argc, char** argv, const PanelRequest& request) {
  return RunPlotCommand(argc, argv, &request);
}

}  // namespace dlmfd::cli
