// ComponentPair: the two components (x and y, or u and v) of a point's force or a slot's velocity
// as one two-lane SSE2 value (GCC vector extension), so that the coupling operator E, its
// transpose and the multiplier CG's dot products move both with one instruction. Per lane the
// products and sums are those of the scalar code in the same order (no FMA on the baseline
// target), so the results are the same bits (docs/evidence/performance.md, "A thousand
// particles"). Loads and stores need no alignment beyond a double's.
#pragma once

#include <cstring>

namespace dlmfd {

using ComponentPair = double __attribute__((vector_size(16)));

inline ComponentPair LoadPair(const double* at) {
  ComponentPair pair;
  std::memcpy(&pair, at, sizeof(pair));
  return pair;
}

inline void StorePair(double* at, ComponentPair pair) { std::memcpy(at, &pair, sizeof(pair)); }

}  // namespace dlmfd
