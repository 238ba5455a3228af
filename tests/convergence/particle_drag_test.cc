// Stokes drag of a fixed disk in a periodic channel driven by a body force, on 3 grids.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "dlmfd/core/observer.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/simulation.h"

namespace dlmfd {
namespace {

struct Timing : Observer {
  std::vector<std::pair<std::string, double>> sum;
  long steps = 0;
  void OnStep(const FlowState&, const StepReport& report) override {
    if (sum.empty()) sum = report.columns;
    else for (std::size_t k = 0; k < sum.size(); ++k) sum[k].second += report.columns[k].second;
    ++steps;
  }
  void Print() const {
    for (const auto& c : sum) std::printf("  %s %.4g\n", c.first.c_str(), c.second / steps);
  }
};

struct DragRun {
  double force = 0.0;
  double last_change = 0.0;
};

DragRun RunDrag(int cells, double dt, double end) {
  Params params;
  params.domain.size = Vec2(1.0, 1.0);
  params.domain.h = 1.0 / cells;
  params.domain.sides[0].type = params.domain.sides[1].type = SideType::kPeriodic;
  params.fluid.density = 1.0;
  params.fluid.viscosity = 1.0;
  params.fluid.body_force = Vec2(1.0, 0.0);
  params.splitting.advection = AdvectionScheme::kWave;
  params.time.dt = dt;
  params.time.end = end;
  params.particle_mesh.h = params.domain.h * 96.0 / 70.0;
  params.threads = 1;
  ParticleParams disk;
  disk.center = Vec2(0.5, 0.5);
  disk.diameter = 0.25;
  disk.motion = Motion::kFixed;
  params.particles.push_back(disk);
  Simulation sim(params);
  Timing timing;
  sim.AddObserver(&timing);
  DragRun run;
  const long steps = sim.TotalSteps();
  double previous = 0.0;
  for (long n = 0; n < steps; ++n) {
    sim.Step();
    const double f = sim.state().particles[0].force.x();
    if (n == steps - 11) previous = f;
    run.force = f;
  }
  run.last_change = std::abs(run.force - previous);
  timing.Print();
  return run;
}

TEST(ParticleDrag, Explore) {
  const int cells = std::atoi(std::getenv("CELLS") ? std::getenv("CELLS") : "16");
  const double dt = std::atof(std::getenv("DT") ? std::getenv("DT") : "0.004");
  const double end = std::atof(std::getenv("END") ? std::getenv("END") : "1.5");
  const DragRun r = RunDrag(cells, dt, end);
  std::printf("cells %d dt %g end %g: F = %.8f (change over 10 steps %.2e)\n", cells, dt, end, r.force,
              r.last_change);
}

}  // namespace
}  // namespace dlmfd
