// The sum of term(k) over k in [0, n) on the OpenMP team, in an order that does not depend on the
// team's size.
//
// [0, n) is cut into kOrderedSumBlocks fixed blocks (block b holds [b n / B, (b + 1) n / B));
// each block is summed in order of k by one thread (the blocks shared out by
// `#pragma omp for schedule(static)`), and the blocks' sums are added in the order of the blocks.
// An OpenMP reduction(+) adds the threads' sums in the order they finish, so two runs of one scene
// on 3 or more threads could differ in the last bits (issue 38, reproducible runs); summing per
// thread would give other bits on every team size. Fixed blocks give the same bits on 1, 2 or any
// number of threads (issue 34, point 5). Allocates nothing: the time loop must not.
#pragma once

namespace dlmfd {

inline constexpr long kOrderedSumBlocks = 256;

template <class Term>
double OrderedSum(long n, const Term& term) {
  double partials[kOrderedSumBlocks];
#pragma omp parallel for schedule(static)
  for (long b = 0; b < kOrderedSumBlocks; ++b) {
    const long begin = b * n / kOrderedSumBlocks, end = (b + 1) * n / kOrderedSumBlocks;
    double s = 0.0;
    for (long k = begin; k < end; ++k) s += term(k);
    partials[b] = s;
  }
  double sum = 0.0;
  for (long b = 0; b < kOrderedSumBlocks; ++b) sum += partials[b];
  return sum;
}

}  // namespace dlmfd
