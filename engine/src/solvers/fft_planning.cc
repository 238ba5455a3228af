#include "dlmfd/solvers/fft_planning.h"

#include <fftw3.h>

#include <atomic>

namespace dlmfd {
namespace {

std::atomic<FftPlanning> g_planning{FftPlanning::kDeterministic};

// Below this many points a measured plan gained nothing measurable (issue 12).
constexpr std::size_t kMeasuredAbove = 4096;

}  // namespace

void SetFftPlanning(FftPlanning planning) { g_planning.store(planning); }

FftPlanning GetFftPlanning() { return g_planning.load(); }

unsigned FftwPlannerFlags(std::size_t points) {
  if (g_planning.load() == FftPlanning::kMeasured && points > kMeasuredAbove) return FFTW_MEASURE;
  return FFTW_ESTIMATE;
}

}  // namespace dlmfd
