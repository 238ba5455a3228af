// wp_error: the error figures of bench/work_precision.sh, read from one dlmfd-solve results
// directory.
//
//   wp_error waters-king DIR [BETA ELASTICITY]
//       max over the field snapshots (t > 0) of |u(centre line, t) - U(0, t)|, U the Waters-King
//       series (engine/include/dlmfd/reference/waters_king_series.h) for the scene of
//       cases/verification/waters_king.toml (H = 1, Ubar = 1, T = t; defaults beta = 1/9, E = 1).
//       Prints: max_error time_of_max snapshots.
//   wp_error particle DIR [ID]
//       the last record of particles.h5 for particle ID (default 0).
//       Prints: time x y u v omega fx fy.
//   wp_error terminal DIR T0 T1 [ID]
//       mean of the vertical velocity of particle ID (default 0) over the records with T0 <= t <=
//       T1 (with output.particles_every = 0 a time average; it removes the small oscillation of a
//       disk crossing the mesh cells). Prints: mean_v records.
//
// Exit status 0, or 2 with a message on stderr (bad arguments, unreadable or empty results).
// Not supported: Waters-King scenes with H != 1 or Ubar != 1 (the series is scaled by them).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "dlmfd/io/field_snapshot.h"
#include "dlmfd/io/particle_history.h"
#include "dlmfd/reference/waters_king_series.h"

namespace {

int Usage() {
  std::fprintf(stderr,
               "usage: wp_error waters-king DIR [BETA ELASTICITY] | wp_error particle DIR [ID] | "
               "wp_error terminal DIR T0 T1 [ID]\n");
  return 2;
}

int WatersKingError(const std::string& dir, double beta, double elasticity) {
  double max_error = -1.0, time_of_max = 0.0;
  int used = 0;
  for (const long step : dlmfd::SnapshotSteps(dir)) {
    const std::string file = dir + "/fields/" + dlmfd::SnapshotFileName(step);
    const dlmfd::FieldSnapshot snap = dlmfd::ReadFieldSnapshot(file);
    if (snap.time <= 0.0) continue;
    const dlmfd::FieldArray& u = snap.fields.at("u");
    const std::size_t rows = u.shape.at(0), columns = u.shape.at(1);
    if (rows % 2 == 0)
      throw std::runtime_error(file + ": the centre line needs an even number of cells in y");
    const double centre = u.values[(rows / 2) * columns];
    const double error =
        std::abs(centre - dlmfd::WatersKingVelocity(0.0, snap.time, beta, elasticity));
    if (error > max_error) {
      max_error = error;
      time_of_max = snap.time;
    }
    ++used;
  }
  if (used == 0) throw std::runtime_error(dir + "/fields: no snapshot with t > 0");
  std::printf("%.6e %.6g %d\n", max_error, time_of_max, used);
  return 0;
}

// Index of particle id in the history; throws when absent.
std::size_t ParticleIndex(const dlmfd::ParticleHistory& h, const std::string& dir, long id) {
  const auto it = std::find(h.id.begin(), h.id.end(), static_cast<std::int64_t>(id));
  if (it == h.id.end())
    throw std::runtime_error(dir + "/particles.h5: no particle " + std::to_string(id));
  return static_cast<std::size_t>(it - h.id.begin());
}

int MeanVerticalVelocity(const std::string& dir, double t0, double t1, long id) {
  const dlmfd::ParticleHistory h = dlmfd::ReadParticleHistory(dir + "/particles.h5");
  const std::size_t np = h.id.size(), p = ParticleIndex(h, dir, id);
  double sum = 0.0;
  int records = 0;
  for (std::size_t n = 0; n < h.time.size(); ++n) {
    if (h.time[n] < t0 || h.time[n] > t1) continue;
    sum += h.velocity[2 * (n * np + p) + 1];
    ++records;
  }
  if (records == 0) throw std::runtime_error(dir + "/particles.h5: no record in the time window");
  std::printf("%.12g %d\n", sum / records, records);
  return 0;
}

int LastParticleRecord(const std::string& dir, long id) {
  const dlmfd::ParticleHistory h = dlmfd::ReadParticleHistory(dir + "/particles.h5");
  const std::size_t np = h.id.size(), nt = h.time.size();
  if (nt == 0) throw std::runtime_error(dir + "/particles.h5: no record");
  const std::size_t k = (nt - 1) * np + ParticleIndex(h, dir, id);
  std::printf("%.10g %.12g %.12g %.12g %.12g %.12g %.12g %.12g\n", h.time[nt - 1],
              h.position[2 * k], h.position[2 * k + 1], h.velocity[2 * k], h.velocity[2 * k + 1],
              h.angular_velocity[k], h.force[2 * k], h.force[2 * k + 1]);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return Usage();
  const std::string command = argv[1], dir = argv[2];
  try {
    if (command == "waters-king" && (argc == 3 || argc == 5)) {
      const double beta = argc == 5 ? std::atof(argv[3]) : 1.0 / 9.0;
      const double elasticity = argc == 5 ? std::atof(argv[4]) : 1.0;
      return WatersKingError(dir, beta, elasticity);
    }
    if (command == "particle" && (argc == 3 || argc == 4))
      return LastParticleRecord(dir, argc == 4 ? std::atol(argv[3]) : 0);
    if (command == "terminal" && (argc == 5 || argc == 6))
      return MeanVerticalVelocity(dir, std::atof(argv[3]), std::atof(argv[4]),
                                  argc == 6 ? std::atol(argv[5]) : 0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "wp_error: %s\n", e.what());
    return 2;
  }
  return Usage();
}
