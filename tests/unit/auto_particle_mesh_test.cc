// particle_mesh.kind = "auto" (scene/auto_particle_mesh.h): one test per rule (each exclusion
// resolves to collocation points, the fixed disk or ellipse in a Newtonian liquid to cut cells),
// on each side of the run-length bound, and the record of the choice (the numbers, the scene as
// run).
#include "dlmfd/scene/auto_particle_mesh.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"
#include "dlmfd/particles/particle_rules.h"
#include "dlmfd/scene/auto_coupling.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace auto_particle_mesh_test {  // named: the unity build puts auto_coupling_test.cc beside it
namespace {

using ::testing::HasSubstr;

// Schaefer-Turek 2D-1 written as a user would (cases/verification/schaefer_turek_2d1.toml's
// physics, no numerics key): a fixed disk in a Newtonian channel flow, 2400 steps.
const char* const kFixedDisk = R"TOML(
[domain]
size = [2.2, 0.41]
h = 0.005
[domain.boundary]
left   = { type = "velocity", profile = "poiseuille", max = [0.3, 0.0] }
right  = { type = "outflow" }
bottom = { type = "wall" }
top    = { type = "wall" }
[fluid]
viscosity = 0.001
[time]
dt = 0.005
end = 12.0
[[particles]]
center = [0.2, 0.2]
diameter = 0.1
motion = "fixed"
)TOML";

// The same disk in a channel periodic along the flow, where domain.flow_rate may drive it.
std::string PeriodicChannel() {
  std::string text = kFixedDisk;
  const std::string inflow_outflow =
      "left   = { type = \"velocity\", profile = \"poiseuille\", max = [0.3, 0.0] }\n"
      "right  = { type = \"outflow\" }\n";
  text.replace(text.find(inflow_outflow), inflow_outflow.size(),
               "left = { type = \"periodic\" }\nright = { type = \"periodic\" }\n");
  return text;
}

const ResolvedChoice& MeshChoice(const Params& p) {
  for (const ResolvedChoice& c : p.numerics.resolved) {
    if (c.key == "particle_mesh.kind") return c;
  }
  ADD_FAILURE() << "particle_mesh.kind was not resolved";
  static const ResolvedChoice none;
  return none;
}

double Number(const ResolvedChoice& c, const std::string& name) {
  for (const auto& [n, value] : c.numbers) {
    if (n == name) return value;
  }
  ADD_FAILURE() << "no number " << name;
  return 0.0;
}

std::string Steps(long n) { return ExactText(0.005 * static_cast<double>(n)); }

// Rule 6: fixed disks in a Newtonian liquid over a long run.
TEST(AutoParticleMesh, AFixedDiskInANewtonianLiquidGetsCutCells) {
  const Params p = ParseScene(kFixedDisk);
  EXPECT_EQ(p.particle_mesh.kind, ParticleMeshKind::kCutCell);
  EXPECT_EQ(MeshChoice(p).value, "cut_cell");
  EXPECT_EQ(Number(MeshChoice(p), "steps"), 2400.0);
  // The coupling is resolved first, and its weights are those cut cells need.
  EXPECT_EQ(p.numerics.resolved.front().key, "splitting.constraint");
  EXPECT_EQ(p.splitting.beta, 0.0);
}

// Rule 1: nothing to hold.
TEST(AutoParticleMesh, WithoutParticlesItIsCollocation) {
  const Params p = ParseScene("[time]\ndt = 0.01\n");
  EXPECT_EQ(p.particle_mesh.kind, ParticleMeshKind::kCollocation);
  EXPECT_EQ(MeshChoice(p).rule, "no particles");
}

// Rule 2: a fixed ellipse in a Newtonian liquid is cut out of the mesh as a disk is (measured:
// docs/evidence/cut_cell_boundary.md, "A fixed ellipse"); a moving one, or one in a polymer
// liquid, keeps the collocation points (the cut cells were not measured there).
TEST(AutoParticleMesh, OnlyAFixedEllipseInANewtonianLiquidGetsCutCells) {
  const std::string scene = std::string(kFixedDisk) + R"TOML(
[[particles]]
center = [1.0, 0.2]
shape = "ellipse"
semi_axes = [0.05, 0.025]
motion = "fixed"
)TOML";
  const Params p = ParseScene(scene);
  EXPECT_EQ(p.particle_mesh.kind, ParticleMeshKind::kCutCell);
  const Params polymer =
      ParseScene(scene, {{"fluid.relaxation_time", "0.1"}, {"fluid.solvent_ratio", "0.5"}});
  EXPECT_EQ(polymer.particle_mesh.kind, ParticleMeshKind::kCollocation);
  EXPECT_THAT(MeshChoice(polymer).rule, HasSubstr("particles.1 is not a disk"));
  const Params moving = ParseScene(scene, {{"particles.1.motion", "\"prescribed\""}});
  EXPECT_EQ(moving.particle_mesh.kind, ParticleMeshKind::kCollocation);
  EXPECT_THAT(MeshChoice(moving).rule, HasSubstr("particles.1 is not a disk"));
}

// Rule 4: the polymers the cut cells were measured with (Oldroyd-B, Giesekus) get them around
// fixed disks, like a Newtonian liquid; the others keep the collocation points, and get cut cells
// when the scene names them.
TEST(AutoParticleMesh, OldroydBAndGiesekusGetCutCells) {
  const std::vector<SceneOverride> oldroyd_b = {{"fluid.relaxation_time", "0.1"},
                                                {"fluid.solvent_ratio", "0.5"}};
  const Params p = ParseScene(kFixedDisk, oldroyd_b);
  EXPECT_EQ(p.particle_mesh.kind, ParticleMeshKind::kCutCell);
  std::vector<SceneOverride> giesekus = oldroyd_b;
  giesekus.push_back({"fluid.model", "\"giesekus\""});
  giesekus.push_back({"fluid.mobility", "0.1"});
  EXPECT_EQ(ParseScene(kFixedDisk, giesekus).particle_mesh.kind, ParticleMeshKind::kCutCell);
}

TEST(AutoParticleMesh, AnUnmeasuredPolymerKeepsCollocationPoints) {
  const std::vector<SceneOverride> fene_p = {{"fluid.relaxation_time", "0.1"},
                                             {"fluid.solvent_ratio", "0.5"},
                                             {"fluid.model", "\"fene_p\""},
                                             {"fluid.extensibility", "100"}};
  const Params p = ParseScene(kFixedDisk, fene_p);
  EXPECT_EQ(p.particle_mesh.kind, ParticleMeshKind::kCollocation);
  EXPECT_THAT(MeshChoice(p).rule, HasSubstr("fluid.model = \"fene_p\""));
  std::vector<SceneOverride> named = fene_p;
  named.push_back({"particle_mesh.kind", "\"cut_cell\""});
  EXPECT_EQ(ParseScene(kFixedDisk, named).particle_mesh.kind, ParticleMeshKind::kCutCell);
}

// Rule 5: each scene the cut cells refuse resolves to collocation points, naming the key that
// RequireCutCellScene names when the scene asks for cut cells (one predicate, CutCellObstacle).
TEST(AutoParticleMesh, EveryCutCellRefusalResolvesToCollocation) {
  const std::vector<std::pair<std::vector<SceneOverride>, std::string>> refused = {
      {{{"splitting.constraint", "\"paper\""}}, "splitting.beta"},  // beta follows: 1/2
      {{{"domain.flow_rate", "0.05"}}, "domain.flow_rate"},
  };
  for (const auto& [overrides, key] : refused) {
    const std::string scene = key == "domain.flow_rate" ? PeriodicChannel() : kFixedDisk;
    const Params p = ParseScene(scene, overrides);
    EXPECT_EQ(p.particle_mesh.kind, ParticleMeshKind::kCollocation) << key;
    EXPECT_THAT(MeshChoice(p).rule, HasSubstr("cut cells cannot run " + key)) << key;
    std::vector<SceneOverride> named = overrides;
    named.push_back({"particle_mesh.kind", "\"cut_cell\""});
    try {
      ParseScene(scene, named);
      ADD_FAILURE() << key << ": cut cells named and not refused";
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.key(), key);
    }
  }
}

// Rule 3: a body in prescribed motion or a free one, which cut cells can run (named, they take
// it), keeps the collocation points.
TEST(AutoParticleMesh, AMovingBodyKeepsCollocationPoints) {
  const std::vector<std::vector<SceneOverride>> moving = {
      {{"particles.0.motion", "\"prescribed\""}},
      {{"particles.0.motion", "\"free\""}, {"particles.0.density", "1.5"}}};
  for (const std::vector<SceneOverride>& overrides : moving) {
    const Params p = ParseScene(kFixedDisk, overrides);
    EXPECT_EQ(p.particle_mesh.kind, ParticleMeshKind::kCollocation);
    EXPECT_THAT(MeshChoice(p).rule, HasSubstr("particles.0 moves"));
    std::vector<SceneOverride> named = overrides;
    named.push_back({"particle_mesh.kind", "\"cut_cell\""});
    EXPECT_EQ(ParseScene(kFixedDisk, named).particle_mesh.kind, ParticleMeshKind::kCutCell);
  }
}

// Rule 5: on each side of the run length from which the set-up pays.
TEST(AutoParticleMesh, AShortRunKeepsCollocationPoints) {
  const Params shorter = ParseScene(kFixedDisk, {{"time.end", Steps(kMinCutCellSteps - 1)}});
  EXPECT_EQ(shorter.particle_mesh.kind, ParticleMeshKind::kCollocation);
  EXPECT_THAT(MeshChoice(shorter).rule, HasSubstr("fewer steps"));
  EXPECT_EQ(Number(MeshChoice(shorter), "steps"), static_cast<double>(kMinCutCellSteps - 1));
  const Params enough = ParseScene(kFixedDisk, {{"time.end", Steps(kMinCutCellSteps)}});
  EXPECT_EQ(enough.particle_mesh.kind, ParticleMeshKind::kCutCell);
}

// numerics.preset = "paper" keeps the ring mesh; a named kind is kept; nothing is resolved then.
TEST(AutoParticleMesh, APresetOrANamedKindIsKept) {
  const Params paper = ParseScene(kFixedDisk, {{"numerics.preset", "\"paper\""}});
  EXPECT_EQ(paper.particle_mesh.kind, ParticleMeshKind::kRing);
  EXPECT_TRUE(paper.numerics.resolved.empty());
  const Params named = ParseScene(kFixedDisk, {{"particle_mesh.kind", "\"collocation\""}});
  EXPECT_EQ(named.particle_mesh.kind, ParticleMeshKind::kCollocation);
  ASSERT_EQ(named.numerics.resolved.size(), 1u);
  EXPECT_EQ(named.numerics.resolved.front().key, "splitting.constraint");
}

// "auto" named in the scene resolves after the coupling as the preset's does, whichever the scene
// names (the rules read the weights that follow the coupling).
TEST(AutoParticleMesh, NamedAutoResolvesAfterTheCoupling) {
  const Params p = ParseScene(
      kFixedDisk, {{"particle_mesh.kind", "\"auto\""}, {"splitting.constraint", "\"auto\""}});
  ASSERT_EQ(p.numerics.resolved.size(), 2u);
  EXPECT_EQ(p.numerics.resolved[0].key, "splitting.constraint");
  EXPECT_EQ(p.numerics.resolved[1].key, "particle_mesh.kind");
  EXPECT_EQ(p.particle_mesh.kind, ParticleMeshKind::kCutCell);
  const Params paper = ParseScene(
      kFixedDisk, {{"particle_mesh.kind", "\"auto\""}, {"splitting.constraint", "\"paper\""}});
  EXPECT_EQ(paper.particle_mesh.kind, ParticleMeshKind::kCollocation);
}

// The scene as run names the kind chosen, so a rerun (even a shorter one) uses the same.
TEST(AutoParticleMesh, TheSceneAsRunNamesTheChoice) {
  const std::string text = WriteScene(ParseScene(kFixedDisk));
  EXPECT_THAT(text, HasSubstr("kind = \"cut_cell\"\n"));
  const Params again = ParseScene(text, {{"time.end", "0.005"}});
  EXPECT_EQ(again.particle_mesh.kind, ParticleMeshKind::kCutCell);
  EXPECT_TRUE(again.numerics.resolved.empty());
}

TEST(AutoParticleMesh, TheTextNamesTheRuleAndItsNumbers) {
  const std::string text = ResolvedChoiceText(MeshChoice(ParseScene(kFixedDisk)));
  EXPECT_THAT(text, HasSubstr("particle_mesh.kind = \"cut_cell\" (auto: fixed bodies"));
  EXPECT_THAT(text, HasSubstr("steps = 2400"));
}

}  // namespace
}  // namespace auto_particle_mesh_test
}  // namespace dlmfd
