// Added mass of a fixed disk in a uniformly accelerated periodic liquid.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "dlmfd/core/params.h"
#include "dlmfd/core/simulation.h"

namespace dlmfd {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(ParticleAddedMass, Explore) {
  const int cells = std::atoi(std::getenv("CELLS") ? std::getenv("CELLS") : "24");
  const double dt = std::atof(std::getenv("DT") ? std::getenv("DT") : "0.001");
  const int steps = std::atoi(std::getenv("STEPS") ? std::getenv("STEPS") : "20");
  const double nu = std::atof(std::getenv("NU") ? std::getenv("NU") : "1e-6");
  Params params;
  params.domain.size = Vec2(1.0, 1.0);
  params.domain.h = 1.0 / cells;
  for (auto& side : params.domain.sides) side.type = SideType::kPeriodic;
  params.fluid.density = 1.0;
  params.fluid.viscosity = nu;
  params.fluid.body_force = Vec2(1.0, 0.0);
  params.splitting.advection = AdvectionScheme::kWave;
  params.time.dt = dt;
  params.time.end = dt * steps;
  params.particle_mesh.h = params.domain.h * std::atof(std::getenv("HP") ? std::getenv("HP") : "1.3714285714285714");
  params.threads = 1;
  ParticleParams disk;
  disk.center = Vec2(0.5, 0.5);
  disk.diameter = std::atof(std::getenv("DIAM") ? std::getenv("DIAM") : "0.2");
  disk.motion = Motion::kFixed;
  params.particles.push_back(disk);
  Simulation sim(params);
  const double volume = kPi * disk.diameter * disk.diameter / 4;
  for (int n = 0; n < steps; ++n) {
    sim.Step();
    double mean_u = 0.0;
    const auto& u = sim.state().u;
    const Grid& g = sim.grid();
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) mean_u += u[g.Index(i, j)];
    mean_u /= g.nx * g.ny;
    std::printf("step %d F/(rho Vp a) = %.6f  Fy %.2e  mean u / (a t) = %.6f\n", n + 1,
                sim.state().particles[0].force.x() / volume, sim.state().particles[0].force.y() / volume,
                mean_u / ((n + 1) * dt));
  }
  const double phi = volume;
  std::printf("theory %.6f\n", 1 + (1 - phi) / (1 + phi));
}

}  // namespace
}  // namespace dlmfd
