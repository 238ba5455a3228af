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
        double angle = 0.0;
        for (std::size_t r = 1; r <= best; ++r) {
          angle += 0.5 * (history.time[r] - history.time[r - 1]) *
                   (history.angular_velocity[r * history.particles + k] +
                    history.angular_velocity[(r - 1) * history.particles + k]);
        }
        frame.disks.push_back(
            {history.position[at], history.position[at + 1], history.radius[k], angle, true});
      }
    }
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
