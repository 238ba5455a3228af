// A freely rotating neutrally buoyant disk in plane Couette flow.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "dlmfd/core/params.h"
#include "dlmfd/core/simulation.h"

namespace dlmfd {
namespace {

struct RotationRun {
  double ratio = 0.0;  // omega / shear rate
  double last_change = 0.0;
  Vec2 velocity = Vec2::Zero();
};

RotationRun RunCouette(int cells, double dt, double end, double viscosity) {
  const double wall_speed = 0.5, height = 1.0, shear = 2 * wall_speed / height;
  Params params;
  params.domain.size = Vec2(1.0, height);
  params.domain.h = height / cells;
  params.domain.sides[0].type = params.domain.sides[1].type = SideType::kPeriodic;
  params.domain.sides[2].type = params.domain.sides[3].type = SideType::kVelocity;
  params.domain.sides[2].value = Vec2(-wall_speed, 0.0);
  params.domain.sides[3].value = Vec2(wall_speed, 0.0);
  params.fluid.density = 1.0;
  params.fluid.viscosity = viscosity;
  params.splitting.advection = AdvectionScheme::kWave;
  params.time.dt = dt;
  params.time.end = end;
  params.particle_mesh.h = params.domain.h * std::atof(std::getenv("HP") ? std::getenv("HP") : "1.3714285714285714");
  params.threads = 1;
  ParticleParams disk;
  disk.center = Vec2(0.5, 0.5 * height);
  disk.diameter = 0.25;
  disk.density = params.fluid.density;  // neutrally buoyant
  params.particles.push_back(disk);
  Simulation sim(params);
  // Start from the undisturbed Couette profile.
  FlowState& state = sim.mutable_state();
  const Grid& grid = sim.grid();
  for (int j = 0; j <= grid.ny; ++j) {
    for (int i = 0; i <= grid.nx; ++i) state.u[grid.Index(i, j)] = shear * (grid.Y(j) - 0.5 * height);
  }
  RotationRun run;
  const long steps = sim.TotalSteps();
  double previous = 0.0;
  for (long n = 0; n < steps; ++n) {
    sim.Step();
    const double ratio = sim.state().particles[0].angular_velocity / shear;
    if (n == steps - 11) previous = ratio;
    run.ratio = ratio;
  }
  run.last_change = std::abs(run.ratio - previous);
  run.velocity = sim.state().particles[0].velocity;
  return run;
}

TEST(ParticleCouetteRotation, Explore) {
  const int cells = std::atoi(std::getenv("CELLS") ? std::getenv("CELLS") : "16");
  const double dt = std::atof(std::getenv("DT") ? std::getenv("DT") : "0.004");
  const double end = std::atof(std::getenv("END") ? std::getenv("END") : "0.5");
  const double nu = std::atof(std::getenv("NU") ? std::getenv("NU") : "1");
  const RotationRun r = RunCouette(cells, dt, end, nu);
  std::printf("cells %d dt %g end %g nu %g: omega/g = %.8f (change over 10 steps %.2e) U = (%.2e, %.2e)\n",
              cells, dt, end, nu, r.ratio, r.last_change, r.velocity.x(), r.velocity.y());
}

}  // namespace
}  // namespace dlmfd
