// Dirichlet data u_Gamma on the velocity grid (paper (1)-(3): u = u_Gamma on Gamma).
//
// Discrete method: nodal interpolation of the side data. A wall is zero; a "velocity" side carries
// its profile times its ramp, g(t) phi(s) (fluid/boundary_profile.h: uniform, poiseuille, quartic;
// s the arc-length fraction along the side).
// A corner shared by two Dirichlet sides takes from each side the component normal to that side:
// u from the left/right side, v from the bottom/top side. So no side's data put flux through
// another side: the nodal interpolant of each side's normal velocity is that side's alone, and the
// flux through a wall is zero. (Where the data are discontinuous at a corner, as at the lid of a
// driven cavity, the other rule, one side owning both components, makes the wall next to the lid
// leak: u = 1 at the corner node, linear to 0 one node below, a source of strength h/2 at one
// upper corner and a sink at the other, an O(h) error in the whole flow;
// docs/evidence/validation.md, lid-driven cavity.) With continuous data (walls, a poiseuille
// profile vanishing at its ends) the rules agree. Outflow and periodic sides carry no data: their
// nodes are left untouched. Time: the data are those of the time last given to SetTime (t = 0 until
// then); a side without a ramp gives the same values at every time, bit for bit (its factor is
// exactly 1). The Simulation sets t_{n+1} before step (33), so steps (33) and (34) of a step see
// the data of its new time level.
#pragma once

#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"

namespace dlmfd {

class BoundaryData {
 public:
  BoundaryData(const Grid& grid, const DomainParams& domain);

  // The data of time t from now on (each side's ramp factor g(t)).
  void SetTime(double t);
  // Writes the data of the current time into the Dirichlet nodes of u and v (full node arrays).
  void Apply(double* u, double* v) const;
  // Largest |phi| over the nodes, the data without their ramps: the largest |u_Gamma| at any time
  // (a velocity scale for CFL and stopping rules).
  double MaxSpeed() const { return max_speed_; }

 private:
  std::vector<std::size_t> nodes_;              // Dirichlet node indices
  std::vector<double> u_, v_;                   // their values phi, without the ramp
  std::vector<unsigned char> u_side_, v_side_;  // the side whose ramp scales each component
  double factor_[4] = {1.0, 1.0, 1.0, 1.0};     // g(t) per Side at the current time
  BoundarySide sides_[4];
  double max_speed_ = 0.0;
};

}  // namespace dlmfd
