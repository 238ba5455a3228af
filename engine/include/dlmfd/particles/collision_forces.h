// The repulsive collision forces F' of the paper, (14)-(15), with a cell-list neighbour search.
//
// Equations (14)-(15), read as in method notes 2, section 1.7: for d_ij < R_i + R_j + rho,
//   F_ij = (1/eps_p) (X_i - X_j) (R_i + R_j + rho - d_ij)^2      (X_i - X_j not normalised),
// and for every non-periodic side with the mirror image X_i' of X_i across it, d_i = |X_i - X_i'|:
//   F_iw = (1/eps_w) (X_i - X_i') (2 R_i + rho - d_i)^2          for d_i < 2 R_i + rho.
// rho = collisions.range * h; eps_p, eps_w from the scene. Periodic sides wrap (minimum image).
// Particles of other shapes (SetShapes; an ellipse) by the proper distance (contact_distance.h),
// not their bounding circles: with the gap g between the surfaces, the closest points and the
// unit normal n from j to i, the same laws read, for g < rho,
//   F_ij = (1/eps_p) (R_i + R_j + g) (rho - g)^2 n,   F_iw = (1/eps_w) 2 (R_i + g) (rho - 2 g)^2 n,
// with R = sqrt(a b) the radius of the disk of the same area (for two disks R_i + R_j + g = d_ij
// and this is (14); for a disk and a wall 2 (R + g) = d_i and this is (15)), acting at the contact
// point (the midpoint of the closest points; a wall's: the particle's point nearest to it), so a
// force off the centre line carries a torque T_i = (c - X_i) x F_i. Pairs of disks and disks at
// walls keep the paper's arithmetic exactly.
// Discrete method: cell lists with cells of side >= 2 R_max + rho, so only the 3 x 3 neighbouring
// cells can interact: building and sweeping cost O(N). Storage is allocated at construction.
// Not supported: a periodic length shorter than 2 (2 R_max + rho) (a pair would interact through
// two images; only the nearest image is seen). References: Glowinski et al., J. Comput. Phys. 169
// (2001) 363-426, section 4; method notes 2, section 1.7; Allen & Tildesley, Computer Simulation of
// Liquids, cell lists.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/particles/contact_distance.h"
#include "dlmfd/particles/shape.h"

namespace dlmfd {

class CollisionForces {
 public:
  // radii: one per particle, fixed for the run.
  CollisionForces(const Params& params, const Grid& grid, std::vector<double> radii);

  // forces[i] = F'_i (pairs plus walls) at the given centres; returns the number of active
  // contacts.
  int Compute(const std::vector<Vec2>& positions, std::vector<Vec2>& forces);

  // The shapes of the particles (one per particle; all disks when never called), and their angles
  // for the following Compute and Gaps calls.
  void SetShapes(const std::vector<Shape>& shapes);
  void SetAngles(const std::vector<double>& angles) { angles_ = angles; }
  // The torques of the collision forces about each centre in the last Compute (0 for disks).
  const std::vector<double>& Torques() const { return torques_; }

  // The true smallest surface gaps at the given centres (and angles, for other shapes than disks:
  // their proper distance): over every pair, d - R_i - R_j (minimum
  // image across periodic sides), and over every particle and non-periodic side, the distance to
  // the side minus R_i. The cell lists find the closest pair when it is nearer than
  // CellSize() - 2 R_max (no pair outside neighbouring cells can be nearer); otherwise the search
  // goes on ring by ring of cells (cells k apart hold centres at least (k - 1) cells apart) until
  // no farther ring can hold a nearer pair, so the result is never capped and costs O(N) for a
  // bed of N particles spread over the domain (every pair was examined before: 29 M instructions a
  // step for 1,000 disks; docs/evidence/performance.md, "A thousand particles"). A gap with
  // nothing to measure (fewer than two particles, or no wall) is NaN, and its indices are -10.
  struct SurfaceGaps {
    double pair = 0.0;
    int first = -10, second = -10;  // the closest pair
    double wall = 0.0;
    int wall_particle = -10, wall_side = -10;  // the particle closest to a side, and the side
    // The smaller of the two (NaN only when both are).
    double Min() const;
    // The particles of Min(): *first and *second the particle indices (second = -1 - side index
    // for a wall, -10 if there was nothing to measure).
    void Closest(int* first, int* second) const;
  };
  SurfaceGaps Gaps(const std::vector<Vec2>& positions);

  // Gaps(positions).Min(); sets *first and *second as SurfaceGaps::Closest does.
  double MinGap(const std::vector<Vec2>& positions, int* first = nullptr, int* second = nullptr);

  // Visits every unordered pair (i < j) whose centres lie in neighbouring cells (a superset of the
  // pairs closer than CellSize()); visit(i, j, delta) with delta = X_i - X_j (minimum image).
  template <class Visit>
  void ForEachNearPair(const std::vector<Vec2>& positions, Visit&& visit);

  // X_i - X_j with periodic sides wrapped to the nearest image.
  Vec2 MinimumImage(Vec2 delta) const;
  double CellSize() const { return cell_size_; }
  double Range() const { return range_; }

 private:
  // Whether the pair or the particle needs the proper distance (not two disks).
  bool Shaped(int i) const { return any_shape_ && !shapes_[i].IsDisk(); }
  PlacedShape Placed(int i, const Vec2& centre) const {
    return PlacedShape{&shapes_[i], centre, angles_.empty() ? 0.0 : angles_[i]};
  }
  // The contact of i and j (delta = X_i - X_j, minimum image).
  Contact PairOf(int i, int j, const std::vector<Vec2>& positions, const Vec2& delta) const {
    return PairContact(Placed(i, positions[i]), Placed(j, positions[i] - delta));
  }
  // The force and torques of a pair or a wall by the proper distance, added when in range.
  void AddShapedPair(int i, int j, const std::vector<Vec2>& positions, const Vec2& delta,
                     std::vector<Vec2>& forces, int& contacts);
  void AddShapedWall(int i, const Vec2& x, const Vec2& inward, double dist,
                     std::vector<Vec2>& forces, int& contacts);
  int CellOf(const Vec2& x) const;
  void BuildCells(const std::vector<Vec2>& positions);
  // Indices of the distinct neighbouring cells of cell (cx, cy), itself included; returns the
  // count. The constructor lists them once per cell (neighbours_).
  int NeighbourCells(int cx, int cy, int* cells) const;
  // Visits every unordered pair (i < j) whose cells lie k >= 2 cells apart (the larger of the
  // distances in x and in y, wrapped across periodic sides), from the cells of the last
  // BuildCells; visit(i, j, delta) as ForEachNearPair's (a pair may come twice when a periodic
  // ring wraps onto itself).
  template <class Visit>
  void ForEachPairInRing(const std::vector<Vec2>& positions, int k, Visit&& visit);
  // The largest ring k that can hold a pair (every pair lies in some ring 0 .. RingCount()).
  int RingCount() const;

  Grid grid_;
  bool periodic_x_, periodic_y_;
  bool wall_[4];  // indexed by Side: the non-periodic sides repel
  double range_, inv_eps_p_, inv_eps_w_;
  std::vector<double> radii_;
  double cell_size_;
  int cells_x_, cells_y_;
  double cell_w_, cell_h_;
  std::vector<int> head_, next_;  // linked cell lists
  // The distinct neighbouring cells of cell c (NeighbourCells, in its order): neighbours_[k] for k
  // in neighbour_start_[c] .. neighbour_start_[c + 1] - 1, listed once at construction rather than
  // deduplicated on every sweep (85 M instructions over 5 steps of the 1,000-disk bed).
  std::vector<int> neighbour_start_, neighbours_;
  bool any_shape_ = false;  // some particle is not a disk
  std::vector<Shape> shapes_;
  std::vector<double> angles_, torques_, area_radius_;  // per particle; R = sqrt(a b)
};

template <class Visit>
void CollisionForces::ForEachNearPair(const std::vector<Vec2>& positions, Visit&& visit) {
  BuildCells(positions);
  const int cell_count = cells_x_ * cells_y_;
  for (int own = 0; own < cell_count; ++own) {
    if (head_[own] < 0) continue;
    const int* first = neighbours_.data() + neighbour_start_[own];
    const int* last = neighbours_.data() + neighbour_start_[own + 1];
    for (int i = head_[own]; i >= 0; i = next_[i]) {
      for (const int* c = first; c != last; ++c) {
        for (int j = head_[*c]; j >= 0; j = next_[j]) {
          if (j > i) visit(i, j, MinimumImage(positions[i] - positions[j]));
        }
      }
    }
  }
}

template <class Visit>
void CollisionForces::ForEachPairInRing(const std::vector<Vec2>& positions, int k, Visit&& visit) {
  // The ring's cell at (dx, dy) from cell (cx, cy), or -1 off a non-periodic side.
  auto wrap = [](int c, int count, bool periodic) {
    if (periodic) return ((c % count) + count) % count;
    return c >= 0 && c < count ? c : -1;
  };
  auto visit_cell = [&](int own, int cx, int cy) {
    if (cx < 0 || cy < 0) return;
    for (int i = head_[own]; i >= 0; i = next_[i]) {
      for (int j = head_[cy * cells_x_ + cx]; j >= 0; j = next_[j]) {
        if (j > i) visit(i, j, MinimumImage(positions[i] - positions[j]));
      }
    }
  };
  for (int cy = 0; cy < cells_y_; ++cy) {
    for (int cx = 0; cx < cells_x_; ++cx) {
      const int own = cy * cells_x_ + cx;
      if (head_[own] < 0) continue;
      for (int d = -k; d <= k; ++d) {  // the bottom and top rows, then the sides between them
        const int x = wrap(cx + d, cells_x_, periodic_x_);
        visit_cell(own, x, wrap(cy - k, cells_y_, periodic_y_));
        visit_cell(own, x, wrap(cy + k, cells_y_, periodic_y_));
      }
      for (int d = -k + 1; d <= k - 1; ++d) {
        const int y = wrap(cy + d, cells_y_, periodic_y_);
        visit_cell(own, wrap(cx - k, cells_x_, periodic_x_), y);
        visit_cell(own, wrap(cx + k, cells_x_, periodic_x_), y);
      }
    }
  }
}

}  // namespace dlmfd
