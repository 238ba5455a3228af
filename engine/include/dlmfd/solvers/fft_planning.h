// How the fast solvers' FFTW plans are chosen.
//
// kDeterministic (the default): FFTW_ESTIMATE, a plan that depends on the transform's sizes only,
// so every run of a scene, and a run resumed from any of its checkpoints, computes the same bits
// (issue 38). kMeasured: FFTW_MEASURE above 4096 points (the choice before issue 38): FFTW times
// candidate algorithms and keeps the fastest, which a loaded machine can change from one run to
// the next, so two runs agreed only to round-off. What the deterministic choice costs per time step
// on the paper's grid is in docs/evidence/performance.md, "FFTW plans and reproducibility"
// (bench/oldroyd_b_step_bench, its planning argument). Set before any solver is built; plans made
// before keep theirs.
#pragma once

#include <cstddef>

namespace dlmfd {

enum class FftPlanning { kDeterministic, kMeasured };

void SetFftPlanning(FftPlanning planning);
FftPlanning GetFftPlanning();
// The FFTW planner flags for a batch of `points` values under the current choice.
unsigned FftwPlannerFlags(std::size_t points);

}  // namespace dlmfd
