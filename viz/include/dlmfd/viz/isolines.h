// Isolines of a P1 node field: the level set {f = c} of the field's finite-element
// representation, exactly.
//
// Method: marching squares on the mesh's own triangles (each square of side h cut by its SW-NE
// diagonal, paper section 3). On a triangle f is linear, so {f = c} is one straight segment
// between the two edges whose end values lie on either side of c (a vertex counts as above when
// f >= c), at the point where linear interpolation along the edge reaches c. Splitting each square
// along the field's own diagonal removes the ambiguous saddle cases of marching squares on
// bilinear cells, and consecutive triangles share their crossing points, so the lines are
// continuous. Non-finite vertex values skip the triangle.
// Reference: W. E. Lorensen, H. E. Cline, "Marching cubes", SIGGRAPH (1987), in 2-D on triangles.
#pragma once

#include <vector>

#include "dlmfd/viz/field_picture.h"

namespace dlmfd {

// The segments of {f = level} as (x0, y0, x1, y1) quadruples in domain coordinates.
std::vector<double> IsolineSegments(const NodeField& field, double level);
// `count` values evenly spaced strictly inside [lo, hi] (lo + k (hi - lo) / (count + 1)), in
// log10 of the value when `log` (then 0 < lo).
std::vector<double> Isovalues(double lo, double hi, int count, bool log);

}  // namespace dlmfd
