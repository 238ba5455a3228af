// Dirichlet data u_Gamma on the velocity grid (paper (1)-(3): u = u_Gamma on Gamma).
//
// Discrete method: nodal interpolation of the side data. A wall is zero; a "velocity" side with the
// uniform profile carries its constant value; the poiseuille profile is the parabola
// 4 s (1 - s) max along the side (s the arc-length fraction, 0 at both corners, max at mid-side).
// Corners shared by two Dirichlet sides take the value of the bottom/top side when it is Dirichlet
// (the left/right value otherwise); with the usual data (walls, a poiseuille profile vanishing at
// its ends) both agree. Outflow and periodic sides carry no data: their nodes are left untouched.
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
