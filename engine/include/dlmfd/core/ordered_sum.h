// The sum of term(k) over k in [0, n) on the OpenMP team, in an order fixed by the team's size.
//
// Each thread sums its static block of k (as `#pragma omp for schedule(static)` gives it) and the
// blocks' sums are added in the order of the threads. An OpenMP reduction(+) adds the threads' sums
// in the order they finish: with 3 or more threads two runs of one scene could differ in the last
// bits (issue 38, reproducible runs). With 1 or 2 threads the result equals that reduction's
// ((0 + a) + b = (0 + b) + a in IEEE arithmetic). Allocates nothing: the time loop must not.
#pragma once

#include <omp.h>

#include <algorithm>

namespace dlmfd {

inline constexpr int kMaxOrderedSumThreads = 256;

template <class Term>
double OrderedSum(long n, const Term& term) {
  struct alignas(64) Partial {
    double value;
  };
  Partial partials[kMaxOrderedSumThreads];
  int team = 1;
#pragma omp parallel num_threads(std::min(omp_get_max_threads(), kMaxOrderedSumThreads))
  {
    double s = 0.0;
#pragma omp for schedule(static) nowait
    for (long k = 0; k < n; ++k) s += term(k);
    partials[omp_get_thread_num()].value = s;
#pragma omp single nowait
    team = omp_get_num_threads();
  }
  double sum = 0.0;
  for (int t = 0; t < team; ++t) sum += partials[t].value;
  return sum;
}

}  // namespace dlmfd
