// splitting.constraint = "auto" (scene/auto_coupling.h): one test per rule, on each side of its
// bound, and the record of the choice (the numbers, the scene as run, a rerun of it).
#include "dlmfd/scene/auto_coupling.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

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

const ResolvedChoice& OnlyChoice(const Params& p) {
  EXPECT_EQ(p.numerics.resolved.size(), 1u);
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

// Rule 3, at the bound's other side: the same disk at dt = 2.4e-4 (U_p dt / h = 0.286, where the
// lagged multiplier was measured to complete at 0.298).
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

// A scene that names its coupling gets it, and nothing is resolved.
TEST(AutoCoupling, ANamedCouplingIsKept) {
  for (const char* word : {"incremental", "paper", "viscous"}) {
    const Params p =
        ParseScene(kPaperDisk, {{"splitting.constraint", std::string("\"") + word + "\""}});
    EXPECT_STREQ(ConstraintCouplingName(p.splitting.constraint), word);
    EXPECT_TRUE(p.numerics.resolved.empty()) << word;
  }
  const Params p = ParseScene(kPaperDisk, {{"splitting.constraint", "\"auto\""}});
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kPaper);
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
