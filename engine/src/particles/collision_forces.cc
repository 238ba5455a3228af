// Collision forces (14)-(15) with cell lists; see particles/collision_forces.h.
#include "dlmfd/particles/collision_forces.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace dlmfd {
namespace {

// The z component of r x f.
double Cross(const Vec2& r, const Vec2& f) { return r.x() * f.y() - r.y() * f.x(); }

}  // namespace

CollisionForces::CollisionForces(const Params& params, const Grid& grid, std::vector<double> radii)
    : grid_(grid),
      periodic_x_(params.domain.PeriodicX()),
      periodic_y_(params.domain.PeriodicY()),
      range_(params.collisions.range * grid.h),
      inv_eps_p_(1.0 / params.collisions.particle_stiffness),
      inv_eps_w_(1.0 / params.collisions.wall_stiffness),
      radii_(std::move(radii)) {
  wall_[static_cast<int>(Side::kLeft)] = wall_[static_cast<int>(Side::kRight)] = !periodic_x_;
  wall_[static_cast<int>(Side::kBottom)] = wall_[static_cast<int>(Side::kTop)] = !periodic_y_;
  double r_max = 0.0;
  for (double r : radii_) r_max = std::max(r_max, r);
  cell_size_ = 2.0 * r_max + range_;
  cells_x_ = std::max(1, static_cast<int>(std::floor(grid.Width() / cell_size_)));
  cells_y_ = std::max(1, static_cast<int>(std::floor(grid.Height() / cell_size_)));
  cell_w_ = grid.Width() / cells_x_;
  cell_h_ = grid.Height() / cells_y_;
  head_.assign(std::size_t(cells_x_) * std::size_t(cells_y_), -1);
  neighbour_start_.assign(head_.size() + 1, 0);
  int cells[9];
  for (int cy = 0; cy < cells_y_; ++cy) {
    for (int cx = 0; cx < cells_x_; ++cx) {
      const int count = NeighbourCells(cx, cy, cells);
      neighbours_.insert(neighbours_.end(), cells, cells + count);
      neighbour_start_[cy * cells_x_ + cx + 1] = static_cast<int>(neighbours_.size());
    }
  }
  next_.assign(radii_.size(), -1);
  torques_.assign(radii_.size(), 0.0);
}

void CollisionForces::SetShapes(const std::vector<Shape>& shapes) {
  shapes_ = shapes;
  any_shape_ = false;
  area_radius_.clear();
  for (const Shape& shape : shapes_) {
    any_shape_ = any_shape_ || !shape.IsDisk();
    area_radius_.push_back(std::sqrt(shape.SemiAxes().x() * shape.SemiAxes().y()));
  }
}

void CollisionForces::AddShapedPair(int i, int j, const std::vector<Vec2>& positions,
                                    const Vec2& delta, std::vector<Vec2>& forces, int& contacts) {
  const Contact c = PairOf(i, j, positions, delta);
  if (!(c.gap < range_)) return;
  const double g = c.gap;
  const Vec2 f =
      inv_eps_p_ * (area_radius_[i] + area_radius_[j] + g) * (range_ - g) * (range_ - g) * c.normal;
  const Vec2 at = 0.5 * (c.point_a + c.point_b);
  forces[i] += f;
  forces[j] -= f;
  torques_[i] += Cross(at - positions[i], f);
  torques_[j] -= Cross(at - (positions[i] - delta), f);
  ++contacts;
}

void CollisionForces::AddShapedWall(int i, const Vec2& x, const Vec2& inward, double dist,
                                    std::vector<Vec2>& forces, int& contacts) {
  const Contact c = WallContact(Placed(i, x), inward, dist);
  if (!(2.0 * c.gap < range_)) return;
  const double g = c.gap;
  const Vec2 f =
      inv_eps_w_ * 2.0 * (area_radius_[i] + g) * (range_ - 2.0 * g) * (range_ - 2.0 * g) * inward;
  forces[i] += f;
  torques_[i] += Cross(c.point_a - x, f);
  ++contacts;
}

Vec2 CollisionForces::MinimumImage(Vec2 delta) const {
  if (periodic_x_) delta.x() -= grid_.Width() * std::round(delta.x() / grid_.Width());
  if (periodic_y_) delta.y() -= grid_.Height() * std::round(delta.y() / grid_.Height());
  return delta;
}

int CollisionForces::CellOf(const Vec2& x) const {
  auto index = [](double s, double width, int count, bool periodic) {
    int c = static_cast<int>(std::floor(s / width));
    if (periodic) return ((c % count) + count) % count;
    return std::min(std::max(c, 0), count - 1);
  };
  const int cx = index(x.x() - grid_.x0, cell_w_, cells_x_, periodic_x_);
  const int cy = index(x.y() - grid_.y0, cell_h_, cells_y_, periodic_y_);
  return cy * cells_x_ + cx;
}

void CollisionForces::BuildCells(const std::vector<Vec2>& positions) {
  std::fill(head_.begin(), head_.end(), -1);
  // Insert in reverse so each list runs in increasing particle index.
  for (int i = static_cast<int>(positions.size()) - 1; i >= 0; --i) {
    const int c = CellOf(positions[i]);
    next_[i] = head_[c];
    head_[c] = i;
  }
}

int CollisionForces::NeighbourCells(int cx, int cy, int* cells) const {
  int count = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    int ny = cy + dy;
    if (periodic_y_) {
      ny = (ny + cells_y_) % cells_y_;
    } else if (ny < 0 || ny >= cells_y_) {
      continue;
    }
    for (int dx = -1; dx <= 1; ++dx) {
      int nx = cx + dx;
      if (periodic_x_) {
        nx = (nx + cells_x_) % cells_x_;
      } else if (nx < 0 || nx >= cells_x_) {
        continue;
      }
      const int c = ny * cells_x_ + nx;
      // With fewer than 3 periodic cells the same cell appears twice: keep it once.
      if (std::find(cells, cells + count, c) == cells + count) cells[count++] = c;
    }
  }
  return count;
}

int CollisionForces::RingCount() const {
  const int x = periodic_x_ ? cells_x_ / 2 : cells_x_ - 1;
  const int y = periodic_y_ ? cells_y_ / 2 : cells_y_ - 1;
  return std::max(x, y);
}

int CollisionForces::Compute(const std::vector<Vec2>& positions, std::vector<Vec2>& forces) {
  const std::size_t n = positions.size();
  for (std::size_t i = 0; i < n; ++i) forces[i].setZero();
  std::fill(torques_.begin(), torques_.end(), 0.0);
  int contacts = 0;
  ForEachNearPair(positions, [&](int i, int j, const Vec2& delta) {
    const double reach = radii_[i] + radii_[j] + range_;
    const double d = delta.norm();
    if (d < reach && (Shaped(i) || Shaped(j))) {
      AddShapedPair(i, j, positions, delta, forces, contacts);  // bounding circles within reach
    } else if (d < reach) {
      const Vec2 f = inv_eps_p_ * (reach - d) * (reach - d) * delta;
      forces[i] += f;
      forces[j] -= f;
      ++contacts;
    }
  });
  for (std::size_t i = 0; i < n; ++i) {
    const double reach = 2.0 * radii_[i] + range_;
    const Vec2& x = positions[i];
    // Distances to the sides and the outward direction of each image.
    const double dist[4] = {x.x() - grid_.x0, grid_.x0 + grid_.Width() - x.x(), x.y() - grid_.y0,
                            grid_.y0 + grid_.Height() - x.y()};
    const Vec2 away[4] = {Vec2(1, 0), Vec2(-1, 0), Vec2(0, 1), Vec2(0, -1)};
    for (int s = 0; s < 4; ++s) {
      if (!wall_[s]) continue;
      if (Shaped(static_cast<int>(i))) {
        AddShapedWall(static_cast<int>(i), x, away[s], dist[s], forces, contacts);
        continue;
      }
      const double d = 2.0 * dist[s];  // centre to mirror image
      if (d < reach) {
        forces[i] += inv_eps_w_ * (reach - d) * (reach - d) * d * away[s];
        ++contacts;
      }
    }
  }
  return contacts;
}

double CollisionForces::SurfaceGaps::Min() const {
  if (std::isnan(pair)) return wall;
  if (std::isnan(wall)) return pair;
  return std::min(pair, wall);
}

CollisionForces::SurfaceGaps CollisionForces::Gaps(const std::vector<Vec2>& positions) {
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  SurfaceGaps gaps;
  gaps.pair = gaps.wall = kNone;
  const std::size_t n = positions.size();
  auto consider = [&](int i, int j, const Vec2& delta) {
    double g = delta.norm() - radii_[i] - radii_[j];
    // Another shape: its proper distance where the bounding circles come near (< one cell).
    if ((Shaped(i) || Shaped(j)) && g < cell_size_) g = PairOf(i, j, positions, delta).gap;
    if (std::isnan(gaps.pair) || g < gaps.pair) {
      gaps.pair = g;
      gaps.first = i;
      gaps.second = j;
    }
  };
  ForEachNearPair(positions, consider);
  // A pair whose cells lie k apart has d >= (k - 1) min(cell_w_, cell_h_) >= (k - 1) CellSize(),
  // so its gap is at least that less 2 R_max: the rings go on until that reaches the nearest gap.
  double r_max = 0.0;
  for (double r : radii_) r_max = std::max(r_max, r);
  const double cell = std::min(cell_w_, cell_h_);
  const int rings = n >= 2 ? RingCount() : 0;
  for (int k = 2; k <= rings && !(gaps.pair <= (k - 1) * cell - 2.0 * r_max); ++k) {
    ForEachPairInRing(positions, k, consider);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& x = positions[i];
    const double dist[4] = {x.x() - grid_.x0, grid_.x0 + grid_.Width() - x.x(), x.y() - grid_.y0,
                            grid_.y0 + grid_.Height() - x.y()};
    const Vec2 away[4] = {Vec2(1, 0), Vec2(-1, 0), Vec2(0, 1), Vec2(0, -1)};
    for (int s = 0; s < 4; ++s) {
      if (!wall_[s]) continue;
      const double g = Shaped(static_cast<int>(i))
                           ? WallContact(Placed(static_cast<int>(i), x), away[s], dist[s]).gap
                           : dist[s] - radii_[i];
      if (std::isnan(gaps.wall) || g < gaps.wall) {
        gaps.wall = g;
        gaps.wall_particle = static_cast<int>(i);
        gaps.wall_side = s;
      }
    }
  }
  return gaps;
}

void CollisionForces::SurfaceGaps::Closest(int* first_out, int* second_out) const {
  const bool wall_closer = std::isnan(pair) || wall < pair;
  if (first_out) *first_out = wall_closer ? wall_particle : first;
  if (second_out) *second_out = wall_closer ? (wall_side >= 0 ? -1 - wall_side : -10) : second;
}

double CollisionForces::MinGap(const std::vector<Vec2>& positions, int* first, int* second) {
  const SurfaceGaps gaps = Gaps(positions);
  gaps.Closest(first, second);
  return gaps.Min();
}

}  // namespace dlmfd
