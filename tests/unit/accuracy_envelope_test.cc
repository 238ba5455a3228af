// The accuracy envelope (scene/accuracy_envelope.h): scenes inside every bound give no warning,
// scenes outside one give exactly that warning with the key to change and a value that brings the
// scene inside; accuracy.strict turns a warning into an InvalidParameter naming the key.
#include "dlmfd/scene/accuracy_envelope.h"
#include "dlmfd/core/constants.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "dlmfd/core/errors.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

using ::testing::HasSubstr;

// cases/verification/waters_king.toml: h = 1/32, dt = 0.005, lambda = 1, eta_p = 8/9, rho = 1.
const char* const kWatersKing = R"TOML(
[domain]
size = [0.125, 2.0]
h = 0.03125
[domain.boundary]
left = { type = "periodic" }
right = { type = "periodic" }
[fluid]
density = 1.0
viscosity = 1.0
relaxation_time = 1.0
solvent_ratio = 0.1111111111111111
body_force = [3.0, 0.0]
[time]
dt = 0.005
end = 6.0
[splitting]
alpha = 1.0
beta = 0.0
)TOML";

// cases/lid_driven_cavity.toml: 64 cells, dt = 0.01, lid speed 1 (U dt / h = 0.64 exactly).
const char* const kCavity = R"TOML(
[domain]
size = [1.0, 1.0]
h = 0.015625
[domain.boundary]
top = { type = "velocity", profile = "uniform", value = [1.0, 0.0] }
[fluid]
viscosity = 0.01
[time]
dt = 0.01
end = 1.0
)TOML";

// cases/verification/schaefer_turek_2d1.toml: D / h = 20, nu dt / h^2 = 0.2.
const char* const kSchaeferTurek = R"TOML(
[domain]
size = [2.2, 0.41]
h = 0.005
[domain.boundary]
left = { type = "velocity", profile = "poiseuille", max = [0.3, 0.0] }
right = { type = "outflow" }
[fluid]
viscosity = 0.001
[time]
dt = 0.005
end = 5.0
[[particles]]
center = [0.2, 0.2]
diameter = 0.1
motion = "fixed"
[particle_mesh]
kind = "ring"  # the mesh whose bounds these tests check; collocation points where they say so
h = 0.006857142857142857
)TOML";

Params Scene(const char* text, const std::vector<std::string>& sets = {}) {
  std::vector<SceneOverride> overrides;
  for (const std::string& s : sets) overrides.push_back(ParseOverride(s));
  return ParseScene(text, overrides, "test.toml");
}

std::vector<std::string> Settings(const std::vector<AccuracyWarning>& warnings) {
  std::vector<std::string> out;
  for (const AccuracyWarning& w : warnings) out.push_back(w.setting);
  return out;
}

// Applying a warning's suggestion removes that warning (and the scene stays valid).
void ExpectSuggestionSatisfies(const char* text, std::vector<std::string> sets,
                               const AccuracyWarning& w) {
  sets.push_back(w.key + "=" + w.suggested);
  const Params fixed = Scene(text, sets);
  for (const AccuracyWarning& other : AccuracyWarnings(fixed)) {
    EXPECT_NE(other.setting.substr(0, 5), w.setting.substr(0, 5))
        << "after " << w.key << " = " << w.suggested << ": " << other.Message();
  }
}

TEST(AccuracyEnvelope, MeasuredScenesInsideEveryBoundGiveNoWarning) {
  // The Waters-King run of docs/evidence/work_precision.md (a) (error 3.3e-3): nu dt / h^2 = 5.12,
  // c dt / h = 0.151, dt / lambda = 0.005, U dt / h = 1.5 * 0.005 * 32 = 0.24.
  EXPECT_TRUE(AccuracyWarnings(Scene(kWatersKing)).empty());
  // The cavity at its Courant number 0.64, the largest of the study: on the bound, not outside.
  EXPECT_TRUE(AccuracyWarnings(Scene(kCavity)).empty());
  EXPECT_TRUE(AccuracyWarnings(Scene(kCavity, {"domain.h=0.0078125", "time.dt=0.005"})).empty());
}

TEST(AccuracyEnvelope, SettingsAreTheDimensionlessNumbersOfTheScene) {
  const std::vector<AccuracySetting> s = AccuracySettings(Scene(kWatersKing));
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s[0].name, "nu dt / h^2");
  EXPECT_DOUBLE_EQ(s[0].value, 0.005 * 32 * 32);
  EXPECT_EQ(s[1].name, "U dt / h");
  EXPECT_DOUBLE_EQ(s[2].value, 3.0 * 2.0 * 2.0 / 8.0);  // plane Poiseuille peak f H^2 / (8 eta)
  EXPECT_DOUBLE_EQ(s[1].value, s[2].value * 0.005 * 32);
  EXPECT_EQ(s[3].name, "c dt / h");
  EXPECT_DOUBLE_EQ(s[3].value, std::sqrt(1.0 - 0.1111111111111111) * 0.005 * 32);
  EXPECT_EQ(s[4].name, "dt / lambda");
  EXPECT_DOUBLE_EQ(s[4].value, 0.005);

  const std::vector<AccuracySetting> st = AccuracySettings(Scene(kSchaeferTurek));
  ASSERT_EQ(st.size(), 5u);
  EXPECT_EQ(st[3].name, "D / h (particles.0)");
  EXPECT_NEAR(st[3].value, 20.0, 1e-12);
  EXPECT_EQ(st[4].name, "D / h_p (particles.0)");
  EXPECT_NEAR(st[4].value, 0.1 / 0.006857142857142857, 1e-12);
  EXPECT_DOUBLE_EQ(st[2].value, 0.3);  // the inflow's peak

  // Collocation points: h_p is their boundary spacing c h (c = 2 by default), not particle_mesh.h.
  const std::vector<AccuracySetting> sc =
      AccuracySettings(Scene(kSchaeferTurek, {"particle_mesh.kind=\"collocation\""}));
  ASSERT_EQ(sc.size(), 5u);
  EXPECT_NEAR(sc[4].value, 0.1 / (2.0 * 0.005), 1e-12);
}

TEST(AccuracyEnvelope, FallSpeedEstimateIsTheSmallerOfTheInertialAndViscousScales) {
  const char* const kDisk = R"TOML(
gravity = [0.0, -981.0]
[domain]
size = [1.0, 2.0]
h = 0.03125
[fluid]
viscosity = 0.1
[time]
dt = 0.001
end = 1.0
[[particles]]
center = [0.5, 1.5]
diameter = 0.2
density = 1.02
)TOML";
  const Params p = Scene(kDisk);
  const double inertial = std::sqrt(0.5 * kPi * 0.02 * 981.0 * 0.2);
  const double viscous = 0.02 * 981.0 * 0.04 / 0.1;
  EXPECT_DOUBLE_EQ(VelocityScale(p), std::min(inertial, viscous));
  EXPECT_DOUBLE_EQ(VelocityScale(Scene(kDisk, {"fluid.viscosity=100"})), 0.02 * 981.0 * 0.04 / 100);
  // A fixed particle does not fall; a neutrally buoyant free one neither.
  EXPECT_DOUBLE_EQ(VelocityScale(Scene(kDisk, {"particles.0.motion=\"fixed\""})), 0.0);
}

TEST(AccuracyEnvelope, ViscousNumberWithParticlesAboveTheBoundWarnsOnTheTimeStep) {
  // D / h = 120, nu dt / h^2 = 0.144, U dt / h = 0.036.
  const Params inside =
      Scene(kSchaeferTurek, {"domain.h=0.000833333333333333333", "time.dt=0.0001", "time.end=0.1"});
  EXPECT_TRUE(AccuracyWarnings(inside).empty()) << AccuracyWarnings(inside).front().Message();

  // The paper's coupling: its bound.
  const std::vector<std::string> paper = {"fluid.viscosity=0.1", "splitting.constraint=\"paper\""};
  const std::vector<AccuracyWarning> w = AccuracyWarnings(Scene(kSchaeferTurek, paper));
  ASSERT_FALSE(w.empty());
  EXPECT_EQ(w[0].setting, "nu dt / h^2");
  EXPECT_DOUBLE_EQ(w[0].value, 0.1 * 0.005 / (0.005 * 0.005));
  EXPECT_EQ(w[0].allowed, "<= 0.195");
  EXPECT_EQ(w[0].key, "time.dt");
  EXPECT_EQ(w[0].current, "0.005");
  EXPECT_LE(0.1 * std::stod(w[0].suggested) / (0.005 * 0.005), kMaxViscousNumberWithParticles);
  ExpectSuggestionSatisfies(kSchaeferTurek, paper, w[0]);
  EXPECT_THAT(w[0].Message(), HasSubstr("set time.dt = " + w[0].suggested));

  // The lagged multiplier (what auto picks below nu dt / h^2 = 18.5): its own bound, measured to
  // 2.05. Here, at 20, auto picks the viscous coupling (the next test), so the scene names it.
  const std::vector<std::string> lagged = {"fluid.viscosity=0.1",
                                           "splitting.constraint=\"incremental\""};
  const std::vector<AccuracyWarning> d = AccuracyWarnings(Scene(kSchaeferTurek, lagged));
  ASSERT_FALSE(d.empty());
  EXPECT_EQ(d[0].setting, "nu dt / h^2");
  EXPECT_EQ(d[0].allowed, "<= 2.05");
  EXPECT_LE(0.1 * std::stod(d[0].suggested) / (0.005 * 0.005),
            kMaxViscousNumberIncrementalCoupling);
  ExpectSuggestionSatisfies(kSchaeferTurek, lagged, d[0]);
}

TEST(AccuracyEnvelope, ViscousCouplingHasTheBoundItWasMeasuredTo) {
  // Schaefer-Turek at nu = 0.1: nu dt / h^2 = 20 at dt = 5e-3 warns with the lagged multiplier,
  // not with the constraint in the Stokes step (measured to 922: Faxen's disk in creeping flow),
  // which is what the default, auto, picks there; 1000 at dt = 0.25 warns with both.
  const std::vector<std::string> viscous = {"fluid.viscosity=0.1",
                                            "splitting.constraint=\"viscous\"", "splitting.alpha=1",
                                            "splitting.beta=0"};
  EXPECT_THAT(
      Settings(AccuracyWarnings(
          Scene(kSchaeferTurek, {"fluid.viscosity=0.1", "splitting.constraint=\"incremental\""}))),
      ::testing::Contains(std::string("nu dt / h^2")));
  const Params inside = Scene(kSchaeferTurek, viscous);
  for (const AccuracyWarning& w : AccuracyWarnings(inside)) EXPECT_NE(w.setting, "nu dt / h^2");
  const Params by_default = Scene(kSchaeferTurek, {"fluid.viscosity=0.1"});
  EXPECT_EQ(by_default.splitting.constraint, ConstraintCoupling::kViscous);
  for (const AccuracyWarning& w : AccuracyWarnings(by_default)) EXPECT_NE(w.setting, "nu dt / h^2");
  std::vector<std::string> coarse = viscous;
  coarse.push_back("time.dt=0.25");
  const std::vector<AccuracyWarning> w = AccuracyWarnings(Scene(kSchaeferTurek, coarse));
  const auto it = std::find_if(w.begin(), w.end(),
                               [](const AccuracyWarning& a) { return a.setting == "nu dt / h^2"; });
  ASSERT_NE(it, w.end());
  EXPECT_EQ(it->allowed, "<= 922");
  EXPECT_THAT(it->source, HasSubstr("Coupling the constraint with viscosity"));
}

TEST(AccuracyEnvelope, ViscousNumberWithoutParticlesHasTheLargerMeasuredBound) {
  // 20.48 > 10.24 (Waters-King at h = 1/64, dt = 0.005 was not measured; 0.0025 was).
  const std::vector<AccuracyWarning> w =
      AccuracyWarnings(Scene(kWatersKing, {"domain.h=0.015625", "domain.size=[0.0625, 2.0]"}));
  EXPECT_EQ(Settings(w), std::vector<std::string>{"nu dt / h^2"});
  EXPECT_EQ(w[0].allowed, "<= 10.24");
  EXPECT_EQ(w[0].suggested, "0.0025");
}

// Cut cells have no multiplier, so the coupling's bounds on nu dt / h^2 (its leak, the lagged
// multiplier's settling) do not apply to them; theirs is the creeping fixed disk's 480.
TEST(AccuracyEnvelope, CutCellsHaveTheViscousBoundTheirRunsMeasured) {
  const std::string cut = "particle_mesh.kind=\"cut_cell\"";
  // nu dt / h^2 = 20: above the lagged multiplier's 2.05 and the liquid's 10.24.
  const std::vector<std::string> lagged = {"fluid.viscosity=0.1",
                                           "splitting.constraint=\"incremental\""};
  EXPECT_THAT(Settings(AccuracyWarnings(Scene(kSchaeferTurek, lagged))),
              ::testing::Contains(std::string("nu dt / h^2")));
  std::vector<std::string> lagged_cut = lagged;
  lagged_cut.push_back(cut);
  EXPECT_THAT(Settings(AccuracyWarnings(Scene(kSchaeferTurek, lagged_cut))),
              ::testing::Not(::testing::Contains(std::string("nu dt / h^2"))));
  // nu dt / h^2 = 1000: above theirs, with its source.
  const std::vector<AccuracyWarning> w = AccuracyWarnings(
      Scene(kSchaeferTurek, {"fluid.viscosity=0.1", "time.dt=0.25", "time.end=5", cut}));
  ASSERT_FALSE(w.empty());
  EXPECT_EQ(w[0].setting, "nu dt / h^2");
  EXPECT_EQ(w[0].allowed, "<= 480");
  EXPECT_THAT(w[0].source, HasSubstr("cut_cell_boundary.md"));
}

TEST(AccuracyEnvelope, AdvectiveCourantAboveTheBoundWarns) {
  const std::vector<AccuracyWarning> w = AccuracyWarnings(Scene(kCavity, {"time.dt=0.02"}));
  EXPECT_EQ(Settings(w), std::vector<std::string>{"U dt / h"});
  EXPECT_DOUBLE_EQ(w[0].value, 1.28);
  EXPECT_EQ(w[0].suggested, "0.01");
  ExpectSuggestionSatisfies(kCavity, {"time.dt=0.02"}, w[0]);
}

TEST(AccuracyEnvelope, ElasticCourantAndStepPerRelaxationTimeAboveTheBoundsWarn) {
  // dt = 0.0125: c dt / h = 0.377, dt / lambda = 0.0125, U dt / h = 0.6, nu dt / h^2 = 12.8.
  const std::vector<std::string> sets = {"time.dt=0.0125"};
  const std::vector<AccuracyWarning> w = AccuracyWarnings(Scene(kWatersKing, sets));
  EXPECT_EQ(Settings(w), (std::vector<std::string>{"nu dt / h^2", "c dt / h", "dt / lambda"}));
  ASSERT_EQ(w.size(), 3u);
  EXPECT_NEAR(w[1].value, std::sqrt(8.0 / 9.0) * 0.0125 * 32, 1e-12);
  EXPECT_EQ(w[1].allowed, "<= 0.3017");
  EXPECT_DOUBLE_EQ(w[2].value, 0.0125);
  EXPECT_EQ(w[2].allowed, "<= 0.01");
  for (const AccuracyWarning& x : w) ExpectSuggestionSatisfies(kWatersKing, sets, x);
  // A Newtonian liquid has no elastic setting (lambda = 0, or beta = 1).
  const Params newtonian = Scene(kWatersKing, {"time.dt=0.0125", "fluid.solvent_ratio=1"});
  EXPECT_EQ(AccuracySettings(newtonian).size(), 3u);
  EXPECT_EQ(Settings(AccuracyWarnings(newtonian)), std::vector<std::string>{"nu dt / h^2"});
}

// A polymer viscous on the grid's scale under devss (El_h = lambda eta_p / (rho h^2) <= 0.105,
// lambda U / h <= 0.016) has no elastic bound: Waters-King's scene (h = 1/32, eta_p = 8/9, U = 1.5)
// at lambda = 1e-4 has El_h = 0.091 and lambda U / h = 0.0048, and c dt / h = 15.1, dt / lambda =
// 50. Under the paper's explicit stress, and at lambda = 1e-3 (El_h = 0.91), both warn.
TEST(AccuracyEnvelope, PolymerViscousOnTheGridHasNoElasticBoundUnderDevss) {
  const std::vector<std::string> viscous = {"fluid.relaxation_time=1e-4"};
  EXPECT_EQ(Settings(AccuracyWarnings(Scene(kWatersKing, viscous))), std::vector<std::string>{});
  std::vector<std::string> explicit_stress = viscous;
  explicit_stress.push_back("fluid.stress_splitting=\"explicit\"");
  EXPECT_EQ(Settings(AccuracyWarnings(Scene(kWatersKing, explicit_stress))),
            (std::vector<std::string>{"c dt / h", "dt / lambda"}));
  EXPECT_EQ(Settings(AccuracyWarnings(Scene(kWatersKing, {"fluid.relaxation_time=1e-3"}))),
            (std::vector<std::string>{"c dt / h", "dt / lambda"}));
}

// The collocation points have their own D / h bound (accuracy_envelope.h): 19.2 under the default
// coupling, 39 under the paper's; the ring mesh keeps 120; cut cells 9.75.
TEST(AccuracyEnvelope, CollocationPointsHaveTheirOwnDiskResolutionBound) {
  auto bound = [](const std::vector<std::string>& sets) {
    for (const AccuracyWarning& w : AccuracyWarnings(Scene(kSchaeferTurek, sets)))
      if (w.setting.rfind("D / h", 0) == 0) return w.allowed;
    return std::string("none");
  };
  EXPECT_EQ(bound({}), ">= 120");  // D / h = 20, ring mesh
  EXPECT_EQ(bound({"particle_mesh.kind=\"collocation\""}), "none");
  EXPECT_EQ(
      bound({"particle_mesh.kind=\"collocation\"", "domain.size=[2.255,0.41]", "domain.h=0.01025"}),
      ">= 19.2");  // D / h = 9.76
  EXPECT_EQ(bound({"particle_mesh.kind=\"collocation\"", "splitting.constraint=\"paper\""}),
            ">= 39");
  // Cut cells: 9.75 (D / h = 9.76 is inside, 7.8 outside).
  const std::string cut = "particle_mesh.kind=\"cut_cell\"";
  EXPECT_EQ(bound({cut, "domain.size=[2.255,0.41]", "domain.h=0.01025"}), "none");
  EXPECT_EQ(bound({cut, "domain.size=[2.46,0.41]", "domain.h=0.0128125"}), ">= 9.75");
}

TEST(AccuracyEnvelope, DiskResolutionBelowTheBoundWarnsOnceOnTheSmallestParticle) {
  const char* const kTwo = R"TOML(
[domain]
size = [1.0, 1.0]
h = 0.015625
[fluid]
viscosity = 0.0001
[time]
dt = 0.001
end = 1.0
[[particles]]
center = [0.3, 0.5]
diameter = 0.25
motion = "fixed"
[[particles]]
center = [0.7, 0.5]
diameter = 0.125
motion = "fixed"
[particle_mesh]
kind = "ring"
h = 0.02142857142857143  # 96 / 70 h, the studies' ratio (and the default of a scene file)
)TOML";
  const std::vector<AccuracyWarning> w = AccuracyWarnings(Scene(kTwo));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].setting, "D / h (particles.1, the smallest of 2 below the bound)");
  EXPECT_DOUBLE_EQ(w[0].value, 8.0);
  EXPECT_EQ(w[0].allowed, ">= 120");
  EXPECT_EQ(w[0].key, "domain.h");
  EXPECT_DOUBLE_EQ(std::stod(w[0].suggested), 0.015625 / 15);  // D / h = 120, cells stay even
  ExpectSuggestionSatisfies(kTwo, {}, w[0]);
}

TEST(AccuracyEnvelope, StrictSceneOutsideTheEnvelopeIsRejectedNamingTheKey) {
  EXPECT_NO_THROW(Scene(kCavity, {"accuracy.strict=true"}));
  try {
    Scene(kCavity, {"accuracy.strict=true", "time.dt=0.02"});
    FAIL() << "a strict scene outside the envelope was accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "time.dt");
    EXPECT_EQ(e.value(), "0.02");
    EXPECT_THAT(e.allowed(), HasSubstr("e.g. 0.01"));
    EXPECT_THAT(e.allowed(), HasSubstr("U dt / h = 1.28"));
    EXPECT_THAT(e.allowed(), HasSubstr("accuracy.strict"));
  }
  // Not strict: the same scene is valid (the run warns and goes on).
  EXPECT_NO_THROW(Scene(kCavity, {"time.dt=0.02"}));
}

TEST(AccuracyEnvelope, StrictKeyIsABoolean) {
  try {
    Scene(kCavity, {"accuracy.strict=1"});
    FAIL() << "accuracy.strict = 1 was accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "accuracy.strict");
    EXPECT_EQ(e.allowed(), "true or false");
  }
  EXPECT_THROW(Scene(kCavity, {"accuracy.loose=true"}), InvalidParameter);
  EXPECT_TRUE(Scene(kCavity, {"accuracy.strict=true"}).accuracy.strict);
  EXPECT_FALSE(Scene(kCavity).accuracy.strict);
  // The scene as run keeps the key when it is set, and is the text of before the key otherwise.
  const Params strict = Scene(kCavity, {"accuracy.strict=true"});
  EXPECT_TRUE(ParseScene(WriteScene(strict), {}, "written.toml").accuracy.strict);
  EXPECT_EQ(WriteScene(Scene(kCavity)).find("accuracy"), std::string::npos);
}

TEST(AccuracyEnvelope, ParticleMeshFinerThanTheBoundWarnsWithTheStudiedRatio) {
  // The Schaefer-Turek scene's ring mesh is at the studies' 96 / 70 of h: no warning on it.
  for (const AccuracyWarning& w : AccuracyWarnings(Scene(kSchaeferTurek))) {
    EXPECT_NE(w.setting, "h_p / h") << w.Message();
  }
  // h_p = h, where the multiplier CG did not converge (bench/multiplier_conditioning.sh).
  const std::vector<std::string> equal = {"particle_mesh.h=0.005"};
  const std::vector<AccuracyWarning> w = AccuracyWarnings(Scene(kSchaeferTurek, equal));
  ASSERT_FALSE(w.empty());
  const AccuracyWarning& last = w.back();
  EXPECT_EQ(last.setting, "h_p / h");
  EXPECT_DOUBLE_EQ(last.value, 1.0);
  EXPECT_EQ(last.allowed, ">= 1.1");
  EXPECT_EQ(last.key, "particle_mesh.h");
  EXPECT_EQ(last.current, "0.005");
  EXPECT_DOUBLE_EQ(std::stod(last.suggested), 96.0 / 70.0 * 0.005);
  EXPECT_THAT(last.source, HasSubstr("The particle mesh against the fluid mesh"));
  ExpectSuggestionSatisfies(kSchaeferTurek, equal, last);
  // On the bound is inside it; collocation points have no ring mesh to warn on.
  for (const AccuracyWarning& x :
       AccuracyWarnings(Scene(kSchaeferTurek, {"particle_mesh.h=0.0055"}))) {
    EXPECT_NE(x.setting, "h_p / h") << x.Message();
  }
  for (const AccuracyWarning& x : AccuracyWarnings(Scene(
           kSchaeferTurek, {"particle_mesh.h=0.005", "particle_mesh.kind=\"collocation\""}))) {
    EXPECT_NE(x.setting, "h_p / h") << x.Message();
  }
}

// The incremental coupling with particles that cross more than 0.3 of a cell a step (the paper's
// case 5.1 at dt = 1e-3: U_p dt / h = 12.41 * 0.001 * 96 = 1.19, where the lagged multiplier
// diverged) warns, suggesting a step that brings it to 0.3; "auto" does not pick it there.
TEST(AccuracyEnvelope, TheIncrementalCouplingWithFastParticlesWarns) {
  const char* const kHeavyDisk = R"TOML(
gravity = [0.0, -981.0]
[domain]
size = [1.5, 6.0]
h = 0.010416666666666666
[fluid]
viscosity = 0.01
[time]
dt = 0.001
[[particles]]
center = [1.125, 5.2]
diameter = 0.2
density = 1.5
)TOML";
  const std::vector<std::string> incremental = {"splitting.constraint=\"incremental\""};
  const std::vector<AccuracyWarning> w = AccuracyWarnings(Scene(kHeavyDisk, incremental));
  const auto lagged = std::find_if(
      w.begin(), w.end(), [](const AccuracyWarning& x) { return x.setting == "U_p dt / h"; });
  ASSERT_NE(lagged, w.end());
  EXPECT_NEAR(lagged->value, 1.1916, 1e-3);
  EXPECT_EQ(lagged->allowed, "<= 0.3");
  EXPECT_EQ(lagged->key, "time.dt");
  EXPECT_DOUBLE_EQ(std::stod(lagged->suggested), 0.001 / 4);
  ExpectSuggestionSatisfies(kHeavyDisk, incremental, *lagged);
  for (const AccuracyWarning& x : AccuracyWarnings(Scene(kHeavyDisk))) {  // auto: paper's coupling
    EXPECT_NE(x.setting, "U_p dt / h");
  }
}

}  // namespace
}  // namespace dlmfd
