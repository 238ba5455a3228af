// LoadResultsFrame: snapshot + particle record of a results directory, read with the results
// readers (dlmfd_results).
#include "dlmfd/viz/results_frame.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "dlmfd/core/errors.h"
#include "dlmfd/io/field_snapshot.h"
#include "dlmfd/io/particle_history.h"

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

}  // namespace

std::vector<double> NodeSpeed(const std::vector<double>& u, const std::vector<double>& v) {
  std::vector<double> speed(std::min(u.size(), v.size()));
  for (std::size_t k = 0; k < speed.size(); ++k) speed[k] = std::hypot(u[k], v[k]);
  return speed;
}

ResultsFrame LoadResultsFrame(const std::string& results_dir, long step,
                              const std::string& quantity) {
  if (!quantity.empty() && quantity != "trA" && quantity != "speed") {
    throw InvalidParameter("quantity", quantity, "trA or speed");
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
  if (wanted == "trA" && !has_tra) {
    throw InvalidParameter("quantity", "trA",
                           "speed: " + frame.snapshot_path + " has no trA (a Newtonian run)");
  }
  const FieldArray& reference = snapshot.fields.at(wanted == "trA" ? "trA" : "u");
  if (reference.shape.size() != 2 || reference.shape[0] < 2 || reference.shape[1] < 2) {
    throw Error(frame.snapshot_path + ": the node fields are not 2-D arrays of at least 2x2 nodes");
  }
  frame.field.grid = Grid{int(reference.shape[1]) - 1, int(reference.shape[0]) - 1, snapshot.h,
                          snapshot.x0, snapshot.y0};
  frame.field.quantity = wanted;
  if (wanted == "trA") {
    frame.field.values = std::move(snapshot.fields.at("trA").values);
  } else {
    if (snapshot.fields.count("v") == 0) throw Error(frame.snapshot_path + ": no /v dataset");
    frame.field.values = NodeSpeed(snapshot.fields.at("u").values, snapshot.fields.at("v").values);
  }

  frame.particles_time = frame.time;
  const fs::path particles = fs::path(results_dir) / "particles.h5";
  std::error_code ec;
  if (fs::exists(particles, ec)) {
    const ParticleHistory history = ReadParticleHistory(particles.string());
    if (history.records > 0 && history.particles > 0) {
      std::size_t best = 0;
      for (std::size_t r = 0; r < history.records; ++r) {
        if (history.step[r] == frame.step) {
          best = r;
          break;
        }
        if (std::abs(history.time[r] - frame.time) < std::abs(history.time[best] - frame.time))
          best = r;
      }
      frame.particles_time = history.time[best];
      for (std::size_t k = 0; k < history.particles; ++k) {
        const std::size_t at = (best * history.particles + k) * 2;
        frame.disks.push_back({history.position[at], history.position[at + 1], history.radius[k]});
      }
    }
  }
  return frame;
}

}  // namespace dlmfd
