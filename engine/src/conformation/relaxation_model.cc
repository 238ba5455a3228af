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
