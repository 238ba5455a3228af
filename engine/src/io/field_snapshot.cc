#include "dlmfd/io/field_snapshot.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "dlmfd/core/errors.h"
#include "dlmfd/io/atomic_file.h"
#include "hdf5_file.h"
#include "results_attributes.h"

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

// The node coordinates x0 + i h (i = 0..n).
std::vector<double> Coordinates(double origin, double h, int cells) {
  std::vector<double> c(std::size_t(cells) + 1);
  for (int i = 0; i <= cells; ++i) c[std::size_t(i)] = origin + i * h;
  return c;
}

void WriteCoordinates(hid_t file, const Grid& grid, const std::string& suffix) {
  const std::vector<double> x = Coordinates(grid.x0, grid.h, grid.nx);
  const std::vector<double> y = Coordinates(grid.y0, grid.h, grid.ny);
  h5::WriteDoubles(file, "x" + suffix, {x.size()}, x.data());
  h5::WriteDoubles(file, "y" + suffix, {y.size()}, y.data());
  h5::Describe(file, "x" + suffix, ResultsFile::kSnapshot, "x" + suffix, "x" + suffix);
  h5::Describe(file, "y" + suffix, ResultsFile::kSnapshot, "y" + suffix, "y" + suffix);
}

// The group /particles: every particle's state at the snapshot's step.
void WriteParticles(hid_t file, const FlowState& state, const std::vector<double>& angles) {
  h5::Handle group = h5::CreateGroup(file, "particles");
  const hid_t g = group.get();
  const hsize_t np = state.particles.size();
  std::vector<std::int64_t> id;
  std::vector<double> radius, position, velocity, omega, force, torque, position3, velocity3;
  std::vector<double> semi_axes;  // (a, b, 0): the ellipse's glyph scale in ParaView
  for (const ParticleState& q : state.particles) {
    position3.insert(position3.end(), {q.position.x(), q.position.y(), 0.0});
    velocity3.insert(velocity3.end(), {q.velocity.x(), q.velocity.y(), 0.0});
    id.push_back(q.id);
    radius.push_back(q.radius);
    position.insert(position.end(), {q.position.x(), q.position.y()});
    velocity.insert(velocity.end(), {q.velocity.x(), q.velocity.y()});
    omega.push_back(q.angular_velocity);
    force.insert(force.end(), {q.force.x(), q.force.y()});
    torque.push_back(q.torque);
    const bool disk = q.shape == ShapeKind::kDisk;
    semi_axes.insert(semi_axes.end(),
                     {disk ? q.radius : q.semi_axes.x(), disk ? q.radius : q.semi_axes.y(), 0.0});
  }
  h5::WriteInts(g, "id", {np}, id.data());
  h5::WriteDoubles(g, "radius", {np}, radius.data());
  h5::WriteDoubles(g, "position", {np, 2}, position.data());
  h5::WriteDoubles(g, "velocity", {np, 2}, velocity.data());
  h5::WriteDoubles(g, "angular_velocity", {np}, omega.data());
  h5::WriteDoubles(g, "force", {np, 2}, force.data());
  h5::WriteDoubles(g, "torque", {np}, torque.data());
  h5::WriteDoubles(g, "position_xyz", {np, 3}, position3.data());
  h5::WriteDoubles(g, "velocity_xyz", {np, 3}, velocity3.data());
  h5::WriteDoubles(g, "semi_axes", {np, 3}, semi_axes.data());
  std::vector<std::string> names = {
      "id",    "radius", "position",     "velocity",     "angular_velocity",
      "force", "torque", "position_xyz", "velocity_xyz", "semi_axes"};
  if (angles.size() == np) {
    h5::WriteDoubles(g, "angle", {np}, angles.data());
    names.push_back("angle");
  }
  for (const std::string& name : names) {
    const bool vector = name == "position" || name == "velocity" || name == "force" ||
                        name == "semi_axes" || name.find("_xyz") != std::string::npos;
    h5::Describe(g, name, ResultsFile::kSnapshot, "particles/" + name,
                 vector ? "particle component" : "particle");
  }
}

std::vector<double> ReadOptional(hid_t loc, const char* name) {
  return h5::Exists(loc, name) ? h5::ReadDoubles(loc, name) : std::vector<double>{};
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

void WriteFieldSnapshot(const std::string& path, const Grid& grid, const FlowState& state,
                        const SnapshotExtras& extras) {
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
    h5::WriteFormat(file.get(), kSnapshotFormat, extras.scene_text);
    WriteCoordinates(file.get(), grid, "");
    WriteCoordinates(file.get(), coarse, "_pressure");
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
    for (const char* name : {"u", "v", "trA", "A11", "A12", "A22"}) {
      if (h5::Exists(file.get(), name))
        h5::Describe(file.get(), name, ResultsFile::kSnapshot, name, "y x");
    }
    h5::Describe(file.get(), "velocity", ResultsFile::kSnapshot, "velocity", "y x component");
    h5::Describe(file.get(), "p", ResultsFile::kSnapshot, "p", "y_pressure x_pressure");
    WriteParticles(file.get(), state, extras.particle_angles);
  }
  CommitTemporary(temporary, path);
}

FieldSnapshot ReadFieldSnapshot(const std::string& path) {
  h5::Handle file = h5::OpenFile(path, false);
  FieldSnapshot s;
  s.format_version = h5::ReadFormatVersion(file.get(), path);
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
  if (h5::Exists(file.get(), "scene")) s.scene_text = h5::ReadText(file.get(), "scene");
  if (h5::Exists(file.get(), "particles")) {
    h5::Handle group = h5::OpenObject(file.get(), "particles");
    const hid_t g = group.get();
    SnapshotParticles& q = s.particles;
    q.id = h5::ReadInts(g, "id");
    q.radius = h5::ReadDoubles(g, "radius");
    q.position = h5::ReadDoubles(g, "position");
    q.velocity = h5::ReadDoubles(g, "velocity");
    q.angular_velocity = h5::ReadDoubles(g, "angular_velocity");
    q.force = h5::ReadDoubles(g, "force");
    q.torque = h5::ReadDoubles(g, "torque");
    q.angle = ReadOptional(g, "angle");
    q.semi_axes = ReadOptional(g, "semi_axes");
    const std::size_t np = q.id.size();
    if (q.radius.size() != np || q.position.size() != 2 * np || q.velocity.size() != 2 * np ||
        q.angular_velocity.size() != np || (!q.angle.empty() && q.angle.size() != np) ||
        (!q.semi_axes.empty() && q.semi_axes.size() != 3 * np)) {
      throw Error(path + ": the datasets of /particles disagree on the number of particles");
    }
    s.has_particles = true;
  }
  return s;
}

}  // namespace dlmfd
