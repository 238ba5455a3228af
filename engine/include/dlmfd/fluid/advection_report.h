// What one solve of step (34) reports, whichever scheme ran it (velocity_advection.h).
#pragma once

namespace dlmfd {

struct AdvectionReport {
  int iterations = 0;      // LS-CG iterations, or wave sub-steps
  double residual = 0.0;   // LS-CG: final sqrt(g.r / g0.r0); wave: 0
  double fast_solves = 0;  // scalar fast solves used
};

}  // namespace dlmfd
