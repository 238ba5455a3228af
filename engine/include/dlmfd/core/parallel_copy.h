// Copies and fills of node arrays shared by the OpenMP team (issue 34): on the paper's grid a
// std::copy of one velocity component (148k doubles) is about 0.1 ms on one core, and the wave
// step made six of them outside its parallel loops, 15 % of its instructions run on one thread
// (docs/evidence/performance.md, "Threads"); the Stokes step's fills and copies were 2.6 % of its
// instructions. The static schedule gives every thread a contiguous
// piece; the values are copied unchanged, so results do not depend on the team.
#pragma once

namespace dlmfd {

inline void ParallelCopy(const double* from, long count, double* to) {
#pragma omp parallel for schedule(static)
  for (long k = 0; k < count; ++k) to[k] = from[k];
}

inline void ParallelFill(double* to, long count, double value) {
#pragma omp parallel for schedule(static)
  for (long k = 0; k < count; ++k) to[k] = value;
}

}  // namespace dlmfd
