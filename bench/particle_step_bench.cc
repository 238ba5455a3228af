// Cost of the particle step (36)-(38) on the paper's grid: 2 x 8, h = 1/96, h_p = 1/70, D = 0.2,
// dt = 4e-4, rho_d = 1.01, g = 981, in a non-rigid velocity field. Reports ms per Advance for 2, 11
// and 102 particles in regular arrangements, with 1 and 2 OpenMP threads; the fluid field and
// particles are restored before each step (untimed) so every step solves the same DLM problem from
// the same warm start. Compare with ms_stokes of newtonian_step_bench (the Stokes step, same grid).
//   OMP_WAIT_POLICY=active build/bench/particle_step_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <string>
#include <vector>

#include "dlmfd/core/constants.h"
#include "dlmfd/particles/particle_step.h"
#include "dlmfd/scene/auto_coupling.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

Params PaperScene(int count) {
  Params params;
  params.domain.size = Vec2(2.0, 8.0);
  params.domain.h = 1.0 / 96;
  params.particle_mesh.h = 1.0 / 70;
  // The settings of the numbers in docs/ (Params{}'s defaults before issue 39).
  params.domain.diagonals = MeshDiagonals::kSwNe;
  params.splitting.steady_correction = SteadyCorrection::kNone;
  params.gravity = Vec2(0.0, -981.0);
  params.time.dt = 4e-4;
  // Regular arrangements: 2 on the axis, 11 in a column, 102 on a 6 x 17 lattice.
  const int columns = count == 102 ? 6 : 1;
  const int rows = count / columns;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      ParticleParams p;
      p.center = Vec2(2.0 * (c + 0.5) / columns, 8.0 * (r + 0.5) / rows);
      p.diameter = 0.2;
      p.density = 1.01;
      params.particles.push_back(p);
    }
  }
  // The keys a scene file would leave to their defaults (the coupling by `auto`), as a run does.
  ResolveDefaults(params);
  return params;
}

void BM_ParticleStepAdvance(benchmark::State& state) {
  const Params params = PaperScene(static_cast<int>(state.range(0)));
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const Grid grid{192, 768, 1.0 / 96, 0.0, 0.0};
  ParticleStep step(params, grid);
  std::vector<double> u0(grid.NodeCount(), 0.0), v0(grid.NodeCount(), 0.0);
  for (int j = 1; j < grid.ny; ++j) {
    for (int i = 1; i < grid.nx; ++i) {
      const double x = grid.X(i), y = grid.Y(j);
      u0[grid.Index(i, j)] = 0.5 * std::sin(kPi * x) * std::cos(2 * kPi * y);
      v0[grid.Index(i, j)] = -0.5 * std::cos(kPi * x) * std::sin(2 * kPi * y) - 1.0;
    }
  }
  std::vector<ParticleState> initial = ParticleStep::InitialStates(params);
  for (auto& p : initial) p.velocity = Vec2(0.0, -1.0);
  // One step to get a warm-start multiplier, as in a run.
  std::vector<double> u = u0, v = v0;
  StepReport report;
  step.Advance(0.0, params.time.dt, initial, u.data(), v.data(), report);
  std::vector<ParticleState> particles = initial;
  double iterations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    u = u0;
    v = v0;
    particles = initial;
    state.ResumeTiming();
    step.Advance(0.0, params.time.dt, particles, u.data(), v.data(), report);
    iterations += report.Get("multiplier_iterations");
  }
  state.counters["cg_iterations"] = iterations / static_cast<double>(state.iterations());
  state.counters["us_per_particle"] = benchmark::Counter(
      static_cast<double>(params.particles.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetLabel(std::string("constraint ") +
                 ConstraintCouplingName(params.splitting.constraint.value()));
  omp_set_num_threads(omp_get_num_procs());
}
BENCHMARK(BM_ParticleStepAdvance)
    ->ArgNames({"particles", "threads"})
    ->ArgsProduct({{2, 11, 102}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace dlmfd

BENCHMARK_MAIN();
