// Collocation multiplier points of a disk; see particles/collocation_points.h.
#include "dlmfd/particles/collocation_points.h"

#include <algorithm>
#include <cmath>

#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"

namespace dlmfd {

int CollocationBoundaryCount(double radius, double fluid_h, double spacing) {
  // 1e-9 guards 2 pi R / (c h) = 41.99999999 from losing a point to round-off.
  return std::max(3, static_cast<int>(std::floor(2.0 * kPi * radius / (spacing * fluid_h) + 1e-9)));
}

CollocationPoints::CollocationPoints(double radius, double fluid_h, double spacing,
                                     BoundaryInterpolation boundary)
    : radius_(radius),
      quadratic_boundary_(boundary != BoundaryInterpolation::kLinear) {
  if (!(radius > 0.0)) throw InvalidParameter("particles.diameter", ExactText(2 * radius), "> 0");
  if (!(fluid_h > 0.0)) throw InvalidParameter("domain.h", ExactText(fluid_h), "> 0");
  if (!(spacing > 0.0)) {
    throw InvalidParameter("particle_mesh.spacing", ExactText(spacing), "> 0");
  }
  boundary_count_ = CollocationBoundaryCount(radius, fluid_h, spacing);
  for (int k = 0; k < boundary_count_; ++k) {
    const double angle = 2.0 * kPi * k / boundary_count_;
    points_.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  const double exclusion = std::sqrt(2.0) * fluid_h;  // d_c
  const int reach = static_cast<int>(std::ceil(radius / fluid_h));
  for (int b = -reach; b <= reach; ++b) {
    for (int a = -reach; a <= reach; ++a) {
      const Vec2 r(a * fluid_h, b * fluid_h);
      if (r.norm() >= radius) continue;
      bool clear = true;
      for (int k = 0; k < boundary_count_ && clear; ++k) {
        clear = (r - points_[k]).norm() >= exclusion;
      }
      if (clear) points_.push_back(r);
    }
  }
}

}  // namespace dlmfd
