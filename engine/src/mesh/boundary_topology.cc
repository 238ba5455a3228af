// Side types of the scene -> end kinds of the velocity and pressure grids (see the header).
#include "dlmfd/mesh/boundary_topology.h"

namespace dlmfd {
namespace {

// Velocity: data prescribed on walls and velocity sides, do-nothing on outflow sides.
EndKind VelocityEnd(SideType type) {
  switch (type) {
    case SideType::kWall:
    case SideType::kVelocity:
      return EndKind::kDirichlet;
    case SideType::kOutflow:
      return EndKind::kNeumann;
    case SideType::kPeriodic:
      return EndKind::kPeriodic;
  }
  return EndKind::kDirichlet;
}

// Pressure: natural where the velocity is prescribed, p = 0 on outflow sides.
EndKind PressureEnd(SideType type) {
  switch (type) {
    case SideType::kWall:
    case SideType::kVelocity:
      return EndKind::kNeumann;
    case SideType::kOutflow:
      return EndKind::kDirichlet;
    case SideType::kPeriodic:
      return EndKind::kPeriodic;
  }
  return EndKind::kNeumann;
}

template <typename EndOf>
BoundaryTopology FromSides(const DomainParams& domain, EndOf end_of) {
  BoundaryTopology topo;
  topo.x.low = end_of(domain.side(Side::kLeft).type);
  topo.x.high = end_of(domain.side(Side::kRight).type);
  topo.y.low = end_of(domain.side(Side::kBottom).type);
  topo.y.high = end_of(domain.side(Side::kTop).type);
  return topo;
}

bool IsUnknownAlong(const AxisBoundary& axis, int n_cells, int index) {
  if (index == 0) return axis.low != EndKind::kDirichlet;
  if (index == n_cells) return axis.high == EndKind::kNeumann;
  return true;
}

}  // namespace

BoundaryTopology BoundaryTopology::ForVelocity(const DomainParams& domain) {
  return FromSides(domain, VelocityEnd);
}

BoundaryTopology BoundaryTopology::ForPressure(const DomainParams& domain) {
  return FromSides(domain, PressureEnd);
}

bool BoundaryTopology::IsUnknown(const Grid& grid, int i, int j) const {
  return IsUnknownAlong(x, grid.nx, i) && IsUnknownAlong(y, grid.ny, j);
}

bool BoundaryTopology::HasNullSpace() const {
  return x.low != EndKind::kDirichlet && x.high != EndKind::kDirichlet &&
         y.low != EndKind::kDirichlet && y.high != EndKind::kDirichlet;
}

}  // namespace dlmfd
