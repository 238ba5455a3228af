// Issue 34, point 5: a step gives the same bits whatever the OpenMP team. 36 disks falling in an
// Oldroyd-B liquid at the engine's defaults (collocation points, the incremental coupling, the wave
// advection, both diagonals; from 32 particles on the multiplier CG shares its loops between the
// threads), 4 steps on 1, 2 (twice) and 3 threads: the velocity, pressure, conformation and every
// particle's motion, force and multipliers are bit-identical. The sums that cross threads are per
// particle in order (particles/multiplier_cg.cc) or over fixed blocks in order
// (core/ordered_sum.h); the fast solves split their work without sums (separable_helmholtz.cc).
#include <omp.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <tuple>
#include <vector>

#include "../support/walled_box_scene.h"
#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

bool SameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

bool SameBits(const Vec2& a, const Vec2& b) { return a.x() == b.x() && a.y() == b.y(); }

// A 1 x 1.25 walled box, h = 1/48; 6 x 6 disks of D = 0.1, 0.14 apart, heavier than the liquid.
std::string Scene() {
  std::string scene =
      "\n" + testing::WalledBoxDomain("1.0, 1.25", "0.020833333333333332") + R"([fluid]
density = 1.0
viscosity = 0.1
relaxation_time = 0.5
solvent_ratio = 0.5
gravity = [0.0, -9.81]
[time]
dt = 0.001
end = 0.004
[output]
fields_every = 0
particles_every = 0
checkpoint_every = 0
)";
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      char disk[160];
      std::snprintf(disk, sizeof disk,
                    "[[particles]]\ncenter = [%.4f, %.4f]\ndiameter = 0.1\n"
                    "density = %.2f\n",
                    0.1513 + 0.14 * c, 0.2271 + 0.14 * r, (r + c) % 3 == 0 ? 1.5 : 1.2);
      scene += disk;
    }
  }
  return scene;
}

FlowState RunOn(int threads) {
  Params params = ParseScene(Scene());
  params.threads = threads;
  Simulation sim(params);
  while (!sim.Done()) sim.Step();
  return sim.state();
}

TEST(SimulationThreads, ThirtySixDisksGiveTheSameBitsOnOneTwoAndThreeThreads) {
  const FlowState one = RunOn(1);
  ASSERT_EQ(one.step, 4);
  ASSERT_EQ(one.particles.size(), 36u);
  ASSERT_FALSE(one.a11.empty());
  EXPECT_GT(one.particles[0].velocity.norm(), 0.0);
  for (int threads : {2, 2, 3}) {
    const FlowState other = RunOn(threads);
    for (const auto& [name, a, b] :
         {std::tuple{"u", &one.u, &other.u}, std::tuple{"v", &one.v, &other.v},
          std::tuple{"p", &one.p, &other.p}, std::tuple{"A11", &one.a11, &other.a11},
          std::tuple{"A12", &one.a12, &other.a12}, std::tuple{"A22", &one.a22, &other.a22}}) {
      EXPECT_TRUE(SameBits(*a, *b)) << name << " on " << threads << " threads";
    }
    for (std::size_t k = 0; k < one.particles.size(); ++k) {
      const ParticleState& a = one.particles[k];
      const ParticleState& b = other.particles[k];
      EXPECT_TRUE(SameBits(a.position, b.position) && SameBits(a.velocity, b.velocity) &&
                  a.angular_velocity == b.angular_velocity && SameBits(a.force, b.force) &&
                  a.torque == b.torque && SameBits(a.multiplier, b.multiplier))
          << "particle " << k << " on " << threads << " threads";
    }
  }
  omp_set_num_threads(omp_get_num_procs());
}

}  // namespace
}  // namespace dlmfd
