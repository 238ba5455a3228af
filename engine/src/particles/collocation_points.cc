// Collocation multiplier points of a particle; see particles/collocation_points.h.
#include "dlmfd/particles/collocation_points.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"

namespace dlmfd {
namespace {

// Points kept so far, bucketed in square cells of side `side` about the centre, so that "is any
// kept point within `side` of r" reads the 3 x 3 cells around r's.
class PointBuckets {
 public:
  PointBuckets(double reach, double side)
      : side_(side),
        half_(static_cast<int>(std::ceil(reach / side)) + 1),
        cells_(static_cast<std::size_t>(2 * half_ + 1) * (2 * half_ + 1)) {}

  void Add(const Vec2& r) { cells_[Index(Cell(r.x()), Cell(r.y()))].push_back(r); }

  // Whether a stored point lies closer than `distance` (<= side) to r.
  bool AnyCloserThan(const Vec2& r, double distance) const {
    const int i = Cell(r.x()), j = Cell(r.y());
    for (int b = std::max(j - 1, -half_); b <= std::min(j + 1, half_); ++b) {
      for (int a = std::max(i - 1, -half_); a <= std::min(i + 1, half_); ++a) {
        for (const Vec2& q : cells_[Index(a, b)]) {
          if ((r - q).norm() < distance) return true;
        }
      }
    }
    return false;
  }

 private:
  int Cell(double x) const {
    return std::clamp(static_cast<int>(std::floor(x / side_ + 0.5)), -half_, half_);
  }
  std::size_t Index(int a, int b) const {
    return static_cast<std::size_t>(b + half_) * (2 * half_ + 1) + (a + half_);
  }

  double side_;
  int half_;
  std::vector<std::vector<Vec2>> cells_;
};

}  // namespace

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
  const double interior = kTurningInteriorSpacing * fluid_h;
  const double reach = shape.BoundingRadius();
  PointBuckets boundary_buckets(reach + exclusion, exclusion);
  for (int k = 0; k < boundary_count_; ++k) boundary_buckets.Add(points_[k]);
  // The candidates: the lattice of spacing h (a disk) or h / 4 (a turning shape) through the
  // centre, inside and d_c clear of every boundary point.
  const double step = shape.TurnsWithAngle() ? fluid_h / kTurningCandidatesPerCell : fluid_h;
  const int n = static_cast<int>(std::ceil(reach / step));
  std::vector<std::pair<double, Vec2>> candidates;
  for (int b = -n; b <= n; ++b) {
    for (int a = -n; a <= n; ++a) {
      const Vec2 r(a * step, b * step);
      if (!shape.Inside(r) || boundary_buckets.AnyCloserThan(r, exclusion)) continue;
      if (!shape.TurnsWithAngle()) {
        points_.push_back(r);
        continue;
      }
      candidates.emplace_back(-shape.SignedDistance(r), r);  // the depth below the boundary
    }
  }
  // A turning shape: shallowest first (ties in lattice order), each kept when at least
  // kTurningInteriorSpacing h from every kept interior point.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  PointBuckets kept(reach, interior);
  for (const auto& [depth, r] : candidates) {
    if (kept.AnyCloserThan(r, interior)) continue;
    kept.Add(r);
    points_.push_back(r);
  }
}

}  // namespace dlmfd
