#include "dlmfd/fluid/boundary_data.h"

#include <algorithm>
#include <cmath>

#include "dlmfd/fluid/boundary_profile.h"

namespace dlmfd {
namespace {

bool IsDirichletSide(const BoundarySide& side) {
  return side.type == SideType::kWall || side.type == SideType::kVelocity;
}

}  // namespace

BoundaryData::BoundaryData(const Grid& grid, const DomainParams& domain) {
  const int nx = grid.nx, ny = grid.ny;
  std::vector<bool> owned(grid.NodeCount(), false);
  std::vector<Vec2> value(grid.NodeCount(), Vec2::Zero());
  std::vector<unsigned char> x_side(grid.NodeCount(), 0), y_side(grid.NodeCount(), 0);
  // Left/right first, bottom/top second. At a corner of two Dirichlet sides each side keeps the
  // component normal to itself: x from the left/right side, y from the bottom/top side.
  const Side order[4] = {Side::kLeft, Side::kRight, Side::kBottom, Side::kTop};
  for (Side s : order) {
    const BoundarySide& side = domain.side(s);
    sides_[static_cast<int>(s)] = side;
    if (!IsDirichletSide(side)) continue;
    const auto side_index = static_cast<unsigned char>(s);
    const bool vertical = (s == Side::kLeft || s == Side::kRight);
    const int count = vertical ? ny : nx;
    for (int k = 0; k <= count; ++k) {
      const int i = vertical ? (s == Side::kLeft ? 0 : nx) : k;
      const int j = vertical ? k : (s == Side::kBottom ? 0 : ny);
      const std::size_t id = grid.Index(i, j);
      // Exact fraction k / count so that mid-side and both ends are hit exactly.
      const Vec2 data = ProfileVelocity(side, static_cast<double>(k) / count);
      if (!vertical && owned[id]) {
        value[id].y() = data.y();  // a corner: the x component stays the vertical side's
        y_side[id] = side_index;
      } else {
        value[id] = data;
        x_side[id] = side_index;
        y_side[id] = side_index;
      }
      owned[id] = true;
    }
  }
  for (std::size_t id = 0; id < owned.size(); ++id) {
    if (!owned[id]) continue;
    nodes_.push_back(id);
    u_.push_back(value[id].x());
    v_.push_back(value[id].y());
    u_side_.push_back(x_side[id]);
    v_side_.push_back(y_side[id]);
    max_speed_ = std::max(max_speed_, value[id].norm());
  }
  SetTime(0.0);
}

void BoundaryData::SetTime(double t) {
  for (int s = 0; s < 4; ++s) factor_[s] = RampFactor(sides_[s], t);
}

void BoundaryData::Apply(double* u, double* v) const {
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    u[nodes_[k]] = factor_[u_side_[k]] * u_[k];
    v[nodes_[k]] = factor_[v_side_[k]] * v_[k];
  }
}

}  // namespace dlmfd
