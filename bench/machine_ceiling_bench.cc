// What a second thread can gain on this machine, whatever the solver does (issue 34, point 1;
// docs/evidence/performance.md, "Threads"): the ceilings a sub-step meets, measured alone.
//   BM_Triad/threads:T/kib:K   STREAM's triad a[i] = b[i] + s c[i] (McCalpin 1995) over three
//                              arrays of K KiB each, the team splitting the range statically;
//                              bytes_per_second counts the 3 K KiB read and written a pass.
//                              K = 1160 is one velocity node array of the 5.2 pair on the paper's
//                              grid (193 x 769 doubles): three need the shared L3 (32 MiB), as do 8
//                              MiB arrays; 64 MiB arrays stream from memory, 64 KiB ones stay in
//                              L2.
//   BM_Latency/threads:T       a polynomial of degree 64 by Horner per element of a 64 KiB array:
//                              one dependent chain per element, bound by the adder's latency.
//   BM_Throughput/threads:T    the same, 16 elements' chains interleaved: bound by the arithmetic
//                              units' throughput. Two cores give both 2.0; two hardware threads of
//                              one core (SMT siblings that a VM shows as two cores) give the
//                              latency-bound kernel about 2 and the throughput-bound one about 1.
//   BM_ForkJoin/threads:T      an empty `omp parallel for` of 2 T items: a region's fork and its
//                              closing barrier (a solver's loop pays this once per loop).
//   BM_Barrier/threads:T       one `omp barrier` inside a region that stays open.
// The speed-up S of a kind of work is its 1-thread time over its 2-thread time; a sub-step that is
// a mix cannot gain more than its kinds' S weighted by their shares of its time.
//   OMP_WAIT_POLICY=active build/bench/machine_ceiling_bench --benchmark_repetitions=5
//     --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace {

constexpr int kDegree = 64;
constexpr std::size_t kComputeDoubles = 8192;  // 64 KiB
constexpr std::size_t kChains = 16;
constexpr int kBarriersPerRegion = 1000;

int Threads(const benchmark::State& state) { return static_cast<int>(state.range(0)); }

void BM_Triad(benchmark::State& state) {
  const int threads = Threads(state);
  const auto n = static_cast<std::int64_t>(state.range(1)) * 1024 / 8;
  std::vector<double> a(static_cast<std::size_t>(n));
  std::vector<double> b(a.size());
  std::vector<double> c(a.size());
  // First touch by the team that will stream them, as the solver's arrays are used.
#pragma omp parallel for schedule(static) num_threads(threads)
  for (std::int64_t i = 0; i < n; ++i) {
    a[i] = 0.0;
    b[i] = 1.0 + 1e-9 * static_cast<double>(i);
    c[i] = 2.0;
  }
  const double s = 0.5;
  for (auto _ : state) {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * n * 3 * static_cast<std::int64_t>(sizeof(double)));
}

void BM_Latency(benchmark::State& state) {
  const int threads = Threads(state);
  std::vector<double> x(kComputeDoubles, 0.5);
  std::vector<double> y(x.size(), 0.0);
  const auto n = static_cast<std::int64_t>(x.size());
  for (auto _ : state) {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t i = 0; i < n; ++i) {
      double p = 1.0;
      for (int k = 0; k < kDegree; ++k) p = p * x[i] + 1.0 / (k + 1);
      y[i] = p;
    }
    benchmark::DoNotOptimize(y.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kComputeDoubles));
}

void BM_Throughput(benchmark::State& state) {
  const int threads = Threads(state);
  std::vector<double> x(kComputeDoubles, 0.5);
  std::vector<double> y(x.size(), 0.0);
  const auto blocks = static_cast<std::int64_t>(x.size() / kChains);
  for (auto _ : state) {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t b = 0; b < blocks; ++b) {
      const double* xb = x.data() + b * kChains;
      double p[kChains];
      for (std::size_t j = 0; j < kChains; ++j) p[j] = 1.0;
      for (int k = 0; k < kDegree; ++k) {
        const double c = 1.0 / (k + 1);
        for (std::size_t j = 0; j < kChains; ++j) p[j] = p[j] * xb[j] + c;
      }
      for (std::size_t j = 0; j < kChains; ++j) y[static_cast<std::size_t>(b) * kChains + j] = p[j];
    }
    benchmark::DoNotOptimize(y.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kComputeDoubles));
}

void BM_ForkJoin(benchmark::State& state) {
  const int threads = Threads(state);
  std::vector<int> touched(static_cast<std::size_t>(2 * threads), 0);
  const auto n = static_cast<std::int64_t>(touched.size());
  for (auto _ : state) {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t i = 0; i < n; ++i) touched[i] += 1;
    benchmark::DoNotOptimize(touched.data());
  }
}

void BM_Barrier(benchmark::State& state) {
  const int threads = Threads(state);
  for (auto _ : state) {
#pragma omp parallel num_threads(threads)
    for (int k = 0; k < kBarriersPerRegion; ++k) {
#pragma omp barrier
    }
  }
  state.SetItemsProcessed(state.iterations() * kBarriersPerRegion);
}

BENCHMARK(BM_Triad)
    ->ArgNames({"threads", "kib"})
    ->ArgsProduct({{1, 2}, {64, 1160, 8192, 65536}})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Latency)->ArgNames({"threads"})->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK(BM_Throughput)->ArgNames({"threads"})->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK(BM_ForkJoin)->ArgNames({"threads"})->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK(BM_Barrier)
    ->ArgNames({"threads"})
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
BENCHMARK_MAIN();
