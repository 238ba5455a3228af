// conformation.velocity = "auto" (scene/auto_conformation_velocity.h): one test per rule, a Params
// built in code that resolves as its scene, the Newtonian and "paper" defaults that resolve
// nothing, and a named velocity that is kept.
#include "dlmfd/scene/auto_conformation_velocity.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace auto_conformation_velocity_test {  // named: the unity build groups the "auto" tests
namespace {

using ::testing::HasSubstr;

// The confined cylinder written as a user would (cases/verification/
// confined_cylinder_oldroyd_b.toml's physics at R/h = 4, no numerics key): a fixed disk in an
// Oldroyd-B channel flow, 150 steps.
const char* const kConfinedCylinder = R"TOML(
[domain]
size = [20.0, 4.0]
h = 0.25
[domain.boundary]
left   = { type = "velocity", profile = "poiseuille", max = [1.5, 0.0] }
right  = { type = "outflow" }
bottom = { type = "wall" }
top    = { type = "wall" }
[fluid]
density = 0.01
viscosity = 1.0
relaxation_time = 0.6
solvent_ratio = 0.59
[time]
dt = 0.005
end = 0.75
[[particles]]
center = [10.0, 2.0]
diameter = 2.0
motion = "fixed"
)TOML";

const ResolvedChoice* VelocityChoice(const Params& p) {
  for (const ResolvedChoice& c : p.numerics.resolved) {
    if (c.key == "conformation.velocity") return &c;
  }
  return nullptr;
}

// Rule 3: fixed disks cut out of the mesh get the Stokes step's velocity, resolved after the
// particle mesh whose kind it reads.
TEST(AutoConformationVelocity, CutCellsGetTheStokesStepsVelocity) {
  const Params p = ParseScene(kConfinedCylinder);
  ASSERT_EQ(p.particle_mesh.kind, ParticleMeshKind::kCutCell);
  EXPECT_EQ(p.conformation.velocity, ConformationVelocity::kStokes);
  const ResolvedChoice* choice = VelocityChoice(p);
  ASSERT_NE(choice, nullptr);
  EXPECT_EQ(choice->value, "stokes");
  EXPECT_THAT(choice->rule, HasSubstr("cut out of the mesh"));
  EXPECT_EQ(p.numerics.resolved.back().key, "conformation.velocity");
  // The scene as run names the velocity chosen, and reading it back resolves nothing.
  const Params again = ParseScene(WriteScene(p));
  EXPECT_EQ(again.conformation.velocity, ConformationVelocity::kStokes);
  EXPECT_EQ(VelocityChoice(again), nullptr);
}

// Rule 2: multiplier points (here a free disk, which cut cells refuse) keep the paper's velocity.
TEST(AutoConformationVelocity, MultiplierPointsKeepTheAdvectedVelocity) {
  const Params p = ParseScene(kConfinedCylinder,
                              {{"particles.0.motion", "\"free\""}, {"particles.0.density", "1.5"}});
  ASSERT_EQ(p.particle_mesh.kind, ParticleMeshKind::kCollocation);
  EXPECT_EQ(p.conformation.velocity, ConformationVelocity::kAdvected);
  ASSERT_NE(VelocityChoice(p), nullptr);
  EXPECT_THAT(VelocityChoice(p)->rule, HasSubstr("particle_mesh.kind = \"collocation\""));
  // The same fixed disk with collocation points named.
  const Params named = ParseScene(kConfinedCylinder, {{"particle_mesh.kind", "\"collocation\""}});
  EXPECT_EQ(named.conformation.velocity, ConformationVelocity::kAdvected);
}

// Rule 1: a polymer without particles gets the Stokes step's velocity, and the scene as run names
// it.
TEST(AutoConformationVelocity, WithoutParticlesItIsTheStokesStepsVelocity) {
  const Params p = ParseScene("[fluid]\nrelaxation_time = 0.1\nsolvent_ratio = 0.5\n");
  EXPECT_EQ(p.conformation.velocity, ConformationVelocity::kStokes);
  ASSERT_NE(VelocityChoice(p), nullptr);
  EXPECT_EQ(VelocityChoice(p)->value, "stokes");
  EXPECT_THAT(VelocityChoice(p)->rule, HasSubstr("no particles"));
  const Params again = ParseScene(WriteScene(p));
  EXPECT_EQ(again.conformation.velocity, ConformationVelocity::kStokes);
  EXPECT_EQ(VelocityChoice(again), nullptr);
}

// A polymer built in code leaves the velocity absent, as a scene that names none: around a fixed
// disk cut out of the mesh ResolveDefaults (and so the Simulation) resolves the same velocity,
// by the same rule, as the same scene read from text, and both write the same scene as run.
TEST(AutoConformationVelocity, ParamsBuiltInCodeResolveAsTheSceneDoes) {
  const Params scene = ParseScene(
      "[fluid]\nrelaxation_time = 0.1\nsolvent_ratio = 0.5\n[particle_mesh]\nkind = "
      "\"cut_cell\"\n[[particles]]\ncenter = [0.5, 0.5]\ndiameter = 0.25\nmotion = \"fixed\"\n");
  Params built;
  built.fluid.relaxation_time = 0.1;
  built.fluid.solvent_ratio = 0.5;
  built.particle_mesh.kind = ParticleMeshKind::kCutCell;
  ParticleParams disk;
  disk.center = Vec2(0.5, 0.5);
  disk.diameter = 0.25;
  disk.motion = Motion::kFixed;
  built.particles.push_back(disk);
  EXPECT_FALSE(built.conformation.velocity.has_value());
  Params resolved = built;
  ResolveDefaults(resolved);
  EXPECT_EQ(scene.conformation.velocity, ConformationVelocity::kStokes);
  EXPECT_EQ(resolved.conformation.velocity, ConformationVelocity::kStokes);
  ASSERT_NE(VelocityChoice(resolved), nullptr);
  EXPECT_EQ(VelocityChoice(resolved)->rule, VelocityChoice(scene)->rule);
  EXPECT_EQ(WriteScene(resolved), WriteScene(scene));
  const Simulation sim(built);
  EXPECT_EQ(sim.params().conformation.velocity, ConformationVelocity::kStokes);
  // The same Params without particles resolves the Stokes step's velocity by rule 1, as its scene
  // does.
  built.particles.clear();
  ResolveDefaults(built);
  EXPECT_EQ(built.conformation.velocity, ConformationVelocity::kStokes);
  ASSERT_NE(VelocityChoice(built), nullptr);
  EXPECT_THAT(VelocityChoice(built)->rule, HasSubstr("no particles"));
}

// A Newtonian liquid has no step (35): "advected" without a rule; numerics.preset = "paper" gives
// the paper's velocity; a named velocity is kept.
TEST(AutoConformationVelocity, NewtonianPaperOrNamedResolveNothing) {
  const Params newtonian = ParseScene(
      kConfinedCylinder, {{"fluid.relaxation_time", "0.0"}, {"fluid.solvent_ratio", "1.0"}});
  EXPECT_EQ(newtonian.conformation.velocity, ConformationVelocity::kAdvected);
  EXPECT_EQ(VelocityChoice(newtonian), nullptr);
  const Params paper = ParseScene(kConfinedCylinder, {{"numerics.preset", "\"paper\""}});
  EXPECT_EQ(paper.conformation.velocity, ConformationVelocity::kAdvected);
  EXPECT_EQ(VelocityChoice(paper), nullptr);
  const Params named = ParseScene(kConfinedCylinder, {{"conformation.velocity", "\"advected\""}});
  EXPECT_EQ(named.particle_mesh.kind, ParticleMeshKind::kCutCell);
  EXPECT_EQ(named.conformation.velocity, ConformationVelocity::kAdvected);
  EXPECT_EQ(VelocityChoice(named), nullptr);
}

}  // namespace
}  // namespace auto_conformation_velocity_test
}  // namespace dlmfd
