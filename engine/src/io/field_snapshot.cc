#include "dlmfd/io/field_snapshot.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "dlmfd/core/errors.h"
#include "dlmfd/io/atomic_file.h"
#include "hdf5_file.h"

namespace dlmfd {
namespace {

namespace fs = std::filesystem;

// The step of "snap_000123.h5", or -1 for any other name.
long StepOfSnapshotName(const std::string& name) {
  const std::string prefix = "snap_";
  const std::string suffix = ".h5";
  if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return -1;
  }
  const std::string digits =
      name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.empty() ||
      !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return -1;
  }
  return std::stol(digits);
}

// /velocity: (u, v, 0) per node, shape (ny+1, nx+1, 3), the vector fields.xmf hands to ParaView
// (its XDMF readers take a vector attribute only with 3 components and evaluate no JOIN).
void WriteVelocityVector(hid_t file, const Grid& grid, const FlowState& state) {
  std::vector<double> velocity(3 * grid.NodeCount(), 0.0);
  for (std::size_t k = 0; k < grid.NodeCount(); ++k) {
    velocity[3 * k] = state.u[k];
    velocity[3 * k + 1] = state.v[k];
  }
  const std::vector<hsize_t> shape = {hsize_t(grid.NodesY()), hsize_t(grid.NodesX()), 3};
  h5::WriteDoubles(file, "velocity", shape, velocity.data());
}

}  // namespace

std::string SnapshotFileName(long step) {
  char name[40];
  std::snprintf(name, sizeof name, "snap_%06ld.h5", step);
  return name;
}

std::vector<long> SnapshotSteps(const std::string& results_dir) {
  std::vector<long> steps;
  std::error_code ec;
  const fs::path fields = fs::path(results_dir) / "fields";
  if (!fs::is_directory(fields, ec)) return steps;
  for (const auto& entry : fs::directory_iterator(fields, ec)) {
    const long step = StepOfSnapshotName(entry.path().filename().string());
    if (step >= 0 && entry.is_regular_file(ec)) steps.push_back(step);
  }
  std::sort(steps.begin(), steps.end());
  return steps;
}

void WriteFieldSnapshot(const std::string& path, const Grid& grid, const FlowState& state) {
  const std::vector<hsize_t> nodes = {hsize_t(grid.NodesY()), hsize_t(grid.NodesX())};
  const Grid coarse = grid.Coarse();
  const std::vector<hsize_t> pressure_nodes = {hsize_t(coarse.NodesY()), hsize_t(coarse.NodesX())};
  if (state.u.size() != grid.NodeCount() || state.v.size() != grid.NodeCount() ||
      state.p.size() != coarse.NodeCount()) {
    throw Error("field snapshot: the state's arrays do not match the grid");
  }
  const std::string temporary = TemporaryPath(path);
  {
    h5::Handle file = h5::CreateFile(temporary);
    h5::WriteAttribute(file.get(), "time", state.time);
    h5::WriteAttribute(file.get(), "step", static_cast<std::int64_t>(state.step));
    h5::WriteAttribute(file.get(), "h", grid.h);
    h5::WriteAttribute(file.get(), "x0", grid.x0);
    h5::WriteAttribute(file.get(), "y0", grid.y0);
    h5::WriteDoubles(file.get(), "u", nodes, state.u.data());
    h5::WriteDoubles(file.get(), "v", nodes, state.v.data());
    WriteVelocityVector(file.get(), grid, state);
    h5::WriteDoubles(file.get(), "p", pressure_nodes, state.p.data());
    if (!state.a11.empty()) {
      std::vector<double> trace(grid.NodeCount());
      for (std::size_t k = 0; k < trace.size(); ++k) trace[k] = state.a11[k] + state.a22[k];
      h5::WriteDoubles(file.get(), "trA", nodes, trace.data());
      h5::WriteDoubles(file.get(), "A11", nodes, state.a11.data());
      h5::WriteDoubles(file.get(), "A12", nodes, state.a12.data());
      h5::WriteDoubles(file.get(), "A22", nodes, state.a22.data());
    }
  }
  CommitTemporary(temporary, path);
}

FieldSnapshot ReadFieldSnapshot(const std::string& path) {
  h5::Handle file = h5::OpenFile(path, false);
  FieldSnapshot s;
  s.time = h5::ReadDoubleAttribute(file.get(), "time");
  s.step = h5::ReadIntAttribute(file.get(), "step");
  s.h = h5::ReadDoubleAttribute(file.get(), "h");
  s.x0 = h5::ReadDoubleAttribute(file.get(), "x0");
  s.y0 = h5::ReadDoubleAttribute(file.get(), "y0");
  for (const char* name : {"u", "v", "velocity", "p", "trA", "A11", "A12", "A22"}) {
    if (!h5::Exists(file.get(), name)) continue;
    std::vector<hsize_t> dims;
    FieldArray a;
    a.values = h5::ReadDoubles(file.get(), name, &dims);
    a.shape.assign(dims.begin(), dims.end());
    s.fields[name] = std::move(a);
  }
  return s;
}

}  // namespace dlmfd
