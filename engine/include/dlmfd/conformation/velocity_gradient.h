// The velocity gradient L_ij = du_i/dx_j at the nodes of the h-grid, for step (35).
//
// Discrete method: u is P1 on the SW-NE triangles; each triangle has a constant gradient. The value
// at a node is the average of the gradients of the triangles around it: 6 in the interior (second
// order on the uniform mesh: (2 (f_{i+1,j} - f_{i-1,j}) + f_{i+1,j+1} - f_{i,j+1} + f_{i,j-1}
// - f_{i-1,j-1}) / 6h for d/dx), the 1 to 3 triangles inside the domain on a non-periodic side (one
// sided, first order there), wrapped across periodic sides. Exact for linear fields at every node.
// With domain.diagonals = "both" the value is the mean of that average on the SW-NE and on the
// NW-SE triangles (interior: (4 (f_{i+1,j} - f_{i-1,j}) + f_{i+1,j+1} - f_{i-1,j+1} + f_{i+1,j-1}
// - f_{i-1,j-1}) / 12h for d/dx; at the other nodes the mean of the two averages over their own
// triangles), in the same sweep as the SW-NE average.
// Not supported: anything but the uniform grid of core/grid.h.
// References: method notes 2, section 2.3 ("L at nodes").
#pragma once

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"

namespace dlmfd {

// l11 = du/dx, l12 = du/dy, l21 = dv/dx, l22 = dv/dy at every node (periodic duplicates included).
void NodeVelocityGradient(const Grid& grid, bool periodic_x, bool periodic_y, const double* u,
                          const double* v, double* l11, double* l12, double* l21, double* l22,
                          MeshDiagonals diagonals = MeshDiagonals::kSwNe);

}  // namespace dlmfd
