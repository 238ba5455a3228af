// Shared by the full-step benchmarks: an Observer that averages StepReport entries (per-substep
// milliseconds, iteration counts) over the timed steps and writes them as Google Benchmark
// counters, with the velocity node updates per second (nodes x steps / wall time); and
// TimeFullSteps, the timing loop of a full Oldroyd-B step with particles.
#pragma once

#include <benchmark/benchmark.h>
#include <omp.h>

#include <string>
#include <utility>
#include <vector>

#include "dlmfd/core/observer.h"
#include "dlmfd/core/simulation.h"
#include "dlmfd/core/state.h"

namespace dlmfd {

class StepAverages : public Observer {
 public:
  // (StepReport entry, counter name) pairs; an entry a step does not report counts as 0.
  explicit StepAverages(std::vector<std::pair<std::string, std::string>> entries)
      : entries_(std::move(entries)),
        sums_(entries_.size(), 0.0) {}

  void OnStep(const FlowState&, const StepReport& report) override {
    for (std::size_t k = 0; k < entries_.size(); ++k) sums_[k] += report.Get(entries_[k].first);
    ++steps_;
  }

  // Forget the set-up steps: call just before the timed loop.
  void Reset() {
    sums_.assign(entries_.size(), 0.0);
    steps_ = 0;
  }

  void Write(benchmark::State& state, double velocity_nodes) const {
    if (steps_ == 0) return;
    for (std::size_t k = 0; k < entries_.size(); ++k)
      state.counters[entries_[k].second] = sums_[k] / steps_;
    state.counters["node_updates_per_s"] =
        benchmark::Counter(velocity_nodes * steps_, benchmark::Counter::kIsRate);
  }

 private:
  std::vector<std::pair<std::string, std::string>> entries_;
  std::vector<double> sums_;
  long steps_ = 0;
};

// The entries of a full Oldroyd-B step with particles: the four substeps' milliseconds and the
// Uzawa, wave and DLM CG counts (and the outer iterations of splitting.constraint = "viscous").
inline std::vector<std::pair<std::string, std::string>> FullStepEntries() {
  return {{"ms_stokes", "ms_stokes"},
          {"ms_advection", "ms_advection"},
          {"ms_conformation", "ms_conformation"},
          {"ms_particles", "ms_particles"},
          {"stokes_iterations", "stokes_its"},
          {"wave_substeps", "wave_substeps"},
          {"multiplier_iterations", "dlm_its"},
          {"coupling_iterations", "coupling_its"}};
}

// Runs `set_up_steps` steps of a simulation of `params` untimed, then times one step per benchmark
// iteration; counters: FullStepEntries, node updates per second, velocity_nodes. Restores the
// OpenMP thread count that Simulation set from params.threads.
inline void TimeFullSteps(benchmark::State& state, const Params& params, int set_up_steps) {
  Simulation sim(params);
  StepAverages averages(FullStepEntries());
  sim.AddObserver(&averages);
  for (int n = 0; n < set_up_steps; ++n) sim.Step();
  averages.Reset();
  for (auto _ : state) sim.Step();
  const double nodes = static_cast<double>(sim.grid().NodeCount());
  averages.Write(state, nodes);
  state.counters["velocity_nodes"] = nodes;
  omp_set_num_threads(omp_get_num_procs());
}

}  // namespace dlmfd
