// Collocation multiplier points of one particle: points on its true boundary plus interior points,
// the multiplier space of the sharp-boundary variant of the DLM step (37) (particle-coupling.md
// section 3; Glowinski, Pan, Hesla, Joseph, Periaux 2001, section 5; Wachs's PeliGRIFF; the
// Basilisk DLMFD of Selcuk, Ghigo and Wachs), for a particle of any shape (particles/shape.h).
//
// Boundary points: N_b = floor(P / (c h)) points equally spaced in arc length on the boundary of
// perimeter P (h the fluid mesh size, c = particle_mesh.spacing; at least 3), the first at (a, 0)
// of the body frame (a disk: floor(2 pi R / (c h)) points at angles 2 pi k / N_b). Interior points
// lie inside the shape at a distance >= d_c = sqrt(2) h (PeliGRIFF's choice) from every boundary
// point, so that no interior constraint nearly
// repeats a boundary one:
// - a disk: the nodes of the square lattice of spacing h through the centre (on a disk centred on a
//   fluid node they are fluid nodes);
// - a shape that turns with its particle (an ellipse): the candidates of the square lattice of
//   spacing h / 4 through the centre (kTurningCandidatesPerCell), taken nearest the boundary first
//   (by -SignedDistance, ties in lattice order), each kept when it is at least s_i h from every
//   interior point kept before, s_i = kTurningInteriorSpacing (sqrt 2, a hair above). Why: these
//   points turn with the body against the fixed grid. A lattice of spacing h turned by theta puts
//   two points in one grid cell at some angles (every cell along a row at 45 degrees) and leaves
//   others empty; two points whose P1 stencils nearly coincide make E E^T nearly singular, so the
//   multiplier CG of (37) took up to 70 iterations a step against a disk's 4-7, and found large
//   multipliers of opposite sign at such pairs (|nu| up to 115 at 45 degrees against 1.6 at 0),
//   which the lagged multiplier (splitting.constraint = "incremental") then spread at positions
//   where they no longer cancel, and blew up. Points at least sqrt(2) h apart can never share a
//   cell (a cell's diagonal), at any angle; taking them from the boundary inward (layers that
//   follow the boundary, not a lattice that can align with the grid) keeps the interior covered:
//   7-9 CG iterations at every angle and sub-grid position tried, |nu| <= 1.9, and the lagged
//   multiplier completes every run of its blow-up study (so scene/auto_coupling.h gives a turning
//   particle the lagged multiplier, as a disk); the price, Jeffery's quarter period at r = 2 up to
//   0.6 % further from T / 4 than with the lattice at h = 1/32 and 1/48 (the worst of three
//   positions: 2.40 against 1.96 %, 1.02 against 0.45 %; nearer at 1/64), and at r = 4, b / h =
//   2.4, 1.8 % further at the node (docs/evidence/validation_particles.md, "An ellipse's interior
//   points: a set that cannot pair up in a cell", "Over grids and sub-grid positions"). Thinning
//   the turned lattice to one point per cell is not enough (33 iterations at 45 degrees): near
//   pairs across a cell edge are as bad. A disk keeps its lattice (it does not turn; a disk with
//   these points takes 9 iterations at every position against 7-53, not switched: it would change
//   every disk result).
// Points are stored relative to the centre in the body frame, boundary points first; they
// translate with the particle and turn with it when its shape does (particles/multiplier_points.h).
// Interpolation (read by the
// coupling operator E): boundary points by the chosen rule (particle_mesh.interpolation:
// quadratic, the P2 basis of the 2h macro-triangle, or linear, P1 on the h-triangle), interior
// points by P1 (the velocity there is rigid, which P1 reproduces). Product of the multiplier space:
// Euclidean, <a, b> = a . b (the multipliers are point forces). Not supported: switching off
// boundary points near walls or other bodies (the method note's option; every point stays active,
// the collisions keep the gap).
#pragma once

#include <vector>

#include "dlmfd/core/params.h"
#include "dlmfd/particles/shape.h"

namespace dlmfd {

// The allowed boundary spacings c (particle_mesh.spacing, in units of h): below 1/2 two boundary
// points share most of their P2 stencil and E E^T nears singular; above 4 the fluid leaks between
// the points (the method note's range is 1 to 2).
inline constexpr double kMinCollocationSpacing = 0.5;
inline constexpr double kMaxCollocationSpacing = 4.0;
// The interior points of a shape that turns: the least distance between two of them, in units of h
// (sqrt 2 times 1 + 1e-9, so that round-off never keeps two points exactly a cell's diagonal
// apart), and the candidates' lattice, kTurningCandidatesPerCell points to a cell side.
inline constexpr double kTurningInteriorSpacing = 1.4142135623730951 * (1.0 + 1e-9);
inline constexpr int kTurningCandidatesPerCell = 4;

class CollocationPoints {
 public:
  // Throws InvalidParameter when fluid_h or spacing is not > 0.
  CollocationPoints(const Shape& shape, double fluid_h, double spacing,
                    BoundaryInterpolation boundary);

  const Shape& shape() const { return shape_; }
  int Count() const { return static_cast<int>(points_.size()); }
  int BoundaryCount() const { return boundary_count_; }
  // Point positions relative to the centre in the body frame, the BoundaryCount() boundary points
  // first.
  const std::vector<Vec2>& points() const { return points_; }
  // The outward unit normals at the boundary points (body frame).
  const std::vector<Vec2>& normals() const { return normals_; }
  // True when point k is evaluated by the quadratic (P2 macro-triangle) stencil.
  bool Quadratic(int k) const { return k < boundary_count_ && quadratic_boundary_; }

 private:
  Shape shape_;
  int boundary_count_ = 0;
  bool quadratic_boundary_ = true;
  std::vector<Vec2> points_;
  std::vector<Vec2> normals_;
};

// N_b for a particle of this shape: floor(P / (c h)), at least 3.
int CollocationBoundaryCount(const Shape& shape, double fluid_h, double spacing);

}  // namespace dlmfd
