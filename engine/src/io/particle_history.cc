#include "dlmfd/io/particle_history.h"

#include <algorithm>

#include "dlmfd/core/errors.h"
#include "hdf5_file.h"
#include "results_attributes.h"

namespace dlmfd {
namespace {

constexpr hsize_t kChunkRecords = 64;

struct Series {
  const char* name;
  int components;  // 0: one value per record; 1: one per particle; 2: a vector per particle
  bool integer;
};

const Series kSeries[] = {
    {"time", 0, false},
    {"step", 0, true},
    {"position", 2, false},
    {"velocity", 2, false},
    {"angular_velocity", 1, false},
    {"force", 2, false},
    {"torque", 1, false},
    {"angle", 1, false},  // version 2
};
constexpr int kSeriesCount = 8;

const char* DimensionsOf(const Series& s) {
  return s.components == 0   ? "record"
         : s.components == 1 ? "record particle"
                             : "record particle component";
}

// A dataset shape without heap allocation (Append runs inside the time loop).
struct Dims {
  hsize_t d[3] = {0, 0, 0};
  int rank = 1;
  const hsize_t* data() const { return d; }
  hsize_t Count() const { return rank == 1 ? d[0] : rank == 2 ? d[0] * d[1] : d[0] * d[1] * d[2]; }
};

Dims Shape(const Series& s, hsize_t nt, hsize_t np) {
  Dims out;
  out.d[0] = nt;
  out.d[1] = np;
  out.d[2] = 2;
  out.rank = s.components == 0 ? 1 : s.components == 1 ? 2 : 3;
  return out;
}

}  // namespace

struct ParticleHistoryWriter::Impl {
  h5::Handle file;
  h5::Handle sets[kSeriesCount];
  int series = kSeriesCount;  // 7 for a file of version 1 (no /angle)
  hsize_t np = 0;
  std::vector<double> buffer;  // one record of the widest series
};

ParticleHistoryWriter::ParticleHistoryWriter(std::unique_ptr<Impl> impl)
    : impl_(std::move(impl)) {}
ParticleHistoryWriter::~ParticleHistoryWriter() = default;

bool ParticleHistoryWriter::has_angle() const { return impl_->series == kSeriesCount; }

std::unique_ptr<ParticleHistoryWriter> ParticleHistoryWriter::Create(
    const std::string& path, const FlowState& state, const std::string& scene_text) {
  auto impl = std::make_unique<Impl>();
  impl->np = state.particles.size();
  impl->file = h5::CreateFile(path);
  const hid_t f = impl->file.get();
  std::vector<std::int64_t> ids;
  std::vector<std::int64_t> shapes;
  std::vector<double> radii, semi_axes;
  for (const auto& q : state.particles) {
    ids.push_back(q.id);
    radii.push_back(q.radius);
    shapes.push_back(q.shape == ShapeKind::kEllipse ? 1 : 0);
    const bool disk = q.shape == ShapeKind::kDisk;
    semi_axes.insert(semi_axes.end(),
                     {disk ? q.radius : q.semi_axes.x(), disk ? q.radius : q.semi_axes.y()});
  }
  h5::WriteInts(f, "id", {impl->np}, ids.data());
  h5::WriteDoubles(f, "radius", {impl->np}, radii.data());
  h5::WriteInts(f, "shape", {impl->np}, shapes.data());
  h5::WriteDoubles(f, "semi_axes", {impl->np, 2}, semi_axes.data());
  h5::WriteFormat(f, kParticlesFormat, scene_text);
  h5::Describe(f, "id", ResultsFile::kParticles, "id", "particle");
  h5::Describe(f, "radius", ResultsFile::kParticles, "radius", "particle");
  h5::Describe(f, "shape", ResultsFile::kParticles, "shape", "particle");
  h5::Describe(f, "semi_axes", ResultsFile::kParticles, "semi_axes", "particle component");
  for (int k = 0; k < kSeriesCount; ++k) {
    const Series& s = kSeries[k];
    const Dims dims = Shape(s, 0, impl->np);
    const hsize_t maxdims[3] = {H5S_UNLIMITED, H5S_UNLIMITED, H5S_UNLIMITED};
    const Dims chunk = Shape(s, kChunkRecords, std::max<hsize_t>(impl->np, 1));
    h5::Handle space(h5::CheckId(H5Screate_simple(dims.rank, dims.data(), maxdims), "dataspace"),
                     H5Sclose);
    h5::Handle plist(h5::CheckId(H5Pcreate(H5P_DATASET_CREATE), "property list"), H5Pclose);
    h5::Check(H5Pset_chunk(plist.get(), chunk.rank, chunk.data()), "chunk particles.h5");
    const hid_t type = s.integer ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE;
    impl->sets[k] = h5::Handle(
        h5::CheckId(H5Dcreate2(f, s.name, type, space.get(), H5P_DEFAULT, plist.get(), H5P_DEFAULT),
                    std::string("create particles.h5:/") + s.name),
        H5Dclose);
    h5::Describe(f, s.name, ResultsFile::kParticles, s.name, DimensionsOf(s));
  }
  impl->buffer.resize(std::max<std::size_t>(2 * impl->np, 1));
  h5::Check(H5Fflush(f, H5F_SCOPE_LOCAL), "flush " + path);
  return std::unique_ptr<ParticleHistoryWriter>(new ParticleHistoryWriter(std::move(impl)));
}

std::unique_ptr<ParticleHistoryWriter> ParticleHistoryWriter::Resume(const std::string& path,
                                                                     long last_step) {
  auto impl = std::make_unique<Impl>();
  impl->file = h5::OpenFile(path, true);
  const hid_t f = impl->file.get();
  std::vector<hsize_t> id_dims;
  h5::ReadInts(f, "id", &id_dims);
  impl->np = id_dims.empty() ? 0 : id_dims[0];
  const std::vector<std::int64_t> steps = h5::ReadInts(f, "step");
  const hsize_t keep = static_cast<hsize_t>(std::count_if(
      steps.begin(), steps.end(), [last_step](std::int64_t s) { return s <= last_step; }));
  impl->series = h5::Exists(f, "angle") ? kSeriesCount : kSeriesCount - 1;
  for (int k = 0; k < impl->series; ++k) {
    impl->sets[k] = h5::Handle(
        h5::CheckId(H5Dopen2(f, kSeries[k].name, H5P_DEFAULT), "open particles.h5"), H5Dclose);
    const Dims dims = Shape(kSeries[k], keep, impl->np);
    h5::Check(H5Dset_extent(impl->sets[k].get(), dims.data()), "truncate particles.h5");
  }
  impl->buffer.resize(std::max<std::size_t>(2 * impl->np, 1));
  h5::Check(H5Fflush(f, H5F_SCOPE_LOCAL), "flush " + path);
  auto writer = std::unique_ptr<ParticleHistoryWriter>(new ParticleHistoryWriter(std::move(impl)));
  writer->records_ = keep;
  return writer;
}

void ParticleHistoryWriter::Append(const FlowState& state, const std::vector<double>& angles) {
  Impl& m = *impl_;
  if (state.particles.size() != m.np) throw Error("particles.h5: the number of particles changed");
  if (m.series == kSeriesCount && angles.size() != m.np)
    throw Error("particles.h5: " + std::to_string(angles.size()) + " angles for " +
                std::to_string(m.np) + " particles");
  const hsize_t row = records_;
  for (int k = 0; k < m.series; ++k) {
    const Series& s = kSeries[k];
    const hid_t set = m.sets[k].get();
    const Dims dims = Shape(s, row + 1, m.np);
    h5::Check(H5Dset_extent(set, dims.data()), "extend particles.h5");
    Dims start = Shape(s, row, 0);
    start.d[2] = 0;
    const Dims count = Shape(s, 1, m.np);
    if (count.Count() == 0) continue;
    h5::Handle file_space(h5::CheckId(H5Dget_space(set), "dataspace"), H5Sclose);
    h5::Check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr,
                                  count.data(), nullptr),
              "select record");
    h5::Handle memory_space(
        h5::CheckId(H5Screate_simple(count.rank, count.data(), nullptr), "dataspace"), H5Sclose);
    if (s.integer) {
      const std::int64_t step = state.step;
      h5::Check(
          H5Dwrite(set, H5T_NATIVE_INT64, memory_space.get(), file_space.get(), H5P_DEFAULT, &step),
          "write particles.h5");
      continue;
    }
    double* b = m.buffer.data();
    if (k == 0) {
      b[0] = state.time;
    } else {
      for (std::size_t i = 0; i < m.np; ++i) {
        const ParticleState& q = state.particles[i];
        switch (k) {
          case 2:
            b[2 * i] = q.position.x();
            b[2 * i + 1] = q.position.y();
            break;
          case 3:
            b[2 * i] = q.velocity.x();
            b[2 * i + 1] = q.velocity.y();
            break;
          case 4:
            b[i] = q.angular_velocity;
            break;
          case 5:
            b[2 * i] = q.force.x();
            b[2 * i + 1] = q.force.y();
            break;
          case 7:
            b[i] = angles[i];
            break;
          default:
            b[i] = q.torque;
            break;
        }
      }
    }
    h5::Check(
        H5Dwrite(set, H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT, b),
        "write particles.h5");
  }
  ++records_;
  h5::Check(H5Fflush(m.file.get(), H5F_SCOPE_LOCAL), "flush particles.h5");
}

ParticleHistory ReadParticleHistory(const std::string& path) {
  h5::Handle file = h5::OpenFile(path, false);
  const hid_t f = file.get();
  ParticleHistory h;
  h.format_version = h5::ReadFormatVersion(f, path);
  std::vector<hsize_t> dims;
  h.id = h5::ReadInts(f, "id", &dims);
  h.particles = dims.empty() ? 0 : dims[0];
  h.radius = h5::ReadDoubles(f, "radius");
  if (h5::Exists(f, "shape")) h.shape = h5::ReadInts(f, "shape");
  if (h5::Exists(f, "semi_axes")) h.semi_axes = h5::ReadDoubles(f, "semi_axes");
  h.time = h5::ReadDoubles(f, "time", &dims);
  h.records = dims.empty() ? 0 : dims[0];
  h.step = h5::ReadInts(f, "step");
  h.position = h5::ReadDoubles(f, "position");
  h.velocity = h5::ReadDoubles(f, "velocity");
  h.angular_velocity = h5::ReadDoubles(f, "angular_velocity");
  h.force = h5::ReadDoubles(f, "force");
  h.torque = h5::ReadDoubles(f, "torque");
  if (h5::Exists(f, "angle")) h.angle = h5::ReadDoubles(f, "angle");
  if (h5::Exists(f, "scene")) h.scene_text = h5::ReadText(f, "scene");
  return h;
}

}  // namespace dlmfd
