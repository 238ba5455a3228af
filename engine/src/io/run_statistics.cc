// Statistics of a whole run from its results directory; see io/run_statistics.h.
#include "dlmfd/io/run_statistics.h"

#include <cmath>
#include <filesystem>
#include <limits>

#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The extreme of a column over every row (NaN rows skipped); NaN when the column is absent or
// empty.
template <class Better>
double ColumnExtreme(const DiagnosticsTable& table, const char* name, Better better) {
  const int column = table.Column(name);
  double best = kNaN;
  if (column < 0) return best;
  for (const std::vector<double>& row : table.rows) {
    if (static_cast<std::size_t>(column) >= row.size()) continue;
    const double x = row[column];
    if (!std::isnan(x) && (std::isnan(best) || better(x, best))) best = x;
  }
  return best;
}

// X_b - X_a wrapped to the nearest image across periodic sides.
Vec2 Displacement(const DomainParams& domain, Vec2 delta) {
  if (domain.PeriodicX()) delta.x() -= domain.size.x() * std::round(delta.x() / domain.size.x());
  if (domain.PeriodicY()) delta.y() -= domain.size.y() * std::round(delta.y() / domain.size.y());
  return delta;
}

void FallSpeeds(const Params& params, const ParticleHistory& h, RunStatistics& s) {
  const std::size_t np = h.particles;
  s.fall_speed.assign(np, kNaN);
  s.fall_window_start = s.fall_window_end = kNaN;
  const double g = params.gravity.norm();
  if (h.records < 2 || np == 0 || !(g > 0.0)) return;
  const Vec2 down = params.gravity / g;
  const std::size_t last = h.records - 1;
  const double t_b = h.time[last];
  std::size_t first = last;
  while (first > 0 && h.time[first - 1] >= 0.5 * t_b) --first;
  if (first == last) return;
  s.fall_window_start = h.time[first];
  s.fall_window_end = t_b;
  const double duration = t_b - h.time[first];
  for (std::size_t p = 0; p < np; ++p) {
    Vec2 moved = Vec2::Zero();
    for (std::size_t k = first; k < last; ++k) {
      const std::size_t a = (k * np + p) * 2, b = ((k + 1) * np + p) * 2;
      moved += Displacement(params.domain, Vec2(h.position[b] - h.position[a],
                                                h.position[b + 1] - h.position[a + 1]));
    }
    s.fall_speed[p] = moved.dot(down) / duration;
  }
}

}  // namespace

RunStatistics ComputeRunStatistics(const Params& params, const DiagnosticsTable& diagnostics,
                                   const ParticleHistory& particles) {
  RunStatistics s;
  auto less = [](double a, double b) { return a < b; };
  auto greater = [](double a, double b) { return a > b; };
  s.min_gap = ColumnExtreme(diagnostics, "particle_pair_gap", less);
  s.min_wall_gap = ColumnExtreme(diagnostics, "particle_wall_gap", less);
  s.max_trA = ColumnExtreme(diagnostics, "max_trA", greater);
  s.min_eig_A = ColumnExtreme(diagnostics, "min_eig_A", less);
  FallSpeeds(params, particles, s);
  double speed = 0.0, diameter = 0.0;
  int free = 0;
  for (std::size_t p = 0; p < params.particles.size() && p < s.fall_speed.size(); ++p) {
    if (params.particles[p].motion != Motion::kFree) continue;
    speed += s.fall_speed[p];
    diameter += params.particles[p].diameter;
    ++free;
  }
  s.mean_fall_speed = free > 0 ? speed / free : kNaN;
  s.diameter = free > 0 ? diameter / free : kNaN;
  // The paper's U is a speed: a particle rising (U < 0) has the same numbers as one falling.
  const double U = std::abs(s.mean_fall_speed), D = s.diameter;
  s.reynolds = params.fluid.density * U * D / params.fluid.viscosity;
  s.deborah = params.fluid.Deborah(U, D);
  s.mach = std::sqrt(s.reynolds * s.deborah);
  s.elasticity = s.reynolds > 0.0 ? s.deborah / s.reynolds : kNaN;
  return s;
}

RunStatistics ReadRunStatistics(const Params& params, const std::string& dir) {
  DiagnosticsTable diagnostics;
  ParticleHistory particles;
  try {
    if (std::filesystem::exists(dir + "/diagnostics.csv"))
      diagnostics = ReadDiagnostics(dir + "/diagnostics.csv");
  } catch (const Error&) {}
  try {
    if (std::filesystem::exists(dir + "/particles.h5"))
      particles = ReadParticleHistory(dir + "/particles.h5");
  } catch (const Error&) {}
  return ComputeRunStatistics(params, diagnostics, particles);
}

}  // namespace dlmfd
