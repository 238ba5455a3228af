// The creeping fixed disk of the cut-cell studies (docs/evidence/cut_cell_boundary.md, "A
// second-order boundary: the engine's cut cells"): D = 0.1 at (0.2 + s h, 0.2) in a 0.8 x 0.4
// channel, Poiseuille inflow of maximum 0.3, eta = 1, steady Stokes. Its drag's reference is the
// Richardson limit of the position means of the prototype at D/h = 20-40-80.
#pragma once

#include "dlmfd/core/params.h"
#include "studied_numerics.h"

namespace dlmfd {

inline constexpr double kCutCreepingReference = 6.487;

// The channel of that disk at D/h = d_over_h: 0.8 x 0.4, Poiseuille inflow of maximum 0.3 on the
// left, outflow on the right, walls below and above.
inline DomainParams CutCreepingChannel(double d_over_h) {
  DomainParams d;
  testing::UseStudiedNumerics(d);
  d.size = Vec2(0.8, 0.4);
  d.h = 0.1 / d_over_h;
  BoundarySide& inflow = d.sides[static_cast<int>(Side::kLeft)];
  inflow.type = SideType::kVelocity;
  inflow.profile = Profile::kPoiseuille;
  inflow.max = Vec2(0.3, 0.0);
  d.sides[static_cast<int>(Side::kRight)].type = SideType::kOutflow;
  return d;
}

}  // namespace dlmfd
