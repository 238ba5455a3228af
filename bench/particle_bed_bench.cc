// A fluidized bed of 100 to 1,000 disks (issue 34, point 4; docs/evidence/performance.md, "A
// thousand particles"): cases/fluidized_bed_1000.toml (8 x 20, h = 1/96, 1.48 M velocity nodes, D =
// 0.2, the liquid and inflow of paper 5.4, the engine's defaults) with its first n disks (the
// lowest n / 25 rows of its lattice), and n = 0 for the same grid without particles. Full steps
// from rest, kSetUpSteps untimed and then kTimedSteps timed (steps 21-25, past the start from
// rest, whose steps take more Uzawa iterations while the lagged multiplier builds up), on 1
// or 2 threads (the second argument; with 1 thread the CPU column is the step's CPU time, which a
// shared machine's load changes less than the wall time). Counters: the sub-steps' ms (StepReport,
// wall), the multiplier CG's iterations (dlm_its), the particle step's ms per disk. Expected:
// ms_particles / n flat in n (cell lists for collisions, per-point stencils: nothing of the
// particle step is all-pairs), dlm_its not growing with n.
//   OMP_WAIT_POLICY=passive build/bench/particle_bed_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <string>

#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"
#include "step_averages.h"

namespace dlmfd {
namespace {

constexpr int kSetUpSteps = 20;
constexpr int kTimedSteps = 5;

void BM_Bed(benchmark::State& state) {
  Params p = LoadSceneFile(std::string(DLMFD_SOURCE_DIR) + "/cases/fluidized_bed_1000.toml");
  p.output.fields_every = 0.0;
  p.threads = static_cast<int>(state.range(1));
  const auto count = static_cast<std::size_t>(state.range(0));
  p.particles.resize(count);
  TimeFullSteps(state, p, kSetUpSteps);
  if (count > 0)
    state.counters["ms_particles_per_disk"] = state.counters["ms_particles"].value / double(count);
}

BENCHMARK(BM_Bed)
    ->ArgNames({"n", "threads"})
    ->ArgsProduct({{0, 100, 250, 500, 1000}, {1, 2}})
    ->Iterations(kTimedSteps)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace dlmfd
BENCHMARK_MAIN();
