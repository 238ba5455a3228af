// The one-disk scene of the rigid-body constraint tests: a unit box of walls, h = 1/48, the liquid
// (density 1) at rest, one disk D = 0.2 off the grid lines at (0.5137, 0.4871) moving with
// U = (0.1, -0.2), omega = 0.5; each test chooses the multiplier points. With the liquid fields the
// tests set on the interior nodes (the boundary nodes keep their values).
#pragma once

#include <cmath>
#include <vector>

#include "dlmfd/core/constants.h"
#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"
#include "studied_numerics.h"

namespace dlmfd::testing {

struct ConstraintDiskScene {
  Params params;
  Grid grid{48, 48, 1.0 / 48, 0.0, 0.0};
  std::vector<ParticleState> particles;
  std::vector<double> u, v;

  explicit ConstraintDiskScene(double density, Motion motion = Motion::kFree) {
    UseStudiedNumerics(params);
    params.domain.size = Vec2(1.0, 1.0);
    params.domain.h = 1.0 / 48;
    params.fluid.density = 1.0;
    ParticleParams pp;
    pp.center = Vec2(0.5137, 0.4871);  // off the grid lines
    pp.diameter = 0.2;
    pp.density = density;
    pp.motion = motion;
    params.particles.push_back(pp);
    ParticleState s;
    s.id = 0;
    s.position = pp.center;
    s.radius = 0.1;
    s.density = density;
    s.motion = motion;
    s.velocity = Vec2(0.1, -0.2);
    s.angular_velocity = 0.5;
    particles.push_back(s);
    u.assign(grid.NodeCount(), 0.0);
    v.assign(grid.NodeCount(), 0.0);
  }

  // The rigid motion u = velocity + omega e_z x (x - centre), which the constraint leaves as it is.
  void Rigid(Vec2 velocity, double omega) {
    for (int j = 1; j < grid.ny; ++j) {
      for (int i = 1; i < grid.nx; ++i) {
        const Vec2 r = Vec2(grid.X(i), grid.Y(j)) - particles[0].position;
        u[grid.Index(i, j)] = velocity.x() - omega * r.y();
        v[grid.Index(i, j)] = velocity.y() + omega * r.x();
      }
    }
  }

  // A non-rigid field: u = sin(2 pi x) cos(2 pi y) + 0.3, v = -cos(2 pi x) sin(2 pi y) + 0.2 x.
  void Vortical() {
    for (int j = 1; j < grid.ny; ++j) {
      for (int i = 1; i < grid.nx; ++i) {
        const double x = grid.X(i), y = grid.Y(j);
        u[grid.Index(i, j)] = std::sin(2 * kPi * x) * std::cos(2 * kPi * y) + 0.3;
        v[grid.Index(i, j)] = -std::cos(2 * kPi * x) * std::sin(2 * kPi * y) + 0.2 * x;
      }
    }
  }
};

}  // namespace dlmfd::testing
