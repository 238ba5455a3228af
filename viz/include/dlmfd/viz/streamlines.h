// Streamlines of a node velocity field, evenly spaced, for field pictures (`--streamlines N`).
//
// Method (B. Jobard, W. Lefer, "Creating evenly-spaced streamlines of arbitrary density",
// Visualization in Scientific Computing 1997, simplified): seeds at the centres of a lattice of
// `columns` columns of spacing d = W / columns, taken in order; from each seed that no line has
// come near yet, the line x(s) of dx/ds = u / |u| (arc length s; u the P1 interpolant of the
// velocity, field_picture.h) is integrated forwards and backwards by the midpoint rule (RK2) with
// steps of d / 10. A line stops at the domain's edge, where |u| is zero or not finite, after
// 40 (W + H) / d steps, or when it comes within d / 2 of another line (an occupancy grid of cells
// of side d / 2, each cell holding the line that entered it first; a line may pass its own recent
// cells). The result is polylines in domain coordinates, each at least 3 points long.
// The direction of flow on a line is that of increasing index.
#pragma once

#include <vector>

#include "dlmfd/viz/field_picture.h"

namespace dlmfd {

// Throws InvalidParameter when columns < 1 or the fields do not share one grid.
std::vector<std::vector<double>> Streamlines(const NodeVelocity& velocity, int columns);

}  // namespace dlmfd
