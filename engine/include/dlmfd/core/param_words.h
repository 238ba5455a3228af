// The scene word of each value of the enums of core/params.h, declared once (issue 39): the scene
// reader and writer (scene/scene_keys.h), the messages that name a value and the docs' key table
// take them from here. Words<Enum>::kAll lists them in the order the messages and docs show.
#pragma once

#include <optional>
#include <string>

#include "dlmfd/core/params.h"

namespace dlmfd {

template <typename Enum>
struct Word {
  const char* text;
  Enum value;
};

// Specialised for every enum a scene key sets.
template <typename Enum>
struct Words;

template <>
struct Words<SideType> {
  static constexpr Word<SideType> kAll[] = {{"wall", SideType::kWall},
                                            {"velocity", SideType::kVelocity},
                                            {"outflow", SideType::kOutflow},
                                            {"periodic", SideType::kPeriodic}};
};
template <>
struct Words<Profile> {
  static constexpr Word<Profile> kAll[] = {{"uniform", Profile::kUniform},
                                           {"poiseuille", Profile::kPoiseuille},
                                           {"quartic", Profile::kQuartic}};
};
template <>
struct Words<MeshDiagonals> {
  static constexpr Word<MeshDiagonals> kAll[] = {{"sw_ne", MeshDiagonals::kSwNe},
                                                 {"both", MeshDiagonals::kBoth}};
};
template <>
struct Words<ConstitutiveModel> {
  static constexpr Word<ConstitutiveModel> kAll[] = {
      {"oldroyd_b", ConstitutiveModel::kOldroydB},
      {"giesekus", ConstitutiveModel::kGiesekus},
      {"fene_p", ConstitutiveModel::kFeneP},
      {"ptt_linear", ConstitutiveModel::kPttLinear},
      {"ptt_exponential", ConstitutiveModel::kPttExponential}};
};
template <>
struct Words<ConformationRepresentation> {
  static constexpr Word<ConformationRepresentation> kAll[] = {
      {"standard", ConformationRepresentation::kStandard},
      {"log", ConformationRepresentation::kLog},
      {"sqrt", ConformationRepresentation::kSqrt}};
};
template <>
struct Words<StressSplitting> {
  static constexpr Word<StressSplitting> kAll[] = {{"explicit", StressSplitting::kExplicit},
                                                   {"devss", StressSplitting::kDevss}};
};
template <>
struct Words<AdvectionScheme> {
  static constexpr Word<AdvectionScheme> kAll[] = {
      {"least_squares", AdvectionScheme::kLeastSquares}, {"wave", AdvectionScheme::kWave}};
};
template <>
struct Words<SteadyCorrection> {
  static constexpr Word<SteadyCorrection> kAll[] = {{"none", SteadyCorrection::kNone},
                                                    {"taylor", SteadyCorrection::kTaylor},
                                                    {"tendency", SteadyCorrection::kTendency}};
};
template <>
struct Words<ConstraintCoupling> {
  static constexpr Word<ConstraintCoupling> kAll[] = {
      {"incremental", ConstraintCoupling::kIncremental},
      {"paper", ConstraintCoupling::kPaper},
      {"viscous", ConstraintCoupling::kViscous}};
};
template <>
struct Words<Motion> {
  static constexpr Word<Motion> kAll[] = {
      {"free", Motion::kFree}, {"fixed", Motion::kFixed}, {"prescribed", Motion::kPrescribed}};
};
template <>
struct Words<ShapeKind> {
  static constexpr Word<ShapeKind> kAll[] = {{"disk", ShapeKind::kDisk},
                                             {"ellipse", ShapeKind::kEllipse}};
};
template <>
struct Words<ParticleMeshKind> {
  static constexpr Word<ParticleMeshKind> kAll[] = {{"ring", ParticleMeshKind::kRing},
                                                    {"collocation", ParticleMeshKind::kCollocation},
                                                    {"cut_cell", ParticleMeshKind::kCutCell}};
};
template <>
struct Words<BoundaryInterpolation> {
  static constexpr Word<BoundaryInterpolation> kAll[] = {
      {"quadratic", BoundaryInterpolation::kQuadratic},
      {"linear", BoundaryInterpolation::kLinear},
      {"biquadratic", BoundaryInterpolation::kBiquadratic}};
};
template <>
struct Words<MultiplierPreconditioning> {
  static constexpr Word<MultiplierPreconditioning> kAll[] = {
      {"blocks", MultiplierPreconditioning::kBlocks}, {"gram", MultiplierPreconditioning::kGram}};
};
template <>
struct Words<ConformationVelocity> {
  static constexpr Word<ConformationVelocity> kAll[] = {
      {"advected", ConformationVelocity::kAdvected}, {"stokes", ConformationVelocity::kStokes}};
};
template <>
struct Words<ConformationForm> {
  static constexpr Word<ConformationForm> kAll[] = {{"A", ConformationForm::kA}};
};
template <>
struct Words<NumericsPreset> {
  static constexpr Word<NumericsPreset> kAll[] = {{"default", NumericsPreset::kDefault},
                                                  {"paper", NumericsPreset::kPaper}};
};

// The scene word of a value.
template <typename Enum>
const char* WordOf(Enum value) {
  for (const Word<Enum>& w : Words<Enum>::kAll) {
    if (w.value == value) return w.text;
  }
  return Words<Enum>::kAll[0].text;
}

// The value of a scene word, or nothing when it is none of the enum's words.
template <typename Enum>
std::optional<Enum> ValueOfWord(const std::string& text) {
  for (const Word<Enum>& w : Words<Enum>::kAll) {
    if (text == w.text) return w.value;
  }
  return std::nullopt;
}

}  // namespace dlmfd
