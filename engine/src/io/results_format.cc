// The meanings of the results datasets and the unit names of their dimensions.
#include "dlmfd/io/results_format.h"

#include <cstdlib>
#include <map>
#include <sstream>

#include "dlmfd/core/errors.h"
#include "results_attributes.h"

namespace dlmfd {
namespace {

using MeaningTable = std::map<std::string, DatasetMeaning>;

const MeaningTable& SnapshotMeanings() {
  static const MeaningTable table = {
      {"scene", {"1", "the scene as run (TOML, every default filled in), as scene.toml"}},
      // Snapshots: the meshes' node coordinates.
      {"x", {"L", "x of the velocity-mesh nodes: column i of every node field is at x[i]"}},
      {"y", {"L", "y of the velocity-mesh nodes: row j of every node field is at y[j]"}},
      {"x_pressure", {"L", "x of the pressure-mesh (2h) nodes: column i of p is at x_pressure[i]"}},
      {"y_pressure", {"L", "y of the pressure-mesh (2h) nodes: row j of p is at y_pressure[j]"}},
      // Snapshots: the fields.
      {"u", {"L T-1", "x component of the fluid velocity at the nodes (P1 on the h mesh)"}},
      {"v", {"L T-1", "y component of the fluid velocity at the nodes (P1 on the h mesh)"}},
      {"velocity",
       {"L T-1", "the fluid velocity (u, v, 0) at the nodes, the vector ParaView reads"}},
      {"p", {"M L-1 T-2", "pressure p of the paper's (1) at the nodes of the 2h mesh"}},
      {"trA", {"1", "trace of the conformation tensor A (2 at rest)"}},
      {"A11", {"1", "conformation tensor component A_xx (1 at rest)"}},
      {"A12", {"1", "conformation tensor component A_xy (0 at rest)"}},
      {"A22", {"1", "conformation tensor component A_yy (1 at rest)"}},
      // Snapshots: the particles at the snapshot's own step.
      {"particles/id",
       {"1", "particle id, as in particles.h5 and the scene's [[particles]] order"}},
      {"particles/radius", {"L", "particle radius"}},
      {"particles/position", {"L", "particle centre (x, y) at the snapshot's step"}},
      {"particles/velocity", {"L T-1", "particle velocity (u, v) at the snapshot's step"}},
      {"particles/position_xyz",
       {"L", "particle centre (x, y, 0): the points of fields.xmf's particle grid in ParaView"}},
      {"particles/velocity_xyz",
       {"L T-1", "particle velocity (u, v, 0): the vector of fields.xmf's particle grid"}},
      {"particles/angular_velocity", {"T-1", "particle angular velocity, counter-clockwise"}},
      {"particles/semi_axes",
       {"L",
        "particle semi-axes (a, b, 0) along its body's x and y axes, (R, R, 0) for a disk: "
        "the scale of an ellipse glyph turned by angle in ParaView"}},
      {"particles/angle",
       {"rad",
        "particle orientation, counter-clockwise: the scene's angle plus the angular velocity "
        "integrated step by step (trapezoidal rule, as the corrector (38) moves the centre)"}},
      {"particles/force",
       {"M T-2", "force of the fluid on the particle over the last step, per unit length"}},
      {"particles/torque",
       {"M L T-2", "torque of the fluid on the particle over the last step, per unit length"}},
  };
  return table;
}

const MeaningTable& ParticleMeanings() {
  static const MeaningTable table = {
      {"scene", {"1", "the scene as run (TOML, every default filled in), as scene.toml"}},
      {"time", {"T", "simulated time of each record"}},
      {"step", {"1", "time step of each record"}},
      {"id", {"1", "particle id, as in the scene's [[particles]] order"}},
      {"radius",
       {"L",
        "particle radius: a disk's, an ellipse's bounding radius max(a, b) (its longer "
        "semi-axis)"}},
      {"shape", {"1", "particle shape: 0 disk, 1 ellipse (the scene's particles.shape)"}},
      {"semi_axes",
       {"L",
        "particle semi-axes (a, b) along its body's x and y axes, (R, R) for a disk; the "
        "body's x axis is turned by angle from the domain's"}},
      {"position", {"L", "particle centre (x, y) at each record"}},
      {"velocity", {"L T-1", "particle velocity (u, v) at each record"}},
      {"angular_velocity", {"T-1", "particle angular velocity at each record, counter-clockwise"}},
      {"angle",
       {"rad",
        "particle orientation at each record, counter-clockwise: the scene's angle plus the "
        "angular velocity integrated step by step (trapezoidal rule, as the corrector (38) "
        "moves the centre)"}},
      {"force",
       {"M T-2", "force of the fluid on the particle over the last step, per unit length"}},
      {"torque",
       {"M L T-2", "torque of the fluid on the particle over the last step, per unit length"}},
  };
  return table;
}

}  // namespace

const DatasetMeaning* MeaningOfDataset(ResultsFile file, const std::string& name) {
  const MeaningTable& table =
      file == ResultsFile::kSnapshot ? SnapshotMeanings() : ParticleMeanings();
  const auto it = table.find(name);
  return it == table.end() ? nullptr : &it->second;
}

void CheckFormatVersion(const std::string& path, std::int64_t version) {
  if (version > kResultsFormatVersion) {
    throw Error(path + " is of results format version " + std::to_string(version) +
                "; this build reads versions 1 to " + std::to_string(kResultsFormatVersion) +
                " (a newer dlmfd wrote it)");
  }
}

std::string UnitsIn(const std::string& dimensions, const std::string& system) {
  if (system.empty() || system == "none") return dimensions;
  if (system != "cgs" && system != "si") {
    throw InvalidParameter("units", system, "cgs, si or none");
  }
  if (dimensions == "1") return "";
  if (dimensions == "rad") return "rad";
  const bool cgs = system == "cgs";
  std::istringstream words(dimensions);
  std::string text;
  for (std::string word; words >> word;) {
    const char symbol = word[0];
    const std::string power = word.substr(1);
    const char* name = symbol == 'L'   ? (cgs ? "cm" : "m")
                       : symbol == 'M' ? (cgs ? "g" : "kg")
                       : symbol == 'T' ? "s"
                                       : nullptr;
    if (name == nullptr) return dimensions;  // not a dimension formula: as it is
    text += (text.empty() ? "" : " ") + std::string(name) + power;
  }
  return text;
}

}  // namespace dlmfd

namespace dlmfd {
namespace h5 {

void WriteFormat(hid_t file, const char* format, const std::string& scene_text) {
  WriteAttribute(file, "format", std::string(format));
  WriteAttribute(file, "format_version", kResultsFormatVersion);
  WriteAttribute(file, "units", std::string(kUnitsNote));
  if (!scene_text.empty()) {
    WriteText(file, "scene", scene_text);
    Describe(file, "scene", ResultsFile::kSnapshot, "scene", "");
  }
}

std::int64_t ReadFormatVersion(hid_t file, const std::string& path) {
  const std::int64_t version =
      HasAttribute(file, "format_version") ? ReadIntAttribute(file, "format_version") : 1;
  CheckFormatVersion(path, version);
  return version;
}

void Describe(hid_t loc, const std::string& name, ResultsFile kind, const std::string& meaning,
              const std::string& dimensions) {
  const DatasetMeaning* m = MeaningOfDataset(kind, meaning);
  if (m == nullptr) throw Error("results format: no meaning recorded for the dataset " + meaning);
  Handle object = OpenObject(loc, name);
  WriteAttribute(object.get(), "units", std::string(m->units));
  WriteAttribute(object.get(), "description", std::string(m->description));
  if (!dimensions.empty()) WriteAttribute(object.get(), "dimensions", dimensions);
}

}  // namespace h5
}  // namespace dlmfd
