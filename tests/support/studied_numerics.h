// The numerics the engine's tests that build Params in code were written and studied with: the
// paper's SW-NE mesh (domain.diagonals = "sw_ne"), its least-squares step (34) without a
// steady-state correction, the lagged multiplier, and the paper's h_p = 1/70. Until issue 39 these
// were the defaults of Params{}; since then Params{} runs as an empty scene file does
// (numerics.preset = "default", scene::ResolveDefaults). A test that calls this, before setting its
// own values, checks what it checked before, with the tolerances its study derived.
#pragma once

#include "dlmfd/core/params.h"

namespace dlmfd::testing {

inline void UseStudiedNumerics(DomainParams& domain) { domain.diagonals = MeshDiagonals::kSwNe; }

// Step (34) of those tests: least squares, no steady-state correction (after a test replaces its
// SplittingParams, e.g. by SplittingParams::DefaultWeights).
// The constraint, where the test names none, is the struct's default of then: the lagged
// multiplier ("incremental"), not "auto".
inline void UseStudiedNumerics(SplittingParams& splitting) {
  if (!splitting.constraint) splitting.constraint = ConstraintCoupling::kIncremental;
  splitting.advection = AdvectionScheme::kLeastSquares;
  splitting.steady_correction = SteadyCorrection::kNone;
}

inline void UseStudiedNumerics(Params& p) {
  UseStudiedNumerics(p.domain);
  UseStudiedNumerics(p.splitting);
  p.particle_mesh.h = 1.0 / 70;
}

}  // namespace dlmfd::testing
