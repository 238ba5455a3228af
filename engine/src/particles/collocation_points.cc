// Collocation multiplier points of a particle; see particles/collocation_points.h.
#include "dlmfd/particles/collocation_points.h"

#include <cmath>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"

namespace dlmfd {

int CollocationBoundaryCount(const Shape& shape, double fluid_h, double spacing) {
  return shape.BoundaryPointCount(spacing * fluid_h);
}

CollocationPoints::CollocationPoints(const Shape& shape, double fluid_h, double spacing,
                                     BoundaryInterpolation boundary)
    : shape_(shape),
      quadratic_boundary_(boundary != BoundaryInterpolation::kLinear) {
  if (!(fluid_h > 0.0)) throw InvalidParameter("domain.h", ExactText(fluid_h), "> 0");
  if (!(spacing > 0.0)) {
    throw InvalidParameter("particle_mesh.spacing", ExactText(spacing), "> 0");
  }
  boundary_count_ = CollocationBoundaryCount(shape, fluid_h, spacing);
  for (const BoundaryPoint& b : shape.BoundaryPoints(boundary_count_)) {
    points_.push_back(b.position);
    normals_.push_back(b.normal);
  }
  const double exclusion = std::sqrt(2.0) * fluid_h;  // d_c
  const int reach = static_cast<int>(std::ceil(shape.BoundingRadius() / fluid_h));
  for (int b = -reach; b <= reach; ++b) {
    for (int a = -reach; a <= reach; ++a) {
      const Vec2 r(a * fluid_h, b * fluid_h);
      if (!shape.Inside(r)) continue;
      bool clear = true;
      for (int k = 0; k < boundary_count_ && clear; ++k) {
        clear = (r - points_[k]).norm() >= exclusion;
      }
      if (clear) points_.push_back(r);
    }
  }
}

}  // namespace dlmfd
