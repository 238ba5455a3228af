// splitting.constraint = "auto" (scene/auto_coupling.h): one test per rule, on each side of its
// bound, and the record of the choice (the numbers, the scene as run, a rerun of it).
#include "dlmfd/scene/auto_coupling.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

using ::testing::HasSubstr;

// The paper's case 5.1 written as a user would, without numerics keys: one disk of rho_p = 1.5
// falling in a Newtonian liquid (eta = 0.01), h = 1/96, dt = 1e-3. Its fall-speed estimate is
// U_p = sqrt(pi/2 (rho_p / rho - 1) g D) = 12.41 (accuracy_envelope.h).
const char* const kPaperDisk = R"TOML(
gravity = [0.0, -981.0]
[domain]
size = [1.5, 6.0]
h = 0.010416666666666666
[fluid]
viscosity = 0.01
[time]
dt = 0.001
end = 0.5
[[particles]]
center = [1.125, 5.2]
diameter = 0.2
density = 1.5
)TOML";

double Number(const ResolvedChoice& c, const std::string& name) {
  for (const auto& [n, value] : c.numbers) {
    if (n == name) return value;
  }
  ADD_FAILURE() << "no number " << name;
  return 0.0;
}

// The coupling's choice, which the scene resolves first (then particle_mesh.kind's,
// scene/auto_particle_mesh.h).
const ResolvedChoice& OnlyChoice(const Params& p) {
  EXPECT_GE(p.numerics.resolved.size(), 1u);
  EXPECT_EQ(p.numerics.resolved.front().key, "splitting.constraint");
  return p.numerics.resolved.front();
}

// Rule 1: nothing to couple.
TEST(AutoCoupling, WithoutParticlesItIsIncremental) {
  const Params p = ParseScene("[time]\ndt = 0.01\n");
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kIncremental);
  EXPECT_EQ(p.splitting.alpha, 1.0);
  EXPECT_EQ(p.splitting.beta, 0.0);
  EXPECT_EQ(OnlyChoice(p).key, "splitting.constraint");
  EXPECT_EQ(OnlyChoice(p).value, "incremental");
  EXPECT_EQ(OnlyChoice(p).rule, "no particles");
}

// Rule 2: the paper's disk at dt = 1e-3 crosses 1.19 cells a step: the paper's coupling, with
// its weights alpha = beta = 1/2.
TEST(AutoCoupling, ParticlesCrossingMoreThanAThirdOfACellAStepGetThePapersCoupling) {
  const Params p = ParseScene(kPaperDisk);
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kPaper);
  EXPECT_EQ(p.splitting.alpha, 0.5);
  EXPECT_EQ(p.splitting.beta, 0.5);
  const ResolvedChoice& c = OnlyChoice(p);
  EXPECT_EQ(c.value, "paper");
  EXPECT_THAT(c.rule, HasSubstr("U_p dt / h > 0.3"));
  EXPECT_NEAR(Number(c, "U_p dt / h"), 12.4126 * 0.001 * 96, 1e-3);
  EXPECT_NEAR(Number(c, "nu dt / h^2"), 0.01 * 0.001 * 96 * 96, 1e-12);
  EXPECT_NEAR(Number(c, "rho_p / rho (max)"), 1.5, 1e-15);
}

// Rule 4, at rule 2's bound's other side: the same disk at dt = 2.4e-4 (U_p dt / h = 0.286, where
// the lagged multiplier was measured to complete at 0.298).
TEST(AutoCoupling, SlowerParticlesGetTheIncrementalCoupling) {
  const Params p = ParseScene(kPaperDisk, {{"time.dt", "0.00024"}});
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kIncremental);
  EXPECT_EQ(p.splitting.alpha, 1.0);
  EXPECT_EQ(p.splitting.beta, 0.0);
  EXPECT_EQ(OnlyChoice(p).value, "incremental");
  EXPECT_LT(Number(OnlyChoice(p), "U_p dt / h"), kMaxLaggedParticleCourant);
}

// Rule 2 needs the paper's leak small: Faxen's disk (cases/verification/faxen_disk_w1.toml) on
// h = 1/48 at dt = 0.024 has U_p dt / h = 2.0 (its estimate U_p = 1.76 is ten times its speed) and
// nu dt / h^2 = 5.5: the incremental coupling, which holds its speed there.
TEST(AutoCoupling, ParticlesInAViscousLiquidKeepTheIncrementalCoupling) {
  const Params p =
      LoadSceneFile(std::string(DLMFD_SOURCE_DIR) + "/cases/verification/faxen_disk_w1.toml",
                    {{"domain.h", "0.020833333333333332"}, {"time.dt", "0.024"}});
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kIncremental);
  const ResolvedChoice& c = OnlyChoice(p);
  EXPECT_GT(Number(c, "U_p dt / h"), kMaxLaggedParticleCourant);
  EXPECT_NEAR(Number(c, "nu dt / h^2"), 0.1 * 0.024 * 48 * 48, 1e-9);
  EXPECT_THAT(c.rule, HasSubstr("nu dt / h^2 > 0.195"));
  // The paper's disk on each side of nu dt / h^2 = 0.195 (eta = 0.0211 / 0.0212: 0.1945 / 0.1954).
  EXPECT_EQ(ParseScene(kPaperDisk, {{"fluid.viscosity", "0.0211"}}).splitting.constraint,
            ConstraintCoupling::kPaper);
  EXPECT_EQ(ParseScene(kPaperDisk, {{"fluid.viscosity", "0.0212"}}).splitting.constraint,
            ConstraintCoupling::kIncremental);
}

// Rule 3: creeping flow. Faxen's disk (cases/verification/faxen_disk_w1.toml, h = 1/96, dt =
// 0.01) at rho_f = 0.1: nu dt / h^2 = 92, where the lagged multiplier was still +1.4 % at t = 1.5
// and the viscous coupling -0.71 % from the start: "viscous". At rho_f = 0.5 (18.4, within 1 %
// as fast as the liquid starts): "incremental".
TEST(AutoCoupling, CreepingFlowGetsTheViscousCoupling) {
  const std::string faxen =
      std::string(DLMFD_SOURCE_DIR) + "/cases/verification/faxen_disk_w1.toml";
  const Params p = LoadSceneFile(
      faxen, {{"time.dt", "0.01"}, {"fluid.density", "0.1"}, {"particles.0.density", "0.11"}});
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kViscous);
  EXPECT_EQ(p.splitting.alpha, 1.0);
  EXPECT_EQ(p.splitting.beta, 0.0);
  const ResolvedChoice& c = OnlyChoice(p);
  EXPECT_EQ(c.value, "viscous");
  EXPECT_THAT(c.rule, HasSubstr("nu dt / h^2 > 18.5"));
  EXPECT_NEAR(Number(c, "nu dt / h^2"), 1.0 * 0.01 * 96 * 96, 1e-9);
  const Params q = LoadSceneFile(
      faxen, {{"time.dt", "0.01"}, {"fluid.density", "0.5"}, {"particles.0.density", "0.51"}});
  EXPECT_EQ(q.splitting.constraint, ConstraintCoupling::kIncremental);
}

// The confined cylinder in the Stokes limit (cases/verification/confined_cylinder_oldroyd_b.toml
// as shipped: rho = 0.01, eta = 1, R/h = 24, dt = lambda / 120): nu dt / h^2 = 288, a fixed disk:
// "viscous" (the fixed disk in the same channel was 16 % low at t = 1 with the lagged multiplier).
TEST(AutoCoupling, TheConfinedCylinderInTheStokesLimitGetsTheViscousCoupling) {
  const Params p = LoadSceneFile(std::string(DLMFD_SOURCE_DIR) +
                                 "/cases/verification/confined_cylinder_oldroyd_b.toml");
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kViscous);
  EXPECT_NEAR(Number(OnlyChoice(p), "nu dt / h^2"), 100.0 * 0.005 * 24 * 24, 1e-6);
}

// A neutrally buoyant free particle cannot take the viscous coupling (ValidateScene): at the same
// numbers it keeps the lagged multiplier.
TEST(AutoCoupling, ANeutralFreeParticleKeepsTheIncrementalCouplingInCreepingFlow) {
  const Params p = LoadSceneFile(
      std::string(DLMFD_SOURCE_DIR) + "/cases/verification/faxen_disk_w1.toml",
      {{"time.dt", "0.01"}, {"fluid.density", "0.1"}, {"particles.0.density", "0.1"}});
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kIncremental);
}

// A particle that turns is no exception (there was a rule for it until 2026-12-07, the paper's
// coupling for free heavy ellipses, whose lagged multiplier blew up with interior points turned
// against the grid). The settling ellipse (cases/shapes/settling_ellipse.toml: a / b = 2,
// rho_p / rho = 1.1, U_p dt / h = 0.167, nu dt / h^2 = 0.10) gets the lagged multiplier, which
// with interior points that cannot pair up in a cell completes it and is nearer its dt limit
// (docs/evidence/validation_particles.md, "The lagged multiplier on a turning shape"): as does a
// nearly round one, one prescribed to rotate, and the disk of the same area, on the same numbers.
TEST(AutoCoupling, AParticleThatTurnsGetsTheIncrementalCoupling) {
  const std::string ellipse = std::string(DLMFD_SOURCE_DIR) + "/cases/shapes/settling_ellipse.toml";
  const Params p = LoadSceneFile(ellipse);
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kIncremental);
  const ResolvedChoice& c = OnlyChoice(p);
  EXPECT_EQ(c.rule, "particles slower than 0.3 of a cell a step");
  EXPECT_LT(Number(c, "U_p dt / h"), kMaxLaggedParticleCourant);
  const auto coupling = [&](std::vector<SceneOverride> overrides) {
    return LoadSceneFile(ellipse, overrides).splitting.constraint;
  };
  EXPECT_EQ(coupling({{"particles.0.semi_axes", "[0.0884, 0.08838]"}}),
            ConstraintCoupling::kIncremental);
  EXPECT_EQ(
      coupling({{"particles.0.motion", "\"prescribed\""}, {"particles.0.angular_velocity", "1.0"}}),
      ConstraintCoupling::kIncremental);
  // The disk of the same area: the same numbers, the lagged multiplier.
  std::string disk = R"TOML(
gravity = [0.0, -981.0]
[domain]
size = [1.0, 6.0]
h = 0.015625
[fluid]
viscosity = 0.05
[time]
dt = 0.0005
end = 2.0
[[particles]]
center = [0.5, 5.2]
diameter = 0.17677669529663687
density = 1.1
)TOML";
  const Params d = ParseScene(disk);
  EXPECT_EQ(d.splitting.constraint, ConstraintCoupling::kIncremental);
  EXPECT_NEAR(Number(OnlyChoice(d), "U_p dt / h"), Number(c, "U_p dt / h"), 1e-9);
}

// A scene that names its coupling gets it, and nothing is resolved.
TEST(AutoCoupling, ANamedCouplingIsKept) {
  for (const char* word : {"incremental", "paper", "viscous"}) {
    const Params p =
        ParseScene(kPaperDisk, {{"splitting.constraint", std::string("\"") + word + "\""}});
    EXPECT_STREQ(ConstraintCouplingName(p.splitting.constraint.value()), word);
    for (const ResolvedChoice& c : p.numerics.resolved) {
      EXPECT_NE(c.key, "splitting.constraint") << word;
    }
  }
  const Params p = ParseScene(kPaperDisk, {{"splitting.constraint", "\"auto\""}});
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kPaper);
}

// Params built in code leaves the constraint to "auto" as a scene does: the paper's disk written
// in code runs as the scene that names no coupling, weights included (scene::ResolveDefaults).
TEST(AutoCoupling, ParamsBuiltInCodeResolveAsTheScene) {
  const Params scene = ParseScene(kPaperDisk);
  Params built = scene;
  built.splitting = SplittingParams{};
  built.splitting.steady_correction = scene.splitting.steady_correction;
  built.numerics.resolved.clear();
  EXPECT_FALSE(built.splitting.constraint);
  ResolveDefaults(built);
  EXPECT_EQ(built.splitting.constraint, ConstraintCoupling::kPaper);
  EXPECT_EQ(WriteScene(built), WriteScene(scene));
  ASSERT_EQ(built.numerics.resolved.size(), 1u);
  EXPECT_EQ(built.numerics.resolved.front().value, "paper");
  // Weights set in code stay: only the struct's own follow the choice.
  Params weighted = built;
  weighted.splitting.constraint.reset();
  weighted.splitting.alpha = 0.75;
  weighted.splitting.beta = 0.25;
  ResolveDefaults(weighted);
  EXPECT_EQ(weighted.splitting.alpha, 0.75);
}

// The scene as run names the coupling chosen, so reading it back (a rerun, a resume's check)
// gives the same scene without resolving again, even where the rule would now choose otherwise.
TEST(AutoCoupling, TheSceneAsRunNamesTheChoice) {
  const Params p = ParseScene(kPaperDisk);
  const std::string text = WriteScene(p);
  EXPECT_THAT(text, HasSubstr("constraint = \"paper\"\n"));
  const Params again = ParseScene(text, {{"time.dt", "0.00024"}});
  EXPECT_TRUE(again.numerics.resolved.empty());
  EXPECT_EQ(again.splitting.constraint, ConstraintCoupling::kPaper);
  EXPECT_EQ(again.splitting.alpha, 0.5);
}

TEST(AutoCoupling, TheTextNamesTheRuleAndItsNumbers) {
  const std::string text = ResolvedChoiceText(OnlyChoice(ParseScene(kPaperDisk)));
  EXPECT_THAT(text, HasSubstr("splitting.constraint = \"paper\" (auto: particles cross"));
  EXPECT_THAT(text, HasSubstr("U_p dt / h = 1.19"));
}

}  // namespace
}  // namespace dlmfd
