#include "dlmfd/fluid/boundary_data.h"

#include <algorithm>
#include <cmath>

namespace dlmfd {
namespace {

bool IsDirichletSide(const BoundarySide& side) {
  return side.type == SideType::kWall || side.type == SideType::kVelocity;
}

// The side's velocity at arc-length fraction s in [0, 1].
Vec2 SideVelocity(const BoundarySide& side, double s) {
  if (side.type != SideType::kVelocity) return Vec2::Zero();
  if (side.profile == Profile::kUniform) return side.value;
  return 4.0 * s * (1.0 - s) * side.max;
}

}  // namespace

BoundaryData::BoundaryData(const Grid& grid, const DomainParams& domain) {
  const int nx = grid.nx, ny = grid.ny;
  std::vector<bool> owned(grid.NodeCount(), false);
  std::vector<Vec2> value(grid.NodeCount(), Vec2::Zero());
  // Left/right first, bottom/top second. At a corner of two Dirichlet sides each side keeps the
  // component normal to itself: x from the left/right side, y from the bottom/top side.
  const Side order[4] = {Side::kLeft, Side::kRight, Side::kBottom, Side::kTop};
  for (Side s : order) {
    const BoundarySide& side = domain.side(s);
    if (!IsDirichletSide(side)) continue;
    const bool vertical = (s == Side::kLeft || s == Side::kRight);
    const int count = vertical ? ny : nx;
    for (int k = 0; k <= count; ++k) {
      const int i = vertical ? (s == Side::kLeft ? 0 : nx) : k;
      const int j = vertical ? k : (s == Side::kBottom ? 0 : ny);
      const std::size_t id = grid.Index(i, j);
      // Exact fraction k / count so that mid-side and both ends are hit exactly.
      const Vec2 data = SideVelocity(side, static_cast<double>(k) / count);
      if (!vertical && owned[id]) {
        value[id].y() = data.y();  // a corner: the x component stays the vertical side's
      } else {
        value[id] = data;
      }
      owned[id] = true;
    }
  }
  for (std::size_t id = 0; id < owned.size(); ++id) {
    if (!owned[id]) continue;
    nodes_.push_back(id);
    u_.push_back(value[id].x());
    v_.push_back(value[id].y());
    max_speed_ = std::max(max_speed_, value[id].norm());
  }
}

void BoundaryData::Apply(double* u, double* v) const {
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    u[nodes_[k]] = u_[k];
    v[nodes_[k]] = v_[k];
  }
}

}  // namespace dlmfd
