#include "dlmfd/conformation/relaxation_model.h"

#include <string>

#include "dlmfd/conformation/fene_p_relaxation.h"
#include "dlmfd/conformation/giesekus_relaxation.h"
#include "dlmfd/conformation/oldroyd_b_relaxation.h"
#include "dlmfd/conformation/ptt_relaxation.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"
#include "dlmfd/core/param_words.h"

namespace dlmfd {
namespace {

std::string Quoted(const char* word) { return std::string("\"") + word + "\""; }

// A model parameter: required for its own model, rejected for any other.
void CheckParameter(const FluidParams& f, const std::optional<double>& value, const char* key,
                    const char* models, bool used, const std::string& range) {
  const std::string full = std::string("fluid.") + key;
  if (!used) {
    if (value.has_value()) {
      throw InvalidParameter(full, ExactText(*value),
                             std::string("no value with fluid.model = ") +
                                 Quoted(ModelName(f.model)) + " (" + key + " is a parameter of " +
                                 models + " only)");
    }
    return;
  }
  if (!value.has_value()) {
    throw InvalidParameter(full, "(absent)",
                           range + ", required with fluid.model = " + Quoted(ModelName(f.model)));
  }
}

}  // namespace

const char* ModelName(ConstitutiveModel m) { return WordOf(m); }

const char* RepresentationName(ConformationRepresentation r) { return WordOf(r); }

std::unique_ptr<RelaxationModel> MakeRelaxationModel(const FluidParams& fluid) {
  switch (fluid.model) {
    case ConstitutiveModel::kOldroydB:
      return std::make_unique<OldroydBRelaxation>();
    case ConstitutiveModel::kGiesekus:
      return std::make_unique<GiesekusRelaxation>(fluid.mobility.value_or(0.0));
    case ConstitutiveModel::kFeneP:
      return std::make_unique<FenePRelaxation>(fluid.extensibility.value_or(0.0));
    case ConstitutiveModel::kPttLinear:
      return std::make_unique<PttRelaxation>(fluid.ptt_epsilon.value_or(0.0), false);
    case ConstitutiveModel::kPttExponential:
      return std::make_unique<PttRelaxation>(fluid.ptt_epsilon.value_or(0.0), true);
  }
  return std::make_unique<OldroydBRelaxation>();
}

void ValidateConstitutiveModel(const FluidParams& f) {
  const bool giesekus = f.model == ConstitutiveModel::kGiesekus;
  const bool fene_p = f.model == ConstitutiveModel::kFeneP;
  const bool ptt =
      f.model == ConstitutiveModel::kPttLinear || f.model == ConstitutiveModel::kPttExponential;
  CheckParameter(f, f.mobility, "mobility", "\"giesekus\"", giesekus, "a number in [0, 0.5]");
  CheckParameter(f, f.extensibility, "extensibility", "\"fene_p\"", fene_p,
                 "a number > 2 (L^2; tr A < L^2, and A = I needs tr I = 2 < L^2)");
  CheckParameter(f, f.ptt_epsilon, "ptt_epsilon", "\"ptt_linear\" and \"ptt_exponential\"", ptt,
                 "a number >= 0");
  if (giesekus && !(*f.mobility >= 0.0 && *f.mobility <= 0.5)) {
    throw InvalidParameter("fluid.mobility", ExactText(*f.mobility),
                           "a number in [0, 0.5] (Giesekus alpha; above 0.5 the steady shear "
                           "stress is not monotone in the shear rate)");
  }
  if (fene_p && !(*f.extensibility > 2.0 && std::isfinite(*f.extensibility))) {
    throw InvalidParameter("fluid.extensibility", ExactText(*f.extensibility),
                           "a finite number > 2 (FENE-P L^2 with tr A < L^2; the rest state A = I "
                           "has tr A = 2)");
  }
  if (ptt && !(*f.ptt_epsilon >= 0.0 && std::isfinite(*f.ptt_epsilon))) {
    throw InvalidParameter("fluid.ptt_epsilon", ExactText(*f.ptt_epsilon),
                           "a finite number >= 0 (0 is Oldroyd-B)");
  }
  if (f.IsNewtonian()) {
    const std::string newtonian =
        " for a Newtonian liquid (fluid.relaxation_time = 0 or fluid.solvent_ratio = 1: there is "
        "no polymer)";
    if (f.model != ConstitutiveModel::kOldroydB) {
      throw InvalidParameter("fluid.model", Quoted(ModelName(f.model)),
                             "\"oldroyd_b\" (the default)" + newtonian);
    }
    if (f.conformation != ConformationRepresentation::kStandard) {
      throw InvalidParameter("fluid.conformation", Quoted(RepresentationName(f.conformation)),
                             "\"standard\" (the default)" + newtonian);
    }
  }
}

}  // namespace dlmfd
