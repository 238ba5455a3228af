// Fast solver and operator costs on the paper's grid (2 x 8, h = 1/96: 193 x 769 velocity nodes,
// 97 x 385 pressure nodes). Method notes 1, section 5 budgets about 1 ms per velocity solve and
// 0.3 ms per pressure solve. Run: build/bench/fast_solver_bench
//   velocity solve: (a M_l + b K) u = f, walls all round, a = 1/dt (dt = 4e-4), b = 0.005
//   pressure solve: Neumann all round, a = 0, b = 1 (the singular case, mean-free result)
//   velocity pair: u and v as one batch (SolvePair)
//   each with 1 and 2 OpenMP threads (the Arg); operators: B, B^T, K, with 1 and 2 threads
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <vector>

#include "dlmfd/mesh/boundary_topology.h"
#include "dlmfd/mesh/fem_operators.h"
#include "dlmfd/solvers/fft_planning.h"
#include "dlmfd/solvers/separable_helmholtz.h"

namespace dlmfd {
namespace {

const Grid kGrid{192, 768, 1.0 / 96.0, 0.0, 0.0};

BoundaryTopology Walls() { return BoundaryTopology{}; }

BoundaryTopology NeumannAllRound() {
  BoundaryTopology t;
  t.x = {EndKind::kNeumann, EndKind::kNeumann};
  t.y = {EndKind::kNeumann, EndKind::kNeumann};
  return t;
}

std::vector<double> Smooth(const Grid& g, double phase) {
  std::vector<double> f(g.NodeCount());
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i)
      f[g.Index(i, j)] = std::sin(3.0 * g.X(i) + phase) * std::cos(1.7 * g.Y(j));
  }
  return f;
}

// Each solve on a team of state.range(0) threads (the solver is built for that team).
void BM_VelocitySolve(benchmark::State& state) {
  omp_set_num_threads(int(state.range(0)));
  const SeparableHelmholtz solver(kGrid, Walls(), 1.0 / 4e-4, 0.005, 1);
  const std::vector<double> f = Smooth(kGrid, 0.0);
  std::vector<double> u(kGrid.NodeCount(), 0.0);
  for (auto _ : state) {
    solver.Solve(f.data(), u.data());
    benchmark::DoNotOptimize(u.data());
  }
}
BENCHMARK(BM_VelocitySolve)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PressureSolve(benchmark::State& state) {
  omp_set_num_threads(int(state.range(0)));
  const Grid coarse = kGrid.Coarse();
  const SeparableHelmholtz solver(coarse, NeumannAllRound(), 0.0, 1.0, 1);
  const std::vector<double> f = Smooth(coarse, 0.3);
  std::vector<double> p(coarse.NodeCount(), 0.0);
  for (auto _ : state) {
    solver.Solve(f.data(), p.data());
    benchmark::DoNotOptimize(p.data());
  }
}
BENCHMARK(BM_PressureSolve)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The velocity and pressure solves with each FFTW planner choice (solvers/fft_planning.h): 0
// deterministic plans (FFTW_ESTIMATE, the default since issue 38), 1 timed ones (FFTW_MEASURE).
// Arguments: planning, grid (0 velocity, 1 pressure).
void BM_SolvePlanning(benchmark::State& state) {
  SetFftPlanning(state.range(0) == 0 ? FftPlanning::kDeterministic : FftPlanning::kMeasured);
  const Grid grid = state.range(1) == 0 ? kGrid : kGrid.Coarse();
  const SeparableHelmholtz solver = state.range(1) == 0
                                        ? SeparableHelmholtz(grid, Walls(), 1.0 / 4e-4, 0.005, 1)
                                        : SeparableHelmholtz(grid, NeumannAllRound(), 0.0, 1.0, 1);
  SetFftPlanning(FftPlanning::kDeterministic);
  const std::vector<double> f = Smooth(grid, 0.3);
  std::vector<double> x(grid.NodeCount(), 0.0);
  for (auto _ : state) {
    solver.Solve(f.data(), x.data());
    benchmark::DoNotOptimize(x.data());
  }
}
BENCHMARK(BM_SolvePlanning)
    ->ArgNames({"planning", "grid"})
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

// u and v as one batch (SolvePair).
void BM_VelocityPair(benchmark::State& state) {
  omp_set_num_threads(int(state.range(0)));
  const SeparableHelmholtz solver(kGrid, Walls(), 1.0 / 4e-4, 0.005, 2);
  const std::vector<double> fu = Smooth(kGrid, 0.0), fv = Smooth(kGrid, 1.0);
  std::vector<double> u(kGrid.NodeCount(), 0.0), v(kGrid.NodeCount(), 0.0);
  for (auto _ : state) {
    solver.SolvePair(fu.data(), u.data(), fv.data(), v.data());
    benchmark::DoNotOptimize(u.data());
    benchmark::DoNotOptimize(v.data());
  }
}
BENCHMARK(BM_VelocityPair)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Divergence(benchmark::State& state) {
  omp_set_num_threads(int(state.range(0)));
  const std::vector<double> u = Smooth(kGrid, 0.0), v = Smooth(kGrid, 1.0);
  std::vector<double> out(kGrid.Coarse().NodeCount());
  for (auto _ : state) {
    ApplyDivergence(kGrid, NeumannAllRound(), u.data(), v.data(), out.data());
    benchmark::DoNotOptimize(out.data());
  }
}
BENCHMARK(BM_Divergence)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DivergenceTranspose(benchmark::State& state) {
  omp_set_num_threads(int(state.range(0)));
  const std::vector<double> p = Smooth(kGrid.Coarse(), 0.0);
  std::vector<double> ou(kGrid.NodeCount()), ov(kGrid.NodeCount());
  for (auto _ : state) {
    ApplyDivergenceTranspose(kGrid, NeumannAllRound(), p.data(), ou.data(), ov.data());
    benchmark::DoNotOptimize(ou.data());
    benchmark::DoNotOptimize(ov.data());
  }
}
BENCHMARK(BM_DivergenceTranspose)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Stiffness(benchmark::State& state) {
  omp_set_num_threads(int(state.range(0)));
  const std::vector<double> u = Smooth(kGrid, 0.0);
  std::vector<double> out(kGrid.NodeCount());
  for (auto _ : state) {
    ApplyStiffness(kGrid, Walls(), u.data(), out.data());
    benchmark::DoNotOptimize(out.data());
  }
}
BENCHMARK(BM_Stiffness)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace dlmfd

BENCHMARK_MAIN();
