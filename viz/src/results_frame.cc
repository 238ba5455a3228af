// LoadResultsFrame: snapshot + particle record of a results directory, read with the results
// readers (dlmfd_results).
#include "dlmfd/viz/results_frame.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "dlmfd/core/errors.h"
#include "dlmfd/io/atomic_file.h"
#include "dlmfd/io/field_snapshot.h"
#include "dlmfd/io/particle_history.h"
#include "dlmfd/viz/node_quantities.h"

namespace dlmfd {
namespace {

namespace fs = std::filesystem;

std::string ListSteps(const std::vector<long>& steps) {
  if (steps.empty()) return "none";
  std::string text;
  const std::size_t shown = std::min<std::size_t>(steps.size(), 12);
  for (std::size_t k = steps.size() - shown; k < steps.size(); ++k)
    text += (text.empty() ? "" : ", ") + std::to_string(steps[k]);
  return (shown < steps.size() ? "..., " : "") + text;
}

// Each particle's angle at record r: the stored /angle, else the trapezoidal integral of the
// recorded angular velocity from the first record.
std::vector<double> RecordAngles(const ParticleHistory& h, std::size_t r) {
  const std::size_t np = h.particles;
  if (h.angle.size() == h.records * np) {
    return std::vector<double>(h.angle.begin() + r * np, h.angle.begin() + (r + 1) * np);
  }
  std::vector<double> angle(np, 0.0);
  for (std::size_t s = 1; s <= r; ++s) {
    for (std::size_t k = 0; k < np; ++k) {
      angle[k] += 0.5 * (h.time[s] - h.time[s - 1]) *
                  (h.angular_velocity[s * np + k] + h.angular_velocity[(s - 1) * np + k]);
    }
  }
  return angle;
}

// An ellipse of particles.h5 (shape 1) drawn as one.
void SetEllipse(const ParticleHistory& h, std::size_t k, DiskOutline& disk) {
  if (h.shape.size() != h.particles || h.shape[k] != 1 || h.semi_axes.size() != 2 * h.particles)
    return;
  disk.semi_a = h.semi_axes[2 * k];
  disk.semi_b = h.semi_axes[2 * k + 1];
}

// The angles at time t from particles.h5 (between records: linear), or none without the file.
std::vector<double> AnglesAt(const std::string& results_dir, double t, std::size_t np) {
  const fs::path path = fs::path(results_dir) / "particles.h5";
  std::error_code ec;
  if (np == 0 || !fs::exists(path, ec)) return {};
  const ParticleHistory h = ReadParticleHistory(path.string());
  if (h.particles != np || h.records == 0) return {};
  std::size_t r = 0;
  while (r + 1 < h.records && h.time[r + 1] <= t) ++r;
  std::vector<double> angle = RecordAngles(h, r);
  if (r + 1 < h.records && h.time[r] < t) {
    const std::vector<double> next = RecordAngles(h, r + 1);
    const double w = (t - h.time[r]) / (h.time[r + 1] - h.time[r]);
    for (std::size_t k = 0; k < np; ++k) angle[k] += w * (next[k] - angle[k]);
  }
  return angle;
}

// The disks of a format-1 snapshot from particles.h5: the record of its step, else interpolated
// linearly in time between the records around it, else the nearest record (frame.particles_note).
void DisksFromRecords(const ParticleHistory& h, ResultsFrame& frame) {
  const std::size_t np = h.particles;
  std::size_t a = h.records, b = h.records;  // the records at or before, and after, the snapshot
  for (std::size_t r = 0; r < h.records; ++r) {
    if (h.step[r] == frame.step) a = b = r;
    if (a == r) break;
    if (h.time[r] <= frame.time) a = r;
    if (h.time[r] > frame.time && b == h.records) b = r;
  }
  double w = 0.0;
  if (a == b) {
    frame.particles_time = h.time[a];
  } else if (a < h.records && b < h.records) {
    w = (frame.time - h.time[a]) / (h.time[b] - h.time[a]);
    frame.particles_time = frame.time;
    frame.particles_note =
        "particles interpolated linearly between the records at t = " + FormatLabel(h.time[a]) +
        " and t = " + FormatLabel(h.time[b]) + " (a snapshot of results format 1 holds none)";
  } else {
    a = b = a < h.records ? a : b;
    frame.particles_time = h.time[a];
    frame.particles_note = "particles from the nearest record, at t = " + FormatLabel(h.time[a]) +
                           " (a snapshot of results format 1 holds none)";
  }
  const std::vector<double> angle_a = RecordAngles(h, a);
  const std::vector<double> angle_b = RecordAngles(h, b);
  for (std::size_t k = 0; k < np; ++k) {
    const std::size_t pa = (a * np + k) * 2, pb = (b * np + k) * 2;
    frame.disks.push_back({h.position[pa] + w * (h.position[pb] - h.position[pa]),
                           h.position[pa + 1] + w * (h.position[pb + 1] - h.position[pa + 1]),
                           h.radius[k], angle_a[k] + w * (angle_b[k] - angle_a[k]), true});
    SetEllipse(h, k, frame.disks.back());
  }
}

}  // namespace

ResultsFrame LoadResultsFrame(const std::string& results_dir, long step,
                              const std::string& quantity) {
  const std::vector<std::string>& known = PictureQuantities();
  if (!quantity.empty() && std::find(known.begin(), known.end(), quantity) == known.end()) {
    throw InvalidParameter("quantity", quantity, PictureQuantityList());
  }
  const std::vector<long> steps = SnapshotSteps(results_dir);
  if (steps.empty()) {
    throw InvalidParameter(
        "results directory", results_dir,
        "a directory with field snapshots in fields/snap_NNNNNN.h5 (output.fields_every > 0)");
  }
  if (step >= 0 && !std::binary_search(steps.begin(), steps.end(), step)) {
    throw InvalidParameter("snapshot", std::to_string(step),
                           "one of the snapshot steps: " + ListSteps(steps));
  }
  const long chosen = step >= 0 ? step : steps.back();
  ResultsFrame frame;
  frame.snapshot_path = (fs::path(results_dir) / "fields" / SnapshotFileName(chosen)).string();
  FieldSnapshot snapshot = ReadFieldSnapshot(frame.snapshot_path);
  frame.time = snapshot.time;
  frame.step = snapshot.step;

  const bool has_tra = snapshot.fields.count("trA") > 0;
  const std::string wanted = quantity.empty() ? (has_tra ? "trA" : "speed") : quantity;
  std::string held;
  for (const auto& [name, array] : snapshot.fields) held += (held.empty() ? "" : ", ") + name;
  for (const std::string& dataset : DatasetsOf(wanted)) {
    if (snapshot.fields.count(dataset) == 0) {
      throw InvalidParameter(
          "quantity", wanted,
          "a quantity of the datasets " + frame.snapshot_path + " holds (" + held + "; /" +
              dataset + " is missing" +
              (dataset == "trA" || dataset[0] == 'A' ? ": a Newtonian run)" : ")"));
    }
  }
  const FieldArray& reference = snapshot.fields.at(DatasetsOf(wanted).front());
  if (reference.shape.size() != 2 || reference.shape[0] < 2 || reference.shape[1] < 2) {
    throw Error(frame.snapshot_path + ": the node fields are not 2-D arrays of at least 2x2 nodes");
  }
  const Grid grid{int(reference.shape[1]) - 1, int(reference.shape[0]) - 1, snapshot.h, snapshot.x0,
                  snapshot.y0};
  // The pressure lives on the 2h mesh (design.md 3.2).
  frame.field.grid = wanted == "pressure"
                         ? Grid{grid.nx, grid.ny, 2.0 * snapshot.h, snapshot.x0, snapshot.y0}
                         : grid;
  frame.field.quantity = wanted;
  const auto values = [&](const char* name) { return snapshot.fields.at(name).values; };
  if (wanted == "speed") {
    frame.field.values = NodeSpeed(values("u"), values("v"));
  } else if (wanted == "vorticity") {
    if (grid.nx < 2 || grid.ny < 2)
      throw Error(frame.snapshot_path + ": too few nodes for the vorticity");
    frame.field.values = NodeVorticity(grid, values("u"), values("v"));
  } else if (wanted == "pressure") {
    frame.field.values = values("p");
  } else if (wanted == "A11" || wanted == "A12" || wanted == "A22") {
    frame.field.values = values(wanted.c_str());
  } else {
    frame.field.values = values("trA");
    for (double& t : frame.field.values) {
      if (wanted == "trA-2") t -= 2.0;
      if (wanted == "log10(trA/2)") t = t > 0.0 ? std::log10(0.5 * t) : std::nan("");
    }
  }
  if (snapshot.fields.count("u") > 0 && snapshot.fields.count("v") > 0) {
    const FieldArray& u = snapshot.fields.at("u");
    const Grid velocity_grid =
        u.shape.size() == 2 && u.shape[0] >= 2 && u.shape[1] >= 2
            ? Grid{int(u.shape[1]) - 1, int(u.shape[0]) - 1, snapshot.h, snapshot.x0, snapshot.y0}
            : Grid{};
    if (velocity_grid.nx > 0 && u.values.size() == velocity_grid.NodeCount() &&
        snapshot.fields.at("v").values.size() == velocity_grid.NodeCount()) {
      frame.velocity.u = NodeField{velocity_grid, values("u"), "u"};
      frame.velocity.v = NodeField{velocity_grid, values("v"), "v"};
      frame.has_velocity = true;
    }
  }

  frame.particles_time = frame.time;
  if (snapshot.has_particles) {
    const SnapshotParticles& q = snapshot.particles;
    const std::vector<double> angles =
        q.angle.empty() ? AnglesAt(results_dir, frame.time, q.Count()) : q.angle;
    for (std::size_t k = 0; k < q.Count(); ++k) {
      frame.disks.push_back({q.position[2 * k], q.position[2 * k + 1], q.radius[k],
                             angles.empty() ? 0.0 : angles[k], !angles.empty()});
      if (q.semi_axes.size() == 3 * q.Count() && q.semi_axes[3 * k] != q.semi_axes[3 * k + 1]) {
        frame.disks.back().semi_a = q.semi_axes[3 * k];
        frame.disks.back().semi_b = q.semi_axes[3 * k + 1];
      }
    }
    return frame;
  }
  const fs::path particles = fs::path(results_dir) / "particles.h5";
  std::error_code ec;
  if (fs::exists(particles, ec)) {
    const ParticleHistory history = ReadParticleHistory(particles.string());
    if (history.records > 0 && history.particles > 0) DisksFromRecords(history, frame);
  }
  return frame;
}

std::string SceneTitle(const std::string& results_dir) {
  const fs::path scene = fs::path(results_dir) / "scene.toml";
  std::error_code ec;
  if (!fs::is_regular_file(scene, ec)) return "";
  // The writer of the scene as run puts `title = "..."` on a line of its own (scene_writer.cc).
  std::istringstream lines(ReadTextFile(scene.string()));
  const std::string key = "title = \"";
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(key, 0) != 0) continue;
    const std::size_t close = line.rfind('"');
    return close > key.size() ? line.substr(key.size(), close - key.size()) : "";
  }
  return "";
}

}  // namespace dlmfd
