// The start-up of simple shear through the engine's conformation step: A = I at rest, then the
// velocity u = Wi (y - 1/2), v = 0 on every node. The P1 gradient of a linear field is exact and a
// field uniform in x is not advected along x, so every node follows the homogeneous start-up.
#pragma once

#include <vector>

#include "dlmfd/conformation/conformation_step.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"

namespace dlmfd::testing {

// A at every node of the velocity grid, and the report the steps wrote.
struct ShearRun {
  std::vector<double> a11, a12, a22;
  StepReport report;
};

// p's velocity grid after `steps` steps of dt.
inline ShearRun ShearStartUp(const Params& p, double wi, double dt, int steps) {
  const Grid grid = p.domain.VelocityGrid();
  ConformationStep step(p, grid);
  const std::size_t count = grid.NodeCount();
  std::vector<double> u(count), v(count, 0.0);
  ShearRun a{std::vector<double>(count, 1.0), std::vector<double>(count, 0.0),
             std::vector<double>(count, 1.0), StepReport{}};
  for (int j = 0; j <= grid.ny; ++j)
    for (int i = 0; i <= grid.nx; ++i) u[grid.Index(i, j)] = wi * (grid.Y(j) - 0.5);
  for (int s = 0; s < steps; ++s)
    step.Advance(s * dt, dt, u.data(), v.data(), nullptr, a.a11.data(), a.a12.data(), a.a22.data(),
                 a.report);
  return a;
}

}  // namespace dlmfd::testing
