// ValidateScene: the ranges of the scene's keys, the footprint limits, the mesh rules, then the
// rules the modules own; see scene/scene_validation.h.
#include "dlmfd/scene/scene_validation.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "dlmfd/conformation/inflow_state.h"
#include "dlmfd/conformation/relaxation_model.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/grid.h"
#include "dlmfd/core/number_text.h"
#include "dlmfd/core/side_names.h"
#include "dlmfd/core/time_stepping.h"
#include "dlmfd/fluid/boundary_profile.h"
#include "dlmfd/particles/collocation_points.h"
#include "dlmfd/particles/particle_rules.h"
#include "dlmfd/scene/accuracy_envelope.h"
#include "dlmfd/scene/scene_file.h"
#include "dlmfd/scene/scene_footprint.h"
#include "dlmfd/scene/scene_keys.h"

namespace dlmfd {
namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

// Both semi-axes > 0 and finite, the longer at most kMaxEllipseAspect times the shorter.
void RequireEllipseAxes(const std::string& key, const Vec2& axes) {
  const double a = axes.x(), b = axes.y();
  const bool positive = a > 0.0 && b > 0.0 && std::isfinite(a) && std::isfinite(b);
  if (!positive || std::max(a, b) > kMaxEllipseAspect * std::min(a, b)) {
    throw InvalidParameter(key, VecText(axes),
                           "[a, b], two numbers > 0 with max / min <= " +
                               ShortText(kMaxEllipseAspect) + " (the ellipse's semi-axes)");
  }
}

// `length` holds an even number >= 4 of cells of h, within 1e-9 relative. Called after the node
// limit, so the count fits in any integer.
void RequireEvenCells(const DomainParams& d, double length) {
  const double n = length / d.h;
  const double rounded = std::round(n);
  if (std::abs(n - rounded) > 1e-9 * std::max(1.0, n) || static_cast<long long>(rounded) % 2 != 0 ||
      rounded < 4) {
    std::ostringstream allowed;
    allowed << "a size that is an even number >= 4 of cells of domain.h = " << ExactText(d.h)
            << " in both directions (here " << ExactText(length) << " / h = " << n
            << "; the pressure mesh is 2h, and its fast solver needs 2 cells)";
    throw InvalidParameter("domain.size", VecText(d.size), allowed.str());
  }
}

// domain.flow_rate (fluid/flux_control.h): a finite number in a channel periodic in exactly one
// direction whose other two sides are Dirichlet (wall or velocity), so that the unit response to
// the mean pressure gradient is a solenoidal profile across the channel; or 0 in a box periodic in
// both directions (zero mean velocity along x and y, the frame of a periodic suspension).
void ValidateFlowRate(const DomainParams& d) {
  if (!d.flow_rate) return;
  const std::string allowed =
      "a channel periodic in one direction: either bottom and top \"periodic\" with left and "
      "right \"wall\" or \"velocity\", or left and right \"periodic\" with bottom and top "
      "\"wall\" or \"velocity\"; or 0 in a box periodic in both directions (or leave "
      "domain.flow_rate out)";
  if (!std::isfinite(*d.flow_rate)) {
    throw InvalidParameter("domain.flow_rate", ExactText(*d.flow_rate),
                           "a finite number (the volume flux per unit depth along the periodic "
                           "direction; 0 for sedimentation without end walls) in " +
                               allowed);
  }
  if (d.PeriodicX() && d.PeriodicY()) {
    if (*d.flow_rate == 0.0) return;
    throw InvalidParameter("domain.flow_rate", ExactText(*d.flow_rate),
                           "0 in a box periodic in both directions (zero mean velocity along x "
                           "and y: a non-zero rate would need a direction; " +
                               allowed + ")");
  }
  if (!d.PeriodicX() && !d.PeriodicY()) {
    throw InvalidParameter("domain.flow_rate", ExactText(*d.flow_rate),
                           allowed + "; this domain is periodic in neither direction");
  }
  const int first = d.PeriodicX() ? 2 : 0;  // the cross-stream sides
  for (int s = first; s < first + 2; ++s) {
    if (d.sides[s].type == SideType::kOutflow) {
      throw InvalidParameter(std::string("domain.boundary.") + SideName(s) + ".type", "\"outflow\"",
                             "\"wall\" or \"velocity\" with domain.flow_rate (" + allowed + ")");
    }
  }
}

void ValidateDomain(const Params& p) {
  const DomainParams& d = p.domain;
  if (!(d.size.x() > 0.0 && d.size.y() > 0.0)) {
    throw InvalidParameter("domain.size", VecText(d.size), "two numbers > 0 (width, height)");
  }
  scene::RequireSectionKeys(p, "domain");
  const SceneFootprint footprint = EstimateFootprint(p);
  if (!(footprint.velocity_nodes <= kMaxVelocityNodes)) {
    throw InvalidParameter(
        "domain.h", ExactText(d.h),
        "a mesh of at most " + ShortText(kMaxVelocityNodes) + " velocity nodes (this one has " +
            ShortText(footprint.velocity_nodes) + ", about " +
            ShortText(kBytesPerNode * footprint.velocity_nodes / kGiB) + " GiB of memory)");
  }
  RequireEvenCells(d, d.size.x());
  RequireEvenCells(d, d.size.y());
  for (int s = 0; s < 4; s += 2) {
    const bool first = d.sides[s].type == SideType::kPeriodic;
    const bool second = d.sides[s + 1].type == SideType::kPeriodic;
    if (first != second) {
      const int odd = first ? s + 1 : s;
      const int even = first ? s : s + 1;
      throw InvalidParameter(
          std::string("domain.boundary.") + SideName(odd) + ".type", "(not periodic)",
          std::string("\"periodic\", because domain.boundary.") + SideName(even) +
              " is periodic (periodic sides come in pairs: left with right, bottom with top)");
    }
  }
  ValidateBoundaryProfiles(d);
  ValidateFlowRate(d);
}

// The tables' keys (scene/scene_keys.h), section by section.
void ValidateFluid(const Params& p) {
  scene::RequireSectionKeys(p, "fluid");
  ValidateConstitutiveModel(p.fluid);
}

void ValidateMeshCollisionsConformation(const Params& p) {
  scene::RequireSectionKeys(p, "particle_mesh");
  scene::RequireSectionKeys(p, "collisions");
  scene::RequireSectionKeys(p, "conformation");
}

void ValidateParticleRangesAndMeshes(const Params& p) {
  for (std::size_t i = 0; i < p.particles.size(); ++i) {
    const std::string prefix = "particles." + std::to_string(i);
    const ParticleParams& q = p.particles[i];
    if (q.shape == ShapeKind::kEllipse) RequireEllipseAxes(prefix + ".semi_axes", q.semi_axes);
    scene::RequireParticleRanges(q, prefix);
  }
  const SceneFootprint footprint = EstimateFootprint(p);
  if (!(footprint.multiplier_nodes <= kMaxMultiplierNodes)) {
    const bool ring = p.particle_mesh.kind == ParticleMeshKind::kRing;
    throw InvalidParameter(ring ? "particle_mesh.h" : "domain.h",
                           ExactText(ring ? p.particle_mesh.RingMeshSize(p.domain.h) : p.domain.h),
                           "multiplier meshes of at most " + ShortText(kMaxMultiplierNodes) +
                               " nodes over all particles (these have about " +
                               ShortText(footprint.multiplier_nodes) + ", about " +
                               ShortText(kBytesPerNode * footprint.multiplier_nodes / kGiB) +
                               " GiB of memory)");
  }
}

// The ring mesh resolves a disk only with h_p <= R: at R / h_p = 1 it is one ring of 6 nodes, and
// coarser it stays 3 nodes however large h_p (issue 38: particle_mesh.h = 1e300 ran). After the
// particles' own rules: a disk too small for its grid is named as such first.
void ValidateRingMesh(const Params& p) {
  if (p.particle_mesh.kind != ParticleMeshKind::kRing || p.particles.empty()) return;
  std::size_t smallest = 0;
  for (std::size_t i = 1; i < p.particles.size(); ++i) {
    if (p.particles[i].diameter < p.particles[smallest].diameter) smallest = i;
  }
  const double radius = p.particles[smallest].Radius();
  const double h_p = p.particle_mesh.RingMeshSize(p.domain.h);
  if (h_p > radius) {
    throw InvalidParameter("particle_mesh.h", ExactText(h_p),
                           "at most the radius of the smallest particle, " + ExactText(radius) +
                               " (particles." + std::to_string(smallest) +
                               "): a coarser ring mesh does not resolve the disk");
  }
}

// accuracy.strict: the first setting outside the accuracy envelope rejects the scene, naming the
// key to change and a value inside the bound (the same warning a non-strict run logs).
void ValidateAccuracy(const Params& p) {
  if (!p.accuracy.strict) return;
  const std::vector<AccuracyWarning> warnings = AccuracyWarnings(p);
  if (warnings.empty()) return;
  const AccuracyWarning& w = warnings.front();
  throw InvalidParameter(w.key, w.current,
                         "a value inside the accuracy envelope, e.g. " + w.suggested + " (" +
                             w.setting + " = " + ShortText(w.value) + ", allowed " + w.allowed +
                             ", " + w.source + "; accuracy.strict = true)");
}

// The checks of a scene whose absent members are resolved (ResolveDefaults).
void ValidateResolved(const Params& params) {
  ValidateDomain(params);
  ValidateFluid(params);
  ValidateTimeStepping(params);
  scene::RequireSectionKeys(params, "solvers");
  ValidateMeshCollisionsConformation(params);
  ValidateParticleRangesAndMeshes(params);
  const Grid grid = params.domain.VelocityGrid();
  ValidateParticles(params, grid);
  ValidateRingMesh(params);
  ValidateInflowStates(params, grid);
  ValidateAccuracy(params);
}

}  // namespace

void ValidateTimeStepping(const Params& params) {
  scene::RequireSectionKeys(params, "time");
  ValidateTimeSteps(params.time);
  scene::RequireSectionKeys(params, "splitting");
  ValidateSplitting(params.splitting, !params.particles.empty());
  scene::RequireSectionKeys(params, "output");
  ValidateOutputPeriods(params.time, params.output);
}

void ValidateScene(const Params& params) {
  Params resolved = params;  // Params built in code is checked as the scene it runs as
  ResolveDefaults(resolved);
  ValidateResolved(resolved);
}

}  // namespace dlmfd
