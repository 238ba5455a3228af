// The time stepping of Simulation (paper section 4) as rules on a scene: the Marchuk-Yanenko
// weights and the step and output counts that the loop supports. The scene validation
// (scene/scene_validation.h) applies them to every scene; Simulation's constructor applies them
// again as its guard, so each rule has one definition.
//
// Splitting: the viscous term is shared as alpha in (33), beta in (34) and gamma = 1 - alpha - beta
// in (37). Supported: gamma = 0 (the paper's choice: no viscosity in the DLM step (37)) with
// alpha > 0 (the Stokes step (33) needs viscosity for its fast Helmholtz solver); with particles
// and splitting.constraint = "viscous" or "incremental" also beta = 0, alpha = 1: the constraint
// meets the viscosity in (33) (particles/viscous_constraint.h, particles/lagged_multiplier.h), and
// viscosity in (34), which does not see the particles, would leak through them as in the paper's
// scheme (a scene without particles has no constraint, and any weights). Steps: the run makes n =
// round(end / dt) steps and computes t_n = n dt and the output period index n dt / every in double,
// which counts integers exactly only up to 2^53 (kMaxStepCount); a longer count would be rounded,
// or overflow the long that holds it, so it is refused.
#pragma once

#include <cmath>

#include "dlmfd/core/params.h"

namespace dlmfd {

// 2^53: the largest step count and output period index the loop counts exactly.
inline constexpr double kMaxStepCount = 9007199254740992.0;

// n = round(end / dt), the number of steps of a run (valid for a time that passed
// ValidateTimeSteps).
inline long StepCount(const TimeParams& time) {
  return static_cast<long>(std::llround(time.end / time.dt));
}

// The index of the output period that t_n = n dt falls in, floor(n dt / every) (every > 0; a
// 1e-9 allowance lets a period that ends on a step count that step); deterministic in n. An
// output is due at step n when the index grows from step n - 1.
inline long OutputPeriod(long n, double dt, double every) {
  return static_cast<long>(std::floor(static_cast<double>(n) * dt / every + 1e-9));
}

// Whether an output of period `every` is due at step n (none when every <= 0).
inline bool OutputDue(long n, double dt, double every) {
  return every > 0.0 && OutputPeriod(n, dt, every) > OutputPeriod(n - 1, dt, every);
}

// The field snapshots a run writes with fields_every = `every`: the initial one and one per
// output period that ends by its last step, OutputPeriod(StepCount) + 1; 0 when every <= 0.
inline long SnapshotCount(const TimeParams& time, double every) {
  return every > 0.0 ? OutputPeriod(StepCount(time), time.dt, every) + 1 : 0;
}

// The rules between keys, for values already in their ranges (the key table's, scene/scene_keys.h:
// dt, end > 0; alpha in (0, 1], beta in [0, 1]; periods >= 0). scene::ValidateTimeStepping
// (scene/scene_validation.h) applies both, for the scene validation and Simulation alike.
// gamma = 1 - alpha - beta = 0; with particles, beta = 0 unless the constraint coupling is the
// paper's.
void ValidateSplitting(const SplittingParams& splitting, bool with_particles);
// dt <= end, end / dt <= kMaxStepCount.
void ValidateTimeSteps(const TimeParams& time);
// end / period <= kMaxStepCount for each period > 0 (0: none, or every step for particles).
void ValidateOutputPeriods(const TimeParams& time, const OutputParams& output);

}  // namespace dlmfd
