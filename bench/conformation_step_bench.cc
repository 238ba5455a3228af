// Cost of step (35) (ConformationStep::Advance) on the paper's grid: 2 x 8 with h = 1/96, that is
// 193 x 769 velocity nodes, dt = 4e-4, Oldroyd-B with lambda = 1.4 (paper 5.2), and a velocity
// field like a disk of diameter 0.2 falling at 1.5 (a divergence-free vortex dipole around the
// disk, no slip on the walls) with A = I inside the disk. Run with 1 and 2 threads:
//   build/bench/conformation_step_bench --benchmark_counters_tabular=true
// Reports wall time per step (ms), node updates per second and the sub-step count. The second
// argument is the variant: 0 Oldroyd-B standard (the paper's), 1 Oldroyd-B log, 2 Oldroyd-B sqrt,
// 3 Giesekus (alpha 0.1) standard, 4 FENE-P (L^2 100) standard (fluid.model, fluid.conformation).
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <vector>

#include "dlmfd/conformation/conformation_step.h"

namespace dlmfd {
namespace {

struct PaperCase {
  Params params;
  Grid grid{192, 768, 1.0 / 96.0, 0.0, 0.0};
  std::vector<double> u, v, a11, a12, a22;
  std::vector<unsigned char> inside;

  explicit PaperCase(int variant) {
    params.domain.size = Vec2(2.0, 8.0);
    params.domain.h = 1.0 / 96.0;
    params.domain.diagonals = MeshDiagonals::kSwNe;                  // as measured in docs/
    params.domain.sides[int(Side::kTop)].type = SideType::kOutflow;  // walls elsewhere
    params.fluid.viscosity = 0.12;
    params.fluid.relaxation_time = 1.4;
    params.fluid.solvent_ratio = 0.5;
    params.time.dt = 4e-4;
    if (variant == 1) params.fluid.conformation = ConformationRepresentation::kLog;
    if (variant == 2) params.fluid.conformation = ConformationRepresentation::kSqrt;
    if (variant == 3) {
      params.fluid.model = ConstitutiveModel::kGiesekus;
      params.fluid.mobility = 0.1;
    }
    if (variant == 4) {
      params.fluid.model = ConstitutiveModel::kFeneP;
      params.fluid.extensibility = 100.0;
    }
    const std::size_t n = grid.NodeCount();
    u.assign(n, 0.0);
    v.assign(n, 0.0);
    a11.assign(n, 1.0);
    a12.assign(n, 0.0);
    a22.assign(n, 1.0);
    inside.assign(n, 0);
    // Stream function psi = U (x - xc) exp(-r^2 / s^2): a jet of speed U downwards through the
    // disk and the return flow beside it; u = dpsi/dy, v = -dpsi/dx (divergence-free).
    const double xc = 1.0, yc = 6.0, speed = 1.5, s = 0.3, radius = 0.1;
    for (int j = 0; j <= grid.ny; ++j) {
      for (int i = 0; i <= grid.nx; ++i) {
        const double x = grid.X(i) - xc, y = grid.Y(j) - yc;
        const double g = std::exp(-(x * x + y * y) / (s * s));
        const std::size_t k = grid.Index(i, j);
        u[k] = -2.0 * speed * x * y * g / (s * s);
        v[k] = -speed * g * (1.0 - 2.0 * x * x / (s * s));
        inside[k] = (x * x + y * y < radius * radius) ? 1 : 0;
        if (i == 0 || i == grid.nx || j == 0) u[k] = v[k] = 0.0;  // walls
      }
    }
  }
};

void BM_ConformationStep(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  PaperCase c(static_cast<int>(state.range(1)));
  ConformationStep step(c.params, c.grid);
  StepReport report;
  const double dt = c.params.time.dt;
  long n = 0;
  // 20 warm-up steps so that A carries stress before timing.
  for (; n < 20; ++n) {
    step.Advance(n * dt, dt, c.u.data(), c.v.data(), c.inside.data(), c.a11.data(), c.a12.data(),
                 c.a22.data(), report);
  }
  for (auto _ : state) {
    step.Advance(n * dt, dt, c.u.data(), c.v.data(), c.inside.data(), c.a11.data(), c.a12.data(),
                 c.a22.data(), report);
    ++n;
  }
  state.counters["node_updates_per_s"] = benchmark::Counter(
      static_cast<double>(c.grid.NodeCount()) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["substeps"] = report.Get("conformation_substeps");
  state.counters["max_trA"] = report.Get("max_trA");
  state.counters["threads"] = static_cast<double>(state.range(0));
  state.counters["variant"] = static_cast<double>(state.range(1));
}
BENCHMARK(BM_ConformationStep)
    ->ArgsProduct({{1, 2}, {0, 1, 2, 3, 4}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace dlmfd

BENCHMARK_MAIN();
