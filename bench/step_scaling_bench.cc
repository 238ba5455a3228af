// How the cost of a full Oldroyd-B step with particles grows with the grid and with the number of
// particles (issue 6, point 3; docs/evidence/performance.md "Scaling"). Base:
// cases/paper/5.2_pair_oldroyd_b.toml (2 x 8 box, eta = 0.12, lambda = 1.4, dt = 4e-4) with the
// wave-like advection, 2 threads, 20 set-up steps from rest, then timed steps.
//   BM_StepMesh/cells:C     the scene's two disks on h = 1/C (C = 24 ... 192; the paper's grid is
//   96),
//                           the particle mesh scaled with h (h_p = h 96/70 as in the paper);
//                           expected: N log N in the velocity nodes N (fast solves), N for the
//                           rest.
//   BM_StepParticles/n:P    P disks (D = 0.2, rho = 1.01) on the paper's grid, in rows of 4 from
//   the
//                           top (x = 0.25, 0.75, 1.25, 1.75; rows 0.4 apart from y = 7.7);
//                           expected: linear in P for the particle step, the rest unchanged.
//   OMP_WAIT_POLICY=active build/bench/step_scaling_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <string>

#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"
#include "step_averages.h"

namespace dlmfd {
namespace {

constexpr int kSetUpSteps = 20;
constexpr int kThreads = 2;

Params PairScene() {
  Params p = LoadSceneFile(std::string(DLMFD_SOURCE_DIR) + "/cases/paper/5.2_pair_oldroyd_b.toml");
  p.splitting.advection = AdvectionScheme::kWave;
  p.output.fields_every = 0.0;
  p.threads = kThreads;
  return p;
}

void BM_StepMesh(benchmark::State& state) {
  Params p = PairScene();
  const double cells = static_cast<double>(state.range(0));
  p.domain.h = 1.0 / cells;
  p.particle_mesh.h = (96.0 / 70.0) / cells;
  TimeFullSteps(state, p, kSetUpSteps);
}

void BM_StepParticles(benchmark::State& state) {
  Params p = PairScene();
  const ParticleParams disk = p.particles.front();
  p.particles.clear();
  for (int k = 0; k < state.range(0); ++k) {
    ParticleParams q = disk;
    q.center = Vec2(0.25 + 0.5 * (k % 4), 7.7 - 0.4 * (k / 4));
    p.particles.push_back(q);
  }
  TimeFullSteps(state, p, kSetUpSteps);
}

BENCHMARK(BM_StepMesh)
    ->ArgNames({"cells"})
    ->Arg(24)
    ->Arg(48)
    ->Arg(96)
    ->Arg(192)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(1.0);

BENCHMARK(BM_StepParticles)
    ->ArgNames({"n"})
    ->Arg(0)
    ->Arg(2)
    ->Arg(8)
    ->Arg(32)
    ->Arg(64)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(1.0);

}  // namespace
}  // namespace dlmfd
BENCHMARK_MAIN();
