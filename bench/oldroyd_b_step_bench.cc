// ms per full Oldroyd-B time step with particles: Stokes (33), advection (34) by the wave-like
// scheme, conformation (35) and particles (36)-(38), on paper 5.2
// (cases/paper/5.2_pair_oldroyd_b.toml: two disks D = 0.2, rho_d = 1.01, in an Oldroyd-B liquid
// with eta = 0.12, lambda = 1.4, beta = 1/2, on the paper's grid 2 x 8, h = 1/96, dt = 4e-4), after
// 20 set-up steps from rest so that the disks move and the flow and the iteration counts are those
// of a developing flow (the scene's own advection, least squares, is replaced by the wave scheme).
// Arguments: threads, coupling (splitting.constraint: 0 paper, 1 viscous, 2 incremental), stress
// (fluid.stress_splitting: 0 explicit, 1 devss, the default), diagonals (domain.diagonals: 0 sw_ne,
// 1 both; both only with the default coupling and stress). BM_FftPlanning: threads, planning (0
// deterministic FFTW_ESTIMATE plans, the default; 1 FFTW_MEASURE above 4096 points, as before
// issue 38; solvers/fft_planning.h), at the default coupling, stress and diagonals.
// Counters: per-substep ms (StepReport ms_stokes, ms_advection, ms_conformation, ms_particles),
// Uzawa and DLM CG iterations, velocity node updates per second.
//   OMP_WAIT_POLICY=active build/bench/oldroyd_b_step_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <string>

#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"
#include "dlmfd/solvers/fft_planning.h"
#include "step_averages.h"

namespace dlmfd {
namespace {

constexpr int kSetUpSteps = 20;

Params PairScene(int threads) {
  Params p = LoadSceneFile(std::string(DLMFD_SOURCE_DIR) + "/cases/paper/5.2_pair_oldroyd_b.toml");
  p.splitting.advection = AdvectionScheme::kWave;
  p.output.fields_every = 0.0;
  p.threads = threads;
  return p;
}

// Arguments: threads, and the coupling of the constraint: 0 the paper's (alpha = beta = 1/2),
// 1 the constraint in the Stokes step (splitting.constraint = "viscous";
// particles/viscous_constraint.h), 2 the lagged multiplier (splitting.constraint = "incremental",
// the default; particles/lagged_multiplier.h); 1 and 2 with all the viscosity in (33), alpha = 1,
// beta = 0.
void BM_OldroydBStep(benchmark::State& state) {
  Params p = PairScene(static_cast<int>(state.range(0)));
  constexpr ConstraintCoupling kCouplings[] = {
      ConstraintCoupling::kPaper, ConstraintCoupling::kViscous, ConstraintCoupling::kIncremental};
  p.splitting = SplittingParams::DefaultWeights(kCouplings[state.range(1)]);
  p.splitting.advection = AdvectionScheme::kWave;
  p.fluid.stress_splitting =
      state.range(2) == 0 ? StressSplitting::kExplicit : StressSplitting::kDevss;
  p.domain.diagonals = state.range(3) == 0 ? MeshDiagonals::kSwNe : MeshDiagonals::kBoth;
  TimeFullSteps(state, p, kSetUpSteps);
}

BENCHMARK(BM_OldroydBStep)
    ->ArgNames({"threads", "coupling", "stress", "diagonals"})
    ->ArgsProduct({{1, 2}, {0, 1, 2}, {0, 1}, {0}})
    ->Args({1, 2, 1, 1})
    ->Args({2, 2, 1, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// The cost of deterministic FFTW plans (issue 38): the same step with each planner choice.
void BM_FftPlanning(benchmark::State& state) {
  SetFftPlanning(state.range(1) == 0 ? FftPlanning::kDeterministic : FftPlanning::kMeasured);
  Params p = PairScene(static_cast<int>(state.range(0)));
  TimeFullSteps(state, p, kSetUpSteps);
  SetFftPlanning(FftPlanning::kDeterministic);
}

BENCHMARK(BM_FftPlanning)
    ->ArgNames({"threads", "planning"})
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

}  // namespace
}  // namespace dlmfd
BENCHMARK_MAIN();
