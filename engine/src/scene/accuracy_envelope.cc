// The accuracy envelope; the bounds and their sources are in scene/accuracy_envelope.h.
#include "dlmfd/scene/accuracy_envelope.h"

#include <algorithm>
#include <cmath>

#include "dlmfd/core/constants.h"
#include "dlmfd/core/number_text.h"
#include "dlmfd/fluid/boundary_profile.h"

namespace dlmfd {
namespace {

constexpr const char* kSourceD = "docs/evidence/work_precision.md (d), Which settings 3";
constexpr const char* kSourceDCollocation =
    "docs/evidence/particle_boundary.md (e), the work-precision chart";
constexpr const char* kSourceViscous = "docs/evidence/work_precision.md (d) dt ladder";
constexpr const char* kSourceViscousFluid = "docs/evidence/work_precision.md (a), (b)";
constexpr const char* kSourceViscousCoupling =
    "docs/evidence/constraint_coupling.md, Coupling the constraint with viscosity";
constexpr const char* kSourceCutCells =
    "docs/evidence/cut_cell_boundary.md, `auto` picks cut cells for fixed disks";
constexpr const char* kSourceDCutCells =
    "docs/evidence/cut_cell_boundary.md, The pressure ghost penalty's scale";
constexpr const char* kSourceCourant = "docs/evidence/work_precision.md (b), Which settings 1";
constexpr const char* kSourceLaggedCourant =
    "docs/evidence/constraint_coupling.md, The automatic coupling";
constexpr const char* kSourceElastic = "docs/evidence/work_precision.md (a)";
constexpr const char* kSourceParticleMesh =
    "docs/evidence/work_precision.md, The particle mesh against the fluid mesh";

// A setting on its bound is inside it: the settings are products and quotients of the scene's
// numbers (0.01 / 0.015625), so a bound is compared with this margin of round-off.
constexpr double kRoundOff = 1e-9;
bool Above(double value, double bound) { return value > bound * (1.0 + kRoundOff); }

double KinematicViscosity(const Params& p) { return p.fluid.viscosity / p.fluid.density; }

bool CutCells(const Params& p) { return p.particle_mesh.kind == ParticleMeshKind::kCutCell; }

// The D / h bound of the scene's particle boundary (accuracy_envelope.h): the ring mesh's, the
// collocation points' per coupling, the cut cells' (no multiplier: the coupling does not matter).
double MinDiskResolution(const Params& p) {
  if (p.particle_mesh.kind == ParticleMeshKind::kRing) return kMinDiskResolution;
  if (CutCells(p)) return kMinDiskResolutionCutCells;
  return p.splitting.constraint.value() == ConstraintCoupling::kPaper
             ? kMinDiskResolutionCollocationPaper
             : kMinDiskResolutionCollocation;
}

bool HasPolymer(const Params& p) { return !p.fluid.IsNewtonian(); }

// El_h = lambda eta_p / (rho h^2), the elasticity number of one cell.
double GridElasticity(const Params& p) { return p.fluid.CellElasticity(p.domain.h); }

// The plane Poiseuille peak of a body force component across the sides it is bounded by.
double BodyForceSpeed(const Params& p, double force, double height, bool periodic_across) {
  if (force == 0.0 || periodic_across) return 0.0;
  return std::abs(force) * height * height / (8.0 * p.fluid.viscosity);
}

// dt / k for the smallest integer k >= 1 with value / k <= bound: the step count stays an integer
// multiple of the one now, so every output period that fitted still fits.
std::string SmallerStep(double dt, double value, double bound) {
  const double k = std::max(1.0, std::ceil(value / bound * (1.0 - kRoundOff)));
  return ExactText(dt / k);
}

AccuracyWarning TimeStepWarning(const Params& p, std::string setting, double value, double bound,
                                const char* source) {
  AccuracyWarning w;
  w.setting = std::move(setting);
  w.value = value;
  w.allowed = "<= " + ShortText(bound);
  w.key = "time.dt";
  w.current = ExactText(p.time.dt);
  w.suggested = SmallerStep(p.time.dt, value, bound);
  w.source = source;
  return w;
}

double ElasticCourant(const Params& p) {
  return p.fluid.ElasticWaveSpeed() * p.time.dt / p.domain.h;
}

}  // namespace

std::string AccuracyWarning::Message() const {
  return setting + " = " + ShortText(value) + " is outside the accuracy envelope (" + allowed +
         ", " + source + "): set " + key + " = " + suggested + " (now " + current + ")";
}

double ParticleVelocityScale(const Params& p) {
  double u = 0.0;
  const double rho = p.fluid.density;
  const double g = p.gravity.norm();
  for (const ParticleParams& q : p.particles) {
    u = std::max(u, q.velocity.norm() + std::abs(q.angular_velocity) * q.Radius());
    if (q.motion != Motion::kFree || g == 0.0) continue;
    const double contrast = std::abs(q.density - rho) / rho;
    const double inertial = std::sqrt(0.5 * kPi * contrast * g * q.diameter);
    const double viscous = contrast * rho * g * q.diameter * q.diameter / p.fluid.viscosity;
    u = std::max(u, std::min(inertial, viscous));
  }
  return u;
}

double VelocityScale(const Params& p) {
  double u = ParticleVelocityScale(p);
  for (const BoundarySide& side : p.domain.sides) {
    u = std::max(u, ProfilePeakSpeed(side));  // the data at their peak over time
  }
  const Vec2& f = p.fluid.body_force;
  u = std::max(u, BodyForceSpeed(p, f.x(), p.domain.size.y(), p.domain.PeriodicY()));
  u = std::max(u, BodyForceSpeed(p, f.y(), p.domain.size.x(), p.domain.PeriodicX()));
  return u;
}

std::vector<AccuracySetting> AccuracySettings(const Params& p) {
  const double h = p.domain.h;
  const double dt = p.time.dt;
  const double u = VelocityScale(p);
  std::vector<AccuracySetting> s = {
      {"nu dt / h^2", KinematicViscosity(p) * dt / (h * h)}, {"U dt / h", u * dt / h}, {"U", u}};
  if (HasPolymer(p)) {
    s.push_back({"c dt / h", ElasticCourant(p)});
    s.push_back({"dt / lambda", dt / p.fluid.relaxation_time});
  }
  for (std::size_t i = 0; i < p.particles.size(); ++i) {
    const std::string which = " (particles." + std::to_string(i) + ")";
    s.push_back({"D / h" + which, p.particles[i].diameter / h});
    if (p.particle_mesh.kind == ParticleMeshKind::kCutCell) continue;  // no multiplier points
    // The multiplier point spacing: h_p of the ring mesh, c h on the collocation circle.
    const double point_spacing = p.particle_mesh.kind == ParticleMeshKind::kRing
                                     ? p.particle_mesh.RingMeshSize(h)
                                     : p.particle_mesh.spacing * h;
    s.push_back({"D / h_p" + which, p.particles[i].diameter / point_spacing});
  }
  return s;
}

std::vector<AccuracyWarning> AccuracyWarnings(const Params& p) {
  std::vector<AccuracyWarning> out;
  const double h = p.domain.h;
  const double dt = p.time.dt;

  const bool particles = !p.particles.empty();
  const double viscous = KinematicViscosity(p) * dt / (h * h);
  const ConstraintCoupling coupling = p.splitting.constraint.value();
  // Cut cells hold the bodies in the Stokes step (33) itself, with no multiplier: the coupling's
  // bounds (its leak, its lag) do not apply; theirs is what their runs measured.
  const bool multipliers = particles && !CutCells(p);
  const double viscous_bound =
      !particles                                     ? kMaxViscousNumberWithoutParticles
      : !multipliers                                 ? kMaxViscousNumberCutCells
      : coupling == ConstraintCoupling::kViscous     ? kMaxViscousNumberViscousCoupling
      : coupling == ConstraintCoupling::kIncremental ? kMaxViscousNumberIncrementalCoupling
                                                     : kMaxViscousNumberWithParticles;
  if (Above(viscous, viscous_bound)) {
    const char* source = !particles                               ? kSourceViscousFluid
                         : !multipliers                           ? kSourceCutCells
                         : coupling == ConstraintCoupling::kPaper ? kSourceViscous
                                                                  : kSourceViscousCoupling;
    out.push_back(TimeStepWarning(p, "nu dt / h^2", viscous, viscous_bound, source));
  }

  const double courant = VelocityScale(p) * dt / h;
  if (Above(courant, kMaxAdvectiveCourant)) {
    out.push_back(TimeStepWarning(p, "U dt / h", courant, kMaxAdvectiveCourant, kSourceCourant));
  }
  if (multipliers && coupling == ConstraintCoupling::kIncremental) {
    const double particle_courant = ParticleVelocityScale(p) * dt / h;
    if (Above(particle_courant, kMaxLaggedParticleCourant)) {
      out.push_back(TimeStepWarning(p, "U_p dt / h", particle_courant, kMaxLaggedParticleCourant,
                                    kSourceLaggedCourant));
    }
  }

  // A polymer viscous on the grid's scale under devss has no elastic bounds (accuracy_envelope.h).
  const bool viscous_polymer = p.fluid.Devss() && !Above(GridElasticity(p), kMaxGridElasticity) &&
                               !Above(p.fluid.Deborah(VelocityScale(p), h), kMaxGridDeborah);
  if (HasPolymer(p) && !viscous_polymer) {
    const double elastic = ElasticCourant(p);
    if (Above(elastic, kMaxElasticCourant)) {
      out.push_back(TimeStepWarning(p, "c dt / h", elastic, kMaxElasticCourant, kSourceElastic));
    }
    const double per_lambda = dt / p.fluid.relaxation_time;
    if (Above(per_lambda, kMaxStepPerRelaxationTime)) {
      out.push_back(
          TimeStepWarning(p, "dt / lambda", per_lambda, kMaxStepPerRelaxationTime, kSourceElastic));
    }
  }

  std::size_t smallest = 0;
  int below = 0;
  const double min_resolution = MinDiskResolution(p);
  for (std::size_t i = 0; i < p.particles.size(); ++i) {
    if (Above(min_resolution, p.particles[i].diameter / h)) ++below;
    if (p.particles[i].diameter < p.particles[smallest].diameter) smallest = i;
  }
  if (below > 0) {
    const double resolution = p.particles[smallest].diameter / h;
    // h / k keeps every cell count an even integer.
    const double k = std::ceil(min_resolution / resolution * (1.0 - kRoundOff));
    AccuracyWarning w;
    w.setting = "D / h (particles." + std::to_string(smallest) + ")";
    if (below > 1) {
      w.setting.back() = ',';
      w.setting += " the smallest of " + std::to_string(below) + " below the bound)";
    }
    w.value = resolution;
    w.allowed = ">= " + ShortText(min_resolution);
    w.key = "domain.h";
    w.current = ExactText(h);
    w.suggested = ExactText(h / k);
    w.source = p.particle_mesh.kind == ParticleMeshKind::kRing ? kSourceD
               : CutCells(p)                                   ? kSourceDCutCells
                                                               : kSourceDCollocation;
    out.push_back(std::move(w));
  }

  if (particles && p.particle_mesh.kind == ParticleMeshKind::kRing) {
    const double ratio = p.particle_mesh.RingMeshSize(h) / h;
    if (Above(kMinParticleMeshRatio, ratio)) {
      AccuracyWarning w;
      w.setting = "h_p / h";
      w.value = ratio;
      w.allowed = ">= " + ShortText(kMinParticleMeshRatio);
      w.key = "particle_mesh.h";
      w.current = ExactText(p.particle_mesh.RingMeshSize(h));
      w.suggested = ExactText(kPaperParticleMeshRatio * h);
      w.source = kSourceParticleMesh;
      out.push_back(std::move(w));
    }
  }
  return out;
}

}  // namespace dlmfd
