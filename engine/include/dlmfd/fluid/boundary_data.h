// Dirichlet data u_Gamma on the velocity grid (paper (1)-(3): u = u_Gamma on Gamma).
//
// Discrete method: nodal interpolation of the side data. A wall is zero; a "velocity" side with the
// uniform profile carries its constant value; the poiseuille profile is the parabola
// 4 s (1 - s) max along the side (s the arc-length fraction, 0 at both corners, max at mid-side).
// A corner shared by two Dirichlet sides takes from each side the component normal to that side:
// u from the left/right side, v from the bottom/top side. So no side's data put flux through
// another side: the nodal interpolant of each side's normal velocity is that side's alone, and the
// flux through a wall is zero. (Where the data are discontinuous at a corner, as at the lid of a
// driven cavity, the other rule, one side owning both components, makes the wall next to the lid
// leak: u = 1 at the corner node, linear to 0 one node below, a source of strength h/2 at one
// upper corner and a sink at the other, an O(h) error in the whole flow; docs/validation.md,
// lid-driven cavity.) With continuous data (walls, a poiseuille profile vanishing at its ends) the
// rules agree. Outflow and periodic sides carry no data: their nodes are left untouched.
// The data do not depend on time (steady boundary data are all the scene language has).
#pragma once

#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"

namespace dlmfd {

class BoundaryData {
 public:
  BoundaryData(const Grid& grid, const DomainParams& domain);

  // Writes the data into the Dirichlet nodes of u and v (full node arrays).
  void Apply(double* u, double* v) const;
  // Largest |u_Gamma| over the data (a velocity scale for CFL and stopping rules).
  double MaxSpeed() const { return max_speed_; }

 private:
  std::vector<std::size_t> nodes_;  // Dirichlet node indices
  std::vector<double> u_, v_;       // their values
  double max_speed_ = 0.0;
};

}  // namespace dlmfd
