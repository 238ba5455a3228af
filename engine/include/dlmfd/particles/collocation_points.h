// Collocation multiplier points of one disk: points on the true circle plus interior points, the
// multiplier space of the sharp-boundary variant of the DLM step (37) (particle-coupling.md
// section 3; Glowinski, Pan, Hesla, Joseph, Periaux 2001, section 5; Wachs's PeliGRIFF; the
// Basilisk DLMFD of Selcuk, Ghigo and Wachs).
//
// Boundary points: N_b = floor(2 pi R / (c h)) equally spaced on the circle of radius R (h the
// fluid mesh size, c = particle_mesh.spacing; at least 3), the first at angle 0. Interior points:
// the nodes of the square lattice of spacing h through the centre (the particle frame; on a disk
// centred on a fluid node they are fluid nodes) that lie inside the circle at a distance >= d_c =
// sqrt(2) h (PeliGRIFF's choice) from every boundary point, so that no interior constraint nearly
// repeats a boundary one. Points are stored relative to the centre, boundary points first; the set
// translates with the particle and does not rotate. Interpolation (read by the coupling operator
// E): boundary points by the chosen rule (particle_mesh.interpolation: quadratic, the P2 basis of
// the 2h macro-triangle, or linear, P1 on the h-triangle), interior points by P1 (the velocity
// there is rigid, which P1 reproduces). Product of the multiplier space: Euclidean, <a, b> = a . b
// (the multipliers are point forces). Not supported: non-circular particles; switching off boundary
// points near walls or other bodies (the method note's option; every point stays active, the
// collisions keep the gap).
#pragma once

#include <vector>

#include "dlmfd/core/params.h"

namespace dlmfd {

// The allowed boundary spacings c (particle_mesh.spacing, in units of h): below 1/2 two boundary
// points share most of their P2 stencil and E E^T nears singular; above 4 the fluid leaks between
// the points (the method note's range is 1 to 2).
inline constexpr double kMinCollocationSpacing = 0.5;
inline constexpr double kMaxCollocationSpacing = 4.0;

class CollocationPoints {
 public:
  // Throws InvalidParameter when radius, fluid_h or spacing is not > 0.
  CollocationPoints(double radius, double fluid_h, double spacing, BoundaryInterpolation boundary);

  double radius() const { return radius_; }
  int Count() const { return static_cast<int>(points_.size()); }
  int BoundaryCount() const { return boundary_count_; }
  // Point positions relative to the centre, the BoundaryCount() boundary points first.
  const std::vector<Vec2>& points() const { return points_; }
  // True when point k is evaluated by the quadratic (P2 macro-triangle) stencil.
  bool Quadratic(int k) const { return k < boundary_count_ && quadratic_boundary_; }

 private:
  double radius_;
  int boundary_count_ = 0;
  bool quadratic_boundary_ = true;
  std::vector<Vec2> points_;
};

// N_b for a disk of this radius: floor(2 pi R / (c h)), at least 3.
int CollocationBoundaryCount(double radius, double fluid_h, double spacing);

}  // namespace dlmfd
