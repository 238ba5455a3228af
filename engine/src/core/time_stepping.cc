#include "dlmfd/core/time_stepping.h"

#include <cmath>
#include <string>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"

namespace dlmfd {
namespace {

// Throws for `key` when end / period is beyond kMaxStepCount; `what` names the count.
void RequireCountable(const std::string& key, double period, double end, const std::string& what) {
  const double count = end / period;
  if (!(count <= kMaxStepCount)) {
    throw InvalidParameter(key, ExactText(period),
                           "at least time.end / 2^53 = " + ShortText(end / kMaxStepCount) +
                               " (time.end / " + key + " = " + ShortText(count) + " " + what +
                               "; the time loop counts them exactly only up to 2^53)");
  }
}

}  // namespace

void ValidateSplitting(const SplittingParams& s, bool with_particles) {
  if (std::abs(s.alpha + s.beta - 1.0) > 1e-12) {
    throw InvalidParameter(
        "splitting.beta", ExactText(s.beta),
        "1 - splitting.alpha = " + ExactText(1.0 - s.alpha) +
            " (gamma = 1 - alpha - beta must be 0: the only splitting the engine supports)");
  }
  const ConstraintCoupling constraint = s.constraint.value();
  if (with_particles && constraint != ConstraintCoupling::kPaper && s.beta != 0.0) {
    throw InvalidParameter(
        "splitting.beta", ExactText(s.beta),
        std::string("0 (and splitting.alpha = 1) with splitting.constraint = \"") +
            (constraint == ConstraintCoupling::kViscous ? "viscous" : "incremental") +
            "\": the advection step (34) does not see the particles, so viscosity there "
            "would leak through them; or splitting.constraint = \"paper\"");
  }
}

void ValidateTimeSteps(const TimeParams& time) {
  if (time.dt > time.end) {
    throw InvalidParameter("time.dt", ExactText(time.dt),
                           "a step <= time.end = " + ExactText(time.end));
  }
  RequireCountable("time.dt", time.dt, time.end, "steps");
}

void ValidateOutputPeriods(const TimeParams& time, const OutputParams& output) {
  const struct {
    const char* key;
    double every;
  } periods[3] = {{"output.fields_every", output.fields_every},
                  {"output.particles_every", output.particles_every},
                  {"output.checkpoint_every", output.checkpoint_every}};
  for (const auto& p : periods) {
    if (p.every > 0.0) RequireCountable(p.key, p.every, time.end, "output periods");
  }
}

}  // namespace dlmfd
