// The channel [0, 1] x [0, 0.5] on h = 1/16, periodic along y (bottom and top) between walls at
// x = 0 and x = 1, with its volume flux held at `flow_rate` (domain.flow_rate,
// fluid/flux_control.h): the scene of tests/unit/flux_control_test.cc and
// tests/unit/step_time_step_test.cc, on the numerics their studies used (studied_numerics.h).
#pragma once

#include "dlmfd/core/params.h"
#include "studied_numerics.h"

namespace dlmfd::testing {

inline Params PeriodicChannel(double flow_rate) {
  Params p;
  UseStudiedNumerics(p);
  p.domain.size = Vec2(1.0, 0.5);
  p.domain.h = 1.0 / 16;
  p.domain.sides[static_cast<int>(Side::kBottom)].type = SideType::kPeriodic;
  p.domain.sides[static_cast<int>(Side::kTop)].type = SideType::kPeriodic;
  p.domain.flow_rate = flow_rate;
  return p;
}

}  // namespace dlmfd::testing
