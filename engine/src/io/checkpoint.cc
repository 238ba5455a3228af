#include "dlmfd/io/checkpoint.h"

#include "dlmfd/core/errors.h"
#include "dlmfd/io/atomic_file.h"
#include "hdf5_file.h"

namespace dlmfd {
namespace {

void WriteField(hid_t f, const char* name, const std::vector<double>& values) {
  h5::WriteDoubles(f, name, {values.size()}, values.data());
}

std::vector<double> ReadField(hid_t f, const char* name) { return h5::ReadDoubles(f, name); }

// Vectors of one length as the rows of a (count, length) dataset.
void WriteRows(hid_t g, const char* name, const std::vector<Eigen::VectorXd>& rows) {
  const auto length = static_cast<hsize_t>(rows.front().size());
  std::vector<double> flat;
  flat.reserve(rows.size() * length);
  for (const Eigen::VectorXd& row : rows) flat.insert(flat.end(), row.begin(), row.end());
  h5::WriteDoubles(g, name, {rows.size(), length}, flat.data());
}

std::vector<Eigen::VectorXd> ReadRows(hid_t g, const char* name, const std::string& path) {
  std::vector<hsize_t> dims;
  const std::vector<double> flat = h5::ReadDoubles(g, name, &dims);
  if (dims.size() != 2) {
    throw Error("checkpoint " + path + ": /cut_cell_start/" + name + " is not (count, length)");
  }
  std::vector<Eigen::VectorXd> rows;
  const auto length = static_cast<Eigen::Index>(dims[1]);
  for (hsize_t i = 0; i < dims[0]; ++i)
    rows.emplace_back(Eigen::Map<const Eigen::VectorXd>(flat.data() + i * dims[1], length));
  return rows;
}

void WriteCutCellStart(hid_t f, const CutCellStart& start) {
  const PressureCorrections& c = start.corrections;
  if (start.previous_pressure.empty() && c.q.empty()) return;
  const h5::Handle group = h5::CreateGroup(f, "cut_cell_start");
  const hid_t g = group.get();
  if (!start.previous_pressure.empty()) WriteField(g, "previous_pressure", start.previous_pressure);
  if (c.q.empty()) return;
  h5::WriteAttribute(g, "corrections_dt", start.corrections_dt);
  WriteRows(g, "q", c.q);
  WriteRows(g, "sq", c.sq);
  WriteRows(g, "wq", c.wq);
}

CutCellStart ReadCutCellStart(hid_t f, const std::string& path) {
  CutCellStart start;
  if (!h5::Exists(f, "cut_cell_start")) return start;
  const h5::Handle group = h5::OpenObject(f, "cut_cell_start");
  const hid_t g = group.get();
  if (h5::Exists(g, "previous_pressure"))
    start.previous_pressure = ReadField(g, "previous_pressure");
  if (!h5::Exists(g, "q")) return start;
  start.corrections_dt = h5::ReadDoubleAttribute(g, "corrections_dt");
  PressureCorrections& c = start.corrections;
  c.q = ReadRows(g, "q", path);
  c.sq = ReadRows(g, "sq", path);
  c.wq = ReadRows(g, "wq", path);
  if (c.sq.size() != c.q.size() || c.wq.size() != c.q.size())
    throw Error("checkpoint " + path + ": inconsistent /cut_cell_start arrays");
  return start;
}

}  // namespace

void WriteCheckpoint(const std::string& path, const FlowState& state, const std::string& scene_text,
                     const std::vector<double>& particle_angles) {
  const std::string temporary = TemporaryPath(path);
  {
    h5::Handle file = h5::CreateFile(temporary);
    const hid_t f = file.get();
    h5::WriteAttribute(f, "step", static_cast<std::int64_t>(state.step));
    h5::WriteAttribute(f, "time", state.time);
    h5::WriteAttribute(f, "scene", scene_text);
    h5::WriteAttribute(f, "newtonian", static_cast<std::int64_t>(state.a11.empty() ? 1 : 0));
    WriteField(f, "u", state.u);
    WriteField(f, "v", state.v);
    WriteField(f, "p", state.p);
    if (!state.a11.empty()) {
      WriteField(f, "a11", state.a11);
      WriteField(f, "a12", state.a12);
      WriteField(f, "a22", state.a22);
    }
    if (!state.d11.empty()) {  // fluid.stress_splitting = devss
      WriteField(f, "d11", state.d11);
      WriteField(f, "d12", state.d12);
      WriteField(f, "d22", state.d22);
    }
    if (!state.stokes_defect.empty()) WriteField(f, "stokes_defect", state.stokes_defect);
    WriteCutCellStart(f, state.cut_cell_start);
    h5::Handle group(h5::CheckId(H5Gcreate2(f, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                                 "create group"),
                     H5Gclose);
    const hid_t g = group.get();
    const hsize_t np = state.particles.size();
    std::vector<std::int64_t> id, motion, offset(1, 0);
    std::vector<double> position, velocity, omega, force, torque, radius, density, multiplier;
    for (const ParticleState& q : state.particles) {
      id.push_back(q.id);
      motion.push_back(static_cast<std::int64_t>(q.motion));
      position.insert(position.end(), {q.position.x(), q.position.y()});
      velocity.insert(velocity.end(), {q.velocity.x(), q.velocity.y()});
      force.insert(force.end(), {q.force.x(), q.force.y()});
      omega.push_back(q.angular_velocity);
      torque.push_back(q.torque);
      radius.push_back(q.radius);
      density.push_back(q.density);
      multiplier.insert(multiplier.end(), q.multiplier.begin(), q.multiplier.end());
      offset.push_back(static_cast<std::int64_t>(multiplier.size()));
    }
    h5::WriteInts(g, "id", {np}, id.data());
    h5::WriteInts(g, "motion", {np}, motion.data());
    h5::WriteDoubles(g, "position", {np, 2}, position.data());
    h5::WriteDoubles(g, "velocity", {np, 2}, velocity.data());
    h5::WriteDoubles(g, "angular_velocity", {np}, omega.data());
    h5::WriteDoubles(g, "force", {np, 2}, force.data());
    h5::WriteDoubles(g, "torque", {np}, torque.data());
    h5::WriteDoubles(g, "radius", {np}, radius.data());
    h5::WriteDoubles(g, "density", {np}, density.data());
    h5::WriteDoubles(g, "multiplier", {multiplier.size()}, multiplier.data());
    h5::WriteInts(g, "multiplier_offset", {np + 1}, offset.data());
    if (particle_angles.size() == np && np > 0)
      h5::WriteDoubles(g, "angle", {np}, particle_angles.data());
    h5::Check(H5Fflush(f, H5F_SCOPE_LOCAL), "flush " + temporary);
  }
  CommitTemporary(temporary, path);
}

Checkpoint ReadCheckpoint(const std::string& path) {
  h5::Handle file = h5::OpenFile(path, false);
  const hid_t f = file.get();
  Checkpoint c;
  FlowState& s = c.state;
  s.step = static_cast<long>(h5::ReadIntAttribute(f, "step"));
  s.time = h5::ReadDoubleAttribute(f, "time");
  c.scene_text = h5::ReadStringAttribute(f, "scene");
  s.u = ReadField(f, "u");
  s.v = ReadField(f, "v");
  s.p = ReadField(f, "p");
  if (h5::ReadIntAttribute(f, "newtonian") == 0) {
    s.a11 = ReadField(f, "a11");
    s.a12 = ReadField(f, "a12");
    s.a22 = ReadField(f, "a22");
  }
  if (H5Lexists(f, "d11", H5P_DEFAULT) > 0) {
    s.d11 = ReadField(f, "d11");
    s.d12 = ReadField(f, "d12");
    s.d22 = ReadField(f, "d22");
  }
  if (H5Lexists(f, "stokes_defect", H5P_DEFAULT) > 0)
    s.stokes_defect = ReadField(f, "stokes_defect");
  s.cut_cell_start = ReadCutCellStart(f, path);
  h5::Handle group(
      h5::CheckId(H5Gopen2(f, "particles", H5P_DEFAULT), "open " + path + ":/particles"), H5Gclose);
  const hid_t g = group.get();
  const auto id = h5::ReadInts(g, "id");
  const auto motion = h5::ReadInts(g, "motion");
  const auto position = h5::ReadDoubles(g, "position");
  const auto velocity = h5::ReadDoubles(g, "velocity");
  const auto omega = h5::ReadDoubles(g, "angular_velocity");
  const auto force = h5::ReadDoubles(g, "force");
  const auto torque = h5::ReadDoubles(g, "torque");
  const auto radius = h5::ReadDoubles(g, "radius");
  const auto density = h5::ReadDoubles(g, "density");
  const auto multiplier = h5::ReadDoubles(g, "multiplier");
  const auto offset = h5::ReadInts(g, "multiplier_offset");
  const std::size_t np = id.size();
  if (h5::Exists(g, "angle")) c.particle_angles = h5::ReadDoubles(g, "angle");
  if (offset.size() != np + 1 || position.size() != 2 * np ||
      static_cast<std::size_t>(offset.back()) != multiplier.size() ||
      (!c.particle_angles.empty() && c.particle_angles.size() != np)) {
    throw Error("checkpoint " + path + ": inconsistent particle arrays");
  }
  for (std::size_t i = 0; i < np; ++i) {
    ParticleState q;
    q.id = static_cast<int>(id[i]);
    q.motion = static_cast<Motion>(motion[i]);
    q.position = Vec2(position[2 * i], position[2 * i + 1]);
    q.velocity = Vec2(velocity[2 * i], velocity[2 * i + 1]);
    q.force = Vec2(force[2 * i], force[2 * i + 1]);
    q.angular_velocity = omega[i];
    q.torque = torque[i];
    q.radius = radius[i];
    q.density = density[i];
    if (!c.particle_angles.empty()) q.angle = c.particle_angles[i];
    q.multiplier.assign(multiplier.begin() + offset[i], multiplier.begin() + offset[i + 1]);
    s.particles.push_back(std::move(q));
  }
  return c;
}

}  // namespace dlmfd
