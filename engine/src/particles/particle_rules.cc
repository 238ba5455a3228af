#include "dlmfd/particles/particle_rules.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"
#include "dlmfd/core/param_words.h"
#include "dlmfd/particles/shape.h"

namespace dlmfd {
namespace {

// Distance between two centres; the nearest periodic image along periodic directions.
double CenterDistance(const DomainParams& d, const Vec2& a, const Vec2& b) {
  Vec2 delta = a - b;
  if (d.PeriodicX()) delta.x() -= d.size.x() * std::round(delta.x() / d.size.x());
  if (d.PeriodicY()) delta.y() -= d.size.y() * std::round(delta.y() / d.size.y());
  return delta.norm();
}

void RequireInside(const DomainParams& d, std::size_t p, const ParticleParams& q) {
  const double r = q.Radius();
  const bool periodic[2] = {d.PeriodicX(), d.PeriodicY()};
  for (int k = 0; k < 2; ++k) {
    const double c = q.center[k];
    const double lo = periodic[k] ? 0.0 : r;
    const double hi = periodic[k] ? d.size[k] : d.size[k] - r;
    if (!(c >= lo && c <= hi)) {
      const char* crossed = k == 0 ? (c < lo ? "left" : "right") : (c < lo ? "bottom" : "top");
      throw InvalidParameter("particles." + std::to_string(p) + ".center", VecText(q.center),
                             std::string("a disk that does not cross the ") + crossed +
                                 " side: a centre with " + (k == 0 ? "x" : "y") + " in [" +
                                 ExactText(lo) + ", " + ExactText(hi) + "] (the disk of radius " +
                                 ExactText(r) + " inside the domain [0, " + ExactText(d.size.x()) +
                                 "] x [0, " + ExactText(d.size.y()) +
                                 "]; it may cross periodic sides only)");
    }
  }
}

void RequireApart(const Params& params) {
  for (std::size_t j = 1; j < params.particles.size(); ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      const ParticleParams& a = params.particles[i];
      const ParticleParams& b = params.particles[j];
      const double gap =
          CenterDistance(params.domain, a.center, b.center) - a.Radius() - b.Radius();
      if (gap < 0.0) {
        throw InvalidParameter("particles." + std::to_string(j) + ".center", VecText(b.center),
                               "a disk that does not overlap particle " + std::to_string(i) +
                                   " at t = 0 (gap " + ShortText(gap) + " between particles " +
                                   std::to_string(i) + " and " + std::to_string(j) + ")");
      }
    }
  }
}

}  // namespace

void RequireNotLighterThanLiquid(const Params& params, std::size_t p) {
  const ParticleParams& q = params.particles[p];
  const double rho = params.fluid.density;
  if (q.motion != Motion::kFree || q.density == rho) return;
  const double excess_mass = Shape::Of(q).Mass(q.density - rho);
  if (q.density > rho && !(excess_mass > 0.0)) {
    throw InvalidParameter("particles." + std::to_string(p) + ".diameter", ExactText(q.diameter),
                           "a diameter whose excess mass (rho_d - rho_L) pi R^2 is a positive "
                           "double (here it underflows to 0)");
  }
  if (!(excess_mass > 0.0)) {
    throw InvalidParameter(
        "particles." + std::to_string(p) + ".density", ExactText(q.density),
        ">= fluid.density = " + ExactText(rho) +
            " for a free particle (a light disk makes the excess mass (rho_d - rho_L) V "
            "of (36)-(38) negative and the multiplier problem (37) indefinite)");
  }
}

void RequireRingMeshShape(const Shape& shape, std::size_t p) {
  if (shape.IsDisk()) return;
  throw InvalidParameter("particle_mesh.kind", "\"ring\"",
                         "\"collocation\" with non-circular particles (particle " +
                             std::to_string(p) +
                             " is an ellipse; the paper's ring mesh is built on disks only)");
}

void RequireIndexableGrid(const Params& params, const Grid& grid) {
  if (grid.NodeCount() > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidParameter("domain.h", ExactText(params.domain.h),
                           "a grid of at most 2^32 - 1 velocity nodes (32-bit node indices of E)");
  }
}

void RequireCoupledInStokes(const Params& params, std::size_t p) {
  const ParticleParams& q = params.particles[p];
  if (params.splitting.constraint.value() != ConstraintCoupling::kViscous ||
      q.motion != Motion::kFree || q.density != params.fluid.density) {
    return;
  }
  throw InvalidParameter(
      "particles." + std::to_string(p) + ".density", ExactText(q.density),
      "a density != fluid.density = " + ExactText(params.fluid.density) +
          " with splitting.constraint = \"viscous\" (a neutrally buoyant free particle has no "
          "excess mass to carry its velocity through the Stokes step (33)), or "
          "splitting.constraint = \"paper\"");
}

std::optional<InvalidParameter> CutCellObstacle(const Params& params) {
  const std::string with = " with particle_mesh.kind = \"cut_cell\"";
  for (std::size_t p = 0; p < params.particles.size(); ++p) {
    const ParticleParams& q = params.particles[p];
    if (q.shape == ShapeKind::kDisk || q.motion == Motion::kFixed) continue;
    if (params.fluid.IsNewtonian()) {
      // A moving ellipse's tip: its radius of curvature b^2 / a in cells (header).
      const double a = std::max(q.semi_axes.x(), q.semi_axes.y());
      const double b = std::min(q.semi_axes.x(), q.semi_axes.y());
      const double most_h = b * b / (a * kMovingEllipseTipCells);
      if (params.domain.h <= most_h * (1.0 + 1e-12)) continue;
      return InvalidParameter("domain.h", ExactText(params.domain.h),
                              "at most " + ExactText(most_h) + with + " (particles." +
                                  std::to_string(p) +
                                  ", a moving ellipse: its tip's radius of curvature b^2 / a at "
                                  "least " +
                                  ExactText(kMovingEllipseTipCells) +
                                  " h; thinner tips made a step fail), or "
                                  "particle_mesh.kind = \"collocation\"");
    }
    return InvalidParameter("particles." + std::to_string(p) + ".shape",
                            "\"" + std::string(WordOf(q.shape)) + "\"",
                            "\"disk\"" + with +
                                " for a particle that moves in a polymer liquid (cut cells were "
                                "measured on moving ellipses in a Newtonian liquid only), or "
                                "particle_mesh.kind = \"collocation\"");
  }
  if (params.splitting.beta != 0.0) {
    return InvalidParameter("splitting.beta", ExactText(params.splitting.beta),
                            "0 (and splitting.alpha = 1)" + with +
                                ": the advection step (34) does not see the bodies, so viscosity "
                                "there would leak through them");
  }
  if (params.domain.flow_rate) {
    return InvalidParameter("domain.flow_rate", ExactText(*params.domain.flow_rate),
                            "absent" + with +
                                " (the cut-cell step has no flux control yet: drive the flow by "
                                "fluid.body_force), or particle_mesh.kind = \"collocation\"");
  }
  return std::nullopt;
}

void RequireCutCellScene(const Params& params) {
  if (params.particle_mesh.kind != ParticleMeshKind::kCutCell || params.particles.empty()) return;
  if (std::optional<InvalidParameter> obstacle = CutCellObstacle(params)) throw *obstacle;
}

void ValidateParticles(const Params& params, const Grid& grid) {
  if (params.particles.empty()) return;
  RequireIndexableGrid(params, grid);
  RequireCutCellScene(params);
  // Cut cells have no multiplier: a free body of any density (particles/cut_cell_free_bodies.h).
  const bool multipliers = params.particle_mesh.kind != ParticleMeshKind::kCutCell;
  for (std::size_t p = 0; p < params.particles.size(); ++p) {
    if (multipliers) {
      RequireNotLighterThanLiquid(params, p);
      RequireCoupledInStokes(params, p);
    }
    if (params.particle_mesh.kind == ParticleMeshKind::kRing) {
      RequireRingMeshShape(Shape::Of(params.particles[p]), p);
    }
    RequireInside(params.domain, p, params.particles[p]);
  }
  RequireApart(params);
}

}  // namespace dlmfd
