// ms per Newtonian time step (Stokes (33) + advection (34)) on the paper's grid: 2 x 8, h = 1/96
// (193 x 769 velocity nodes), walls, eta = 0.01, alpha = beta = 0.5, dt = 4e-4, the flow driven by
// the left wall moving upwards at 1 (5 set-up steps before timing so that iterations are those of a
// developing flow). Arguments: {advection scheme: 0 least squares, 1 wave} x {threads} x
// {domain.diagonals: 0 sw_ne, 1 both}.
// Counters: per-substep ms, Uzawa and LS-CG iterations (or wave sub-steps), node updates per
// second.
#include <benchmark/benchmark.h>
#include <omp.h>

#include "dlmfd/core/simulation.h"
#include "step_averages.h"

namespace dlmfd {
namespace {

Params PaperGrid(AdvectionScheme scheme, int threads, MeshDiagonals diagonals) {
  Params p;
  p.domain.size = Vec2(2.0, 8.0);
  p.domain.h = 1.0 / 96;
  p.domain.diagonals = diagonals;
  p.domain.sides[0].type = SideType::kVelocity;
  p.domain.sides[0].value = Vec2(0.0, 1.0);
  p.fluid.density = 1.0;
  p.fluid.viscosity = 0.01;
  p.fluid.solvent_ratio = 1.0;
  p.time.dt = 4e-4;
  p.time.end = 1.0;
  p.splitting.alpha = 0.5;
  p.splitting.beta = 0.5;
  p.splitting.advection = scheme;
  p.splitting.steady_correction = SteadyCorrection::kNone;  // as measured in docs/
  p.output.fields_every = 0.0;
  p.threads = threads;
  return p;
}

void BM_NewtonianStep(benchmark::State& state) {
  const auto scheme = state.range(0) == 0 ? AdvectionScheme::kLeastSquares : AdvectionScheme::kWave;
  const int threads = static_cast<int>(state.range(1));
  const auto diagonals = state.range(2) == 0 ? MeshDiagonals::kSwNe : MeshDiagonals::kBoth;
  Simulation sim(PaperGrid(scheme, threads, diagonals));
  const bool wave = scheme == AdvectionScheme::kWave;
  StepAverages averages(
      {{"ms_stokes", "ms_stokes"},
       {"ms_advection", "ms_advection"},
       {"stokes_iterations", "stokes_its"},
       {wave ? "wave_substeps" : "advection_iterations", wave ? "wave_substeps" : "ls_its"}});
  sim.AddObserver(&averages);
  for (int n = 0; n < 5; ++n) sim.Step();
  averages.Reset();
  for (auto _ : state) sim.Step();
  averages.Write(state, static_cast<double>(sim.grid().NodeCount()));
  omp_set_num_threads(omp_get_num_procs());
}

BENCHMARK(BM_NewtonianStep)
    ->ArgNames({"wave", "threads", "both"})
    ->Args({1, 1, 0})
    ->Args({1, 2, 0})
    ->Args({0, 1, 0})
    ->Args({0, 2, 0})
    ->Args({1, 1, 1})
    ->Args({1, 2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

}  // namespace
}  // namespace dlmfd
BENCHMARK_MAIN();
