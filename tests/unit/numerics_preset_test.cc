// numerics.preset (scene/numerics_preset.h): "paper" selects every choice of the paper at once, a
// key the scene sets wins over its preset, and the "default" preset's choices are the struct
// defaults of core/params.h.
#include "dlmfd/scene/numerics_preset.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "dlmfd/core/errors.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

using ::testing::HasSubstr;

const char* const kDiskInPolymer = R"TOML(
gravity = [0.0, -981.0]
[domain]
size = [1.0, 2.0]
h = 0.03125
[fluid]
viscosity = 0.1
relaxation_time = 0.1
solvent_ratio = 0.5
[time]
dt = 0.001
[[particles]]
center = [0.5, 1.5]
diameter = 0.2
density = 1.01
)TOML";

TEST(NumericsPreset, PaperSelectsEveryChoiceOfThePaper) {
  const Params p = ParseScene(std::string(kDiskInPolymer) + "[numerics]\npreset = \"paper\"\n");
  EXPECT_EQ(p.numerics.preset, NumericsPreset::kPaper);
  EXPECT_EQ(p.particle_mesh.kind, ParticleMeshKind::kRing);
  EXPECT_EQ(p.domain.diagonals, MeshDiagonals::kSwNe);
  EXPECT_EQ(p.splitting.advection, AdvectionScheme::kLeastSquares);
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kPaper);
  EXPECT_EQ(p.splitting.alpha, 0.5);
  EXPECT_EQ(p.splitting.beta, 0.5);
  EXPECT_EQ(p.splitting.steady_correction, SteadyCorrection::kNone);
  EXPECT_EQ(p.fluid.stress_splitting, StressSplitting::kExplicit);
  EXPECT_EQ(p.solvers.multiplier_preconditioner, MultiplierPreconditioning::kGram);
  EXPECT_TRUE(p.numerics.resolved.empty());
  // In a Newtonian liquid too: no steady correction.
  const Params newtonian = ParseScene("[numerics]\npreset = \"paper\"\n");
  EXPECT_EQ(newtonian.splitting.steady_correction, SteadyCorrection::kNone);
}

TEST(NumericsPreset, AKeyTheSceneSetsWinsOverThePreset) {
  const Params p =
      ParseScene(std::string(kDiskInPolymer) + "[numerics]\npreset = \"paper\"\n",
                 {{"splitting.advection", "\"wave\""}, {"particle_mesh.kind", "\"collocation\""}});
  EXPECT_EQ(p.splitting.advection, AdvectionScheme::kWave);
  EXPECT_EQ(p.particle_mesh.kind, ParticleMeshKind::kCollocation);
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kPaper);
  EXPECT_EQ(p.fluid.stress_splitting, StressSplitting::kExplicit);
}

// What a scene without numerics keys gets: numerics.preset = "default"'s words, which the struct
// of core/params.h holds too (since issue 39): collocation points, both diagonals, the wave-like
// advection, the coupling "auto" chose here and DEVSS (scene/numerics_preset.h).
TEST(NumericsPreset, TheDefaultPresetIsTheMeasuredConfiguration) {
  const Params p = ParseScene(kDiskInPolymer);
  const Params d;
  EXPECT_EQ(p.numerics.preset, NumericsPreset::kDefault);
  EXPECT_EQ(p.particle_mesh.kind, ParticleMeshKind::kCollocation);
  EXPECT_EQ(p.particle_mesh.kind, d.particle_mesh.kind);
  EXPECT_EQ(p.domain.diagonals, MeshDiagonals::kBoth);
  EXPECT_EQ(p.domain.diagonals, d.domain.diagonals);
  EXPECT_EQ(p.splitting.advection, AdvectionScheme::kWave);
  EXPECT_EQ(p.splitting.advection, d.splitting.advection);
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kIncremental);  // what "auto" chose here
  EXPECT_FALSE(d.splitting.constraint);                                 // "auto" in Params{} too
  EXPECT_EQ(p.splitting.alpha, d.splitting.alpha);
  EXPECT_EQ(p.splitting.beta, d.splitting.beta);
  EXPECT_EQ(p.fluid.stress_splitting, StressSplitting::kDevss);
  EXPECT_EQ(p.fluid.stress_splitting, d.fluid.stress_splitting);
  EXPECT_EQ(p.solvers.multiplier_preconditioner, d.solvers.multiplier_preconditioner);
  EXPECT_EQ(p.splitting.steady_correction, SteadyCorrection::kNone);  // with a polymer
  EXPECT_EQ(ParseScene("").splitting.steady_correction, SteadyCorrection::kTendency);  // without
}

TEST(NumericsPreset, TheSceneAsRunNamesThePresetAndReadsBackTheSame) {
  const Params p = ParseScene(std::string(kDiskInPolymer) + "[numerics]\npreset = \"paper\"\n",
                              {{"splitting.advection", "\"wave\""}});
  const std::string text = WriteScene(p);
  EXPECT_THAT(text, HasSubstr("[numerics]\npreset = \"paper\"\n"));
  EXPECT_EQ(WriteScene(ParseScene(text)), text);
  EXPECT_THAT(WriteScene(ParseScene(kDiskInPolymer)), ::testing::Not(HasSubstr("[numerics]")));
}

TEST(NumericsPreset, AnUnknownPresetNamesTheKeyAndTheAllowedValues) {
  try {
    ParseScene("[numerics]\npreset = \"basilisk\"\n");
    FAIL() << "accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_THAT(e.what(), HasSubstr("numerics.preset"));
    EXPECT_THAT(e.what(), HasSubstr("\"default\", \"paper\""));
  }
  try {
    ParseScene("[numerics]\nadvection = \"wave\"\n");
    FAIL() << "accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_THAT(e.what(), HasSubstr("numerics.advection"));
  }
}

}  // namespace
}  // namespace dlmfd
