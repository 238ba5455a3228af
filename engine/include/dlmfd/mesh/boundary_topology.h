// Which nodes of a grid are unknowns, side by side: the bridge between the scene's side types and
// the discrete operators and fast solvers.
//
// Velocity (and A): wall and velocity sides are Dirichlet (data prescribed), outflow sides are
// Neumann (do-nothing: the natural condition nu du/dn - p n = 0), periodic sides are periodic.
// Pressure: the other way round on the 2h grid: Neumann where the velocity is prescribed, Dirichlet
// (p = 0) on outflow sides, periodic where periodic. Corners belong to Dirichlet when either side
// is. A periodic pair keeps its last node column (row) equal to the first; only the first is an
// unknown.
#pragma once

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"

namespace dlmfd {

enum class EndKind { kDirichlet, kNeumann, kPeriodic };

struct AxisBoundary {
  EndKind low = EndKind::kDirichlet;   // left (x) or bottom (y)
  EndKind high = EndKind::kDirichlet;  // right (x) or top (y)
};

struct BoundaryTopology {
  AxisBoundary x, y;

  static BoundaryTopology ForVelocity(const DomainParams& domain);
  static BoundaryTopology ForPressure(const DomainParams& domain);

  // True at nodes whose value a solve determines; false on Dirichlet sides and on the repeated
  // last column/row of a periodic pair.
  bool IsUnknown(const Grid& grid, int i, int j) const;
  // True when no side is Dirichlet: constants are in the kernel of the stiffness.
  bool HasNullSpace() const;
};

}  // namespace dlmfd
