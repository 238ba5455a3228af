// Scene files (design.md 3.1): bad scenes are rejected with the key, the value and what is allowed
// (the ranges and the module rules of scene/scene_validation.h, the footprint limits); good scenes
// give the stated values; defaults; --set overrides; WriteScene round-trips exactly.
#include "dlmfd/scene/scene_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include "../support/scratch_path.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/scene/scene_footprint.h"
#include "dlmfd/scene/scene_validation.h"

namespace dlmfd {
namespace {

using ::testing::HasSubstr;

// The example scene of design.md 3.1 (paper 5.2), written out in full.
const char* const kPaperScene = R"TOML(
title = "Two disks in an Oldroyd-B liquid (paper 5.2)"

[domain]
size = [2.0, 8.0]
h = 0.010416666666666666
[domain.boundary]
left   = { type = "wall" }
right  = { type = "wall" }
bottom = { type = "velocity", profile = "poiseuille", max = [0.0, 0.5] }
top    = { type = "outflow" }

[fluid]
density = 1.0
viscosity = 0.12
relaxation_time = 1.4
solvent_ratio = 0.5

gravity = [0.0, -981.0]

[time]
dt = 0.0004
end = 25.0

[splitting]
advection = "least_squares"

[[particles]]
center = [1.0, 7.7]
diameter = 0.2
density = 1.01
velocity = [0.0, 0.0]
angular_velocity = 0.0
motion = "free"

[[particles]]
center = [1.0, 7.3]
diameter = 0.2
density = 1.01

[particle_mesh]
h = 0.014285714285714285

[collisions]
range = 1.5
wall_stiffness = 1.0e-5
particle_stiffness = 2.0e-5

[output]
fields_every = 0.1
particles_every = 0.01
checkpoint_every = 1.0
)TOML";

// ----- bad scenes
// ---------------------------------------------------------------------------------

struct BadScene {
  const char* name;
  const char* text;
  const char* key;    // expected InvalidParameter::key()
  const char* value;  // expected InvalidParameter::value()
};

std::ostream& operator<<(std::ostream& os, const BadScene& b) { return os << b.name; }

class BadSceneTest : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadSceneTest, RejectedNamingKeyValueAndAllowed) {
  const BadScene& bad = GetParam();
  try {
    ParseScene(bad.text);
    FAIL() << "accepted: " << bad.text;
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), bad.key) << e.what();
    EXPECT_EQ(e.value(), bad.value) << e.what();
    EXPECT_FALSE(e.allowed().empty());
    const std::string message = e.what();
    EXPECT_THAT(message, HasSubstr(bad.key));
    EXPECT_THAT(message, HasSubstr(bad.value));
    EXPECT_THAT(message, HasSubstr(e.allowed()));
  }
}

const BadScene kBadScenes[] = {
    // domain.flow_rate: in a channel periodic in one direction, Dirichlet across it; in a box
    // periodic in both directions only 0.
    {"FlowRateInAClosedBox", "[domain]\nflow_rate = 0.0\n", "domain.flow_rate", "0.0"},
    {"FlowRateFullyPeriodic",
     "[domain]\nflow_rate = 0.5\n[domain.boundary]\nleft = { type = \"periodic\" }\n"
     "right = { type = \"periodic\" }\nbottom = { type = \"periodic\" }\n"
     "top = { type = \"periodic\" }\n",
     "domain.flow_rate", "0.5"},
    {"FlowRateBesideAnOutflow",
     "[domain]\nflow_rate = 0.0\n[domain.boundary]\nleft = { type = \"outflow\" }\n"
     "bottom = { type = \"periodic\" }\ntop = { type = \"periodic\" }\n",
     "domain.boundary.left.type", "\"outflow\""},
    {"FlowRateNotANumber", "[domain]\nflow_rate = \"zero\"\n", "domain.flow_rate", "\"zero\""},
    {"UnknownTopKey", "visc = 1.0\n", "visc", "1.0"},
    {"UnknownFluidKey", "[fluid]\nviscosty = 0.1\n", "fluid.viscosty", "0.1"},
    {"FluidNotATable", "fluid = 1.0\n", "fluid", "1.0"},
    {"ViscosityWrongType", "[fluid]\nviscosity = \"high\"\n", "fluid.viscosity", "\"high\""},
    {"ViscosityNegative", "[fluid]\nviscosity = -0.1\n", "fluid.viscosity", "-0.1"},
    {"DensityZero", "[fluid]\ndensity = 0.0\n", "fluid.density", "0.0"},
    {"RelaxationTimeNegative", "[fluid]\nrelaxation_time = -1.0\n", "fluid.relaxation_time",
     "-1.0"},
    {"SolventRatioZero", "[fluid]\nsolvent_ratio = 0.0\n", "fluid.solvent_ratio", "0.0"},
    {"SolventRatioAboveOne", "[fluid]\nsolvent_ratio = 1.5\n", "fluid.solvent_ratio", "1.5"},
    {"BodyForceScalar", "[fluid]\nbody_force = 1.0\n", "fluid.body_force", "1.0"},
    {"GravityTwice", "gravity = [0.0, -1.0]\n[fluid]\ngravity = [0.0, -2.0]\n", "fluid.gravity",
     "[0.0, -2.0]"},
    {"GravityOneComponent", "gravity = [0.0]\n", "gravity", "[0.0]"},
    {"DtZero", "[time]\ndt = 0.0\n", "time.dt", "0.0"},
    {"DtNegative", "[time]\ndt = -0.001\n", "time.dt", "-0.001"},
    {"EndNegative", "[time]\nend = -1.0\n", "time.end", "-1.0"},
    // Issue 38: a run to t = 0 made no step and "completed".
    {"EndZero", "[time]\nend = 0.0\n", "time.end", "0.0"},
    {"EndNegativeZero", "[time]\nend = -0.0\n", "time.end", "-0.0"},
    // Issue 38: a ring mesh coarser than the disk (even h_p = 1e300) ran.
    {"ParticleMeshCoarserThanTheDisk",
     "[particle_mesh]\nkind = \"ring\"\nh = 1e300\n[[particles]]\ncenter = [0.5, 0.5]\n"
     "diameter = 0.2\n"
     "density = 1.5\n",
     "particle_mesh.h", "1e+300"},
    {"DtLongerThanEnd", "[time]\ndt = 0.5\nend = 0.1\n", "time.dt", "0.5"},
    {"StepCountBeyond2To53", "[time]\ndt = 1e-300\nend = 1e300\n", "time.dt", "1e-300"},
    {"SizeNotMultipleOfH", "[domain]\nsize = [1.0, 1.0]\nh = 0.3\n", "domain.size", "[1.0, 1.0]"},
    {"SizeOddCells", "[domain]\nsize = [1.0, 2.0]\nh = 0.2\n", "domain.size", "[1.0, 2.0]"},
    {"SizeZeroWidth", "[domain]\nsize = [0.0, 1.0]\n", "domain.size", "[0.0, 1.0]"},
    {"HNegative", "[domain]\nh = -0.1\n", "domain.h", "-0.1"},
    {"GridTooLarge", "[domain]\nsize = [100.0, 100.0]\nh = 0.001\n", "domain.h", "0.001"},
    {"GridTiny", "[domain]\nh = 1e-300\n", "domain.h", "1e-300"},
    {"TooFewCellsForThePressureMesh", "[domain]\nsize = [1.0, 2.0]\nh = 0.5\n", "domain.size",
     "[1.0, 2.0]"},
    {"SideTypeUnknown", "[domain.boundary]\nleft = { type = \"slip\" }\n",
     "domain.boundary.left.type", "\"slip\""},
    {"SideTypeMissing", "[domain.boundary]\nleft = { profile = \"uniform\" }\n",
     "domain.boundary.left.type", "(missing)"},
    {"PeriodicUnpaired", "[domain.boundary]\nleft = { type = \"periodic\" }\n",
     "domain.boundary.right.type", "(not periodic)"},
    {"PeriodicUnpairedTop", "[domain.boundary]\ntop = { type = \"periodic\" }\n",
     "domain.boundary.bottom.type", "(not periodic)"},
    {"UniformWithoutValue", "[domain.boundary]\ntop = { type = \"velocity\" }\n",
     "domain.boundary.top.value", "(missing)"},
    {"PoiseuilleWithoutMax",
     "[domain.boundary]\ntop = { type = \"velocity\", profile = \"poiseuille\" }\n",
     "domain.boundary.top.max", "(missing)"},
    {"PoiseuilleWithValue",
     "[domain.boundary]\ntop = { type = \"velocity\", profile = \"poiseuille\", max = [1.0, 0.0], "
     "value = [1.0, 0.0] }\n",
     "domain.boundary.top.value", "[1.0, 0.0]"},
    {"QuarticWithANormalComponent",
     "[domain.boundary]\ntop = { type = \"velocity\", profile = \"quartic\", max = [1.0, 0.5] }\n",
     "domain.boundary.top.max", "[1.0, 0.5]"},
    {"QuarticWithValue",
     "[domain.boundary]\ntop = { type = \"velocity\", profile = \"quartic\", max = [1.0, 0.0], "
     "value = [1.0, 0.0] }\n",
     "domain.boundary.top.value", "[1.0, 0.0]"},
    {"RampTimeNegative",
     "[domain.boundary]\ntop = { type = \"velocity\", value = [1.0, 0.0], ramp_time = -0.5 }\n",
     "domain.boundary.top.ramp_time", "-0.5"},
    {"RampTimeOnAnInflow",
     "[domain.boundary]\nleft = { type = \"velocity\", profile = \"poiseuille\", max = [1.0, 0.0], "
     "ramp_time = 0.5 }\nright = { type = \"outflow\" }\n",
     "domain.boundary.left.ramp_time", "0.5"},
    {"RampTimeOnAWall", "[domain.boundary]\nleft = { type = \"wall\", ramp_time = 0.5 }\n",
     "domain.boundary.left.ramp_time", "0.5"},
    {"ProfileUnknown",
     "[domain.boundary]\ntop = { type = \"velocity\", profile = \"parabolic\", max = [1.0, 0.0] "
     "}\n",
     "domain.boundary.top.profile", "\"parabolic\""},
    {"WallWithValue", "[domain.boundary]\nleft = { type = \"wall\", value = [1.0, 0.0] }\n",
     "domain.boundary.left.value", "[1.0, 0.0]"},
    {"OutflowWithMax", "[domain.boundary]\ntop = { type = \"outflow\", max = [1.0, 0.0] }\n",
     "domain.boundary.top.max", "[1.0, 0.0]"},
    {"SideNameUnknown", "[domain.boundary]\nfront = { type = \"wall\" }\n", "domain.boundary.front",
     "{ type = \"wall\" }"},
    {"SideNotATable", "[domain.boundary]\nleft = \"wall\"\n", "domain.boundary.left", "\"wall\""},
    {"GammaNonZero", "[splitting]\nalpha = 0.5\nbeta = 0.4\n", "splitting.beta", "0.4"},
    {"AlphaAboveOne", "[splitting]\nalpha = 1.5\nbeta = -0.5\n", "splitting.alpha", "1.5"},
    {"AlphaZero", "[splitting]\nalpha = 0.0\nbeta = 1.0\n", "splitting.alpha", "0.0"},
    {"AdvectionUnknown", "[splitting]\nadvection = \"upwind\"\n", "splitting.advection",
     "\"upwind\""},
    {"ConstraintUnknown", "[splitting]\nconstraint = \"implicit\"\n", "splitting.constraint",
     "\"implicit\""},
    {"StressSplittingUnknown", "[fluid]\nstress_splitting = \"implicit\"\n",
     "fluid.stress_splitting", "\"implicit\""},
    {"SteadyCorrectionUnknown", "[splitting]\nadvection = \"wave\"\nsteady_correction = \"full\"\n",
     "splitting.steady_correction", "\"full\""},
    {"DiagonalsUnknown", "[domain]\ndiagonals = \"nw_se\"\n", "domain.diagonals", "\"nw_se\""},
    {"ViscousConstraintWithViscosityInAdvection",
     "[splitting]\nalpha = 0.5\nbeta = 0.5\nconstraint = \"viscous\"\n[[particles]]\ncenter = "
     "[0.5, 0.5]\n",
     "splitting.beta", "0.5"},
    {"IncrementalConstraintWithViscosityInAdvection",
     "[splitting]\nalpha = 0.5\nbeta = 0.5\n[[particles]]\ncenter = [0.5, 0.5]\n", "splitting.beta",
     "0.5"},
    {"ViscousConstraintWithNeutralParticle",
     "[splitting]\nalpha = 1.0\nbeta = 0.0\nconstraint = \"viscous\"\n[[particles]]\ncenter = "
     "[0.5, 0.5]\ndensity = 1.0\n",
     "particles.0.density", "1.0"},
    {"StokesToleranceOne", "[solvers]\nstokes_tolerance = 1.0\n", "solvers.stokes_tolerance",
     "1.0"},
    {"StokesMaxIterationsZero", "[solvers]\nstokes_max_iterations = 0\n",
     "solvers.stokes_max_iterations", "0"},
    {"MultiplierIterationsReal", "[solvers]\nmultiplier_max_iterations = 10.5\n",
     "solvers.multiplier_max_iterations", "10.5"},
    {"WaveCourantZero", "[solvers]\nwave_max_courant = 0.0\n", "solvers.wave_max_courant", "0.0"},
    {"ParticleMeshHZero", "[particle_mesh]\nh = 0.0\n", "particle_mesh.h", "0.0"},
    {"ParticleMeshKindUnknown", "[particle_mesh]\nkind = \"cut_cells\"\n", "particle_mesh.kind",
     "\"cut_cells\""},
    {"CutCellWithAPrescribedEllipseThinnerThanItsCells",  // b^2 / a = 0.8 h
     "[particle_mesh]\nkind = \"cut_cell\"\n[domain.boundary]\nright = { type = \"outflow\" }\n"
     "[[particles]]\ncenter = [0.5, 0.5]\nshape = \"ellipse\"\nsemi_axes = [0.1, 0.05]\n"
     "motion = \"prescribed\"\n",
     "domain.h", "0.03125"},
    {"CutCellWithAPrescribedEllipseInAPolymer",
     "[particle_mesh]\nkind = \"cut_cell\"\n[domain.boundary]\nright = { type = \"outflow\" }\n"
     "[fluid]\nrelaxation_time = 1.0\nsolvent_ratio = 0.5\n"
     "[[particles]]\ncenter = [0.5, 0.5]\nshape = \"ellipse\"\nsemi_axes = [0.1, 0.05]\n"
     "motion = \"prescribed\"\n",
     "particles.0.shape", "\"ellipse\""},
    {"CutCellWithViscosityInAdvection",
     "[particle_mesh]\nkind = \"cut_cell\"\n[domain.boundary]\nright = { type = \"outflow\" }\n"
     "[splitting]\nconstraint = \"paper\"\n[[particles]]\ncenter = [0.5, 0.5]\nmotion = "
     "\"fixed\"\n",
     "splitting.beta", "0.5"},
    {"CutCellWithAFlowRate",
     "[particle_mesh]\nkind = \"cut_cell\"\n[domain]\nflow_rate = 0.5\n[domain.boundary]\n"
     "left = { type = \"periodic\" }\nright = { type = \"periodic\" }\n[[particles]]\n"
     "center = [0.5, 0.5]\nmotion = \"fixed\"\n",
     "domain.flow_rate", "0.5"},
    {"CollocationSpacingBelowHalf", "[particle_mesh]\nkind = \"collocation\"\nspacing = 0.25\n",
     "particle_mesh.spacing", "0.25"},
    {"CollocationSpacingAboveFour", "[particle_mesh]\nspacing = 5.0\n", "particle_mesh.spacing",
     "5.0"},
    {"BoundaryInterpolationUnknown", "[particle_mesh]\ninterpolation = \"cubic\"\n",
     "particle_mesh.interpolation", "\"cubic\""},
    {"ParticleMeshTiny",
     "[particle_mesh]\nkind = \"ring\"\nh = 1e-300\n[[particles]]\ncenter = [0.5, 0.5]\n"
     "density = 1.5\n",
     "particle_mesh.h", "1e-300"},
    {"CollisionRangeZero", "[collisions]\nrange = 0.0\n", "collisions.range", "0.0"},
    {"WallStiffnessNegative", "[collisions]\nwall_stiffness = -1e-5\n", "collisions.wall_stiffness",
     "-1e-05"},
    {"ParticleStiffnessZero", "[collisions]\nparticle_stiffness = 0\n",
     "collisions.particle_stiffness", "0.0"},
    {"SubstepsZero", "[collisions]\nsubsteps = 0\n", "collisions.substeps", "0"},
    {"ConformationFormLog", "[conformation]\nform = \"log\"\n", "conformation.form", "\"log\""},
    {"BlendKappaZero", "[conformation]\nblend_kappa = 0.0\n", "conformation.blend_kappa", "0.0"},
    {"FieldsEveryNegative", "[output]\nfields_every = -0.1\n", "output.fields_every", "-0.1"},
    {"CheckpointPeriodBeyond2To53", "[output]\ncheckpoint_every = 1e-300\n",
     "output.checkpoint_every", "1e-300"},
    {"InflowWithoutSteadyState",
     "[domain.boundary]\nbottom = { type = \"velocity\", profile = \"poiseuille\", max = [0.5, "
     "1.0] }\ntop = { type = \"outflow\" }\n[fluid]\nrelaxation_time = 1.0\nsolvent_ratio = 0.5\n",
     "fluid.relaxation_time", "1.0"},
    {"CheckpointEveryString", "[output]\ncheckpoint_every = \"often\"\n", "output.checkpoint_every",
     "\"often\""},
    {"ParticleMissingCenter",
     "[fluid]\ndensity = 1.0\n[[particles]]\ndiameter = 0.2\ndensity = 1.5\n", "particles.0.center",
     "(missing)"},
    {"ParticleDiameterZero", "[[particles]]\ncenter = [0.5, 0.5]\ndiameter = 0.0\ndensity = 1.5\n",
     "particles.0.diameter", "0.0"},
    {"ParticleDensityNegative",
     "[[particles]]\ncenter = [0.5, 0.5]\ndiameter = 0.2\ndensity = -1.5\n", "particles.0.density",
     "-1.5"},
    {"ParticleMotionUnknown",
     "[[particles]]\ncenter = [0.5, 0.5]\ndensity = 1.5\nmotion = \"spinning\"\n",
     "particles.0.motion", "\"spinning\""},
    {"ParticleLighterThanFluid",
     "[fluid]\ndensity = 1.0\n[[particles]]\ncenter = [0.5, 0.5]\ndensity = 0.9\n",
     "particles.0.density", "0.9"},
    {"ParticleOutsideDomain", "[[particles]]\ncenter = [1.5, 0.5]\ndensity = 1.5\n",
     "particles.0.center", "[1.5, 0.5]"},
    {"ParticleCrossesWall", "[[particles]]\ncenter = [0.5, 0.05]\ndiameter = 0.2\ndensity = 1.5\n",
     "particles.0.center", "[0.5, 0.05]"},
    {"ParticlesOverlap",
     "[[particles]]\ncenter = [0.5, 0.5]\ndensity = 1.5\n[[particles]]\ncenter = [0.5, "
     "0.65]\ndensity = 1.5\n",
     "particles.1.center", "[0.5, 0.65]"},
    {"ParticlesOverlapAcrossPeriodicSides",
     "[domain.boundary]\nleft = { type = \"periodic\" }\nright = { type = \"periodic\" }\n"
     "[[particles]]\ncenter = [0.02, 0.5]\ndensity = 1.5\n[[particles]]\ncenter = [0.95, "
     "0.5]\ndensity = 1.5\n",
     "particles.1.center", "[0.95, 0.5]"},
    {"ParticleUnknownKey", "[[particles]]\ncenter = [0.5, 0.5]\ndensity = 1.5\ncolour = \"red\"\n",
     "particles.0.colour", "\"red\""},
    {"ParticlesNotTables", "particles = [1, 2]\n", "particles.0", "1"},
    {"TitleNotString", "title = 3\n", "title", "3"},
    {"NotToml", "[fluid\nviscosity = 1\n", "scene", "line 1 column 7"},
};

INSTANTIATE_TEST_SUITE_P(SceneFile, BadSceneTest, ::testing::ValuesIn(kBadScenes),
                         [](const ::testing::TestParamInfo<BadScene>& param_info) {
                           return std::string(param_info.param.name);
                         });

TEST(SceneFile, OverlapMessageNamesBothParticlesAndTheGap) {
  try {
    ParseScene(
        "[[particles]]\ncenter = [0.5, 0.5]\ndensity = 1.5\n"
        "[[particles]]\ncenter = [0.5, 0.65]\ndensity = 1.5\n");
    FAIL();
  } catch (const InvalidParameter& e) {
    // Radii 0.1 + 0.1, distance 0.15: gap -0.05 (to rounding).
    EXPECT_THAT(e.allowed(), HasSubstr("particles 0 and 1"));
    EXPECT_THAT(e.allowed(), HasSubstr("gap -0.05"));
  }
}

TEST(SceneFile, GridTooLargeEstimatesMemory) {
  try {
    ParseScene("[domain]\nsize = [100.0, 100.0]\nh = 0.001\n");
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_THAT(e.allowed(), HasSubstr("GiB"));
  }
}

TEST(SceneFile, StepCountMessageNamesTimeEnd) {
  try {
    ParseScene("[time]\ndt = 1e-300\nend = 1e300\n");
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_THAT(e.allowed(), HasSubstr("time.end"));
    EXPECT_THAT(e.allowed(), HasSubstr("2^53"));
  }
}

TEST(SceneFile, InflowMessageNamesTheSide) {
  try {
    ParseScene(
        "[domain.boundary]\nleft = { type = \"velocity\", profile = \"poiseuille\", max = [1.0, "
        "2.0] }\nright = { type = \"outflow\" }\n[fluid]\nrelaxation_time = 1.0\n"
        "solvent_ratio = 0.5\n");
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_THAT(e.allowed(), HasSubstr("domain.boundary.left"));
    EXPECT_THAT(e.allowed(), HasSubstr("no steady Oldroyd-B state"));
  }
}

// A normal Poiseuille inflow (L^2 = 0) has a steady state at any lambda; so has any inflow of a
// Newtonian liquid, which has no conformation.
TEST(SceneFile, InflowStatesThatExistAreAccepted) {
  const std::string sides =
      "[domain.boundary]\nbottom = { type = \"velocity\", profile = \"poiseuille\", max = [0.0, "
      "1.0] }\ntop = { type = \"outflow\" }\n";
  EXPECT_NO_THROW(ParseScene(sides + "[fluid]\nrelaxation_time = 100.0\nsolvent_ratio = 0.5\n"));
  const std::string tangential =
      "[domain.boundary]\nbottom = { type = \"velocity\", profile = \"poiseuille\", max = [0.5, "
      "1.0] }\ntop = { type = \"outflow\" }\n";
  EXPECT_NO_THROW(ParseScene(tangential + "[fluid]\nrelaxation_time = 1.0\n"));
  // 2 lambda max Re eig(L) = 2 lambda 4 (0.5) / 1 = 4 lambda < 1.
  EXPECT_NO_THROW(ParseScene(tangential + "[fluid]\nrelaxation_time = 0.2\nsolvent_ratio = 0.5\n"));
}

// The regularised, ramped lid of Fattal & Kupferman (2005) (fluid/boundary_profile.h): tangential,
// so no liquid enters and no inflow state limits lambda (their Wi = 3 and beyond).
TEST(SceneFile, RegularisedLidIsReadAndNeedsNoInflowState) {
  const Params p = ParseScene(
      "[domain.boundary]\ntop = { type = \"velocity\", profile = \"quartic\", max = [1.0, 0.0], "
      "ramp_time = 0.5 }\n[fluid]\nrelaxation_time = 3.0\nsolvent_ratio = 0.5\n");
  const BoundarySide& top = p.domain.side(Side::kTop);
  EXPECT_EQ(top.type, SideType::kVelocity);
  EXPECT_EQ(top.profile, Profile::kQuartic);
  EXPECT_EQ(top.max, Vec2(1.0, 0.0));
  EXPECT_EQ(top.ramp_time, 0.5);
  EXPECT_EQ(ParseScene("[domain.boundary]\ntop = { type = \"velocity\", value = [1.0, 0.0] }\n")
                .domain.side(Side::kTop)
                .ramp_time,
            0.0);
}

TEST(SceneFile, ValidateSceneChecksParamsBuiltInCode) {
  Params p;
  EXPECT_NO_THROW(ValidateScene(p));
  p.splitting.alpha = 0.0;
  p.splitting.beta = 1.0;
  try {
    ValidateScene(p);
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "splitting.alpha");
  }
}

TEST(SceneFile, FootprintIsFiniteForTinyMeshSizes) {
  Params p;
  p.domain.h = 1e-300;
  ParticleParams q;
  q.center = Vec2(0.5, 0.5);
  p.particles.push_back(q);
  p.particle_mesh.h = 1e-300;
  const SceneFootprint f = EstimateFootprint(p);
  EXPECT_TRUE(std::isfinite(f.velocity_nodes));
  EXPECT_TRUE(std::isfinite(f.multiplier_nodes));
  EXPECT_TRUE(std::isfinite(f.bytes));
  EXPECT_GT(f.velocity_nodes, kMaxVelocityNodes);
  EXPECT_GT(f.multiplier_nodes, kMaxMultiplierNodes);
}

TEST(SceneFile, FootprintCountsTheGridAndBoundsTheRingMeshes) {
  Params p;  // 32 x 32 cells
  ParticleParams q;
  q.center = Vec2(0.5, 0.5);
  q.diameter = 0.2;
  p.particles.push_back(q);
  p.particle_mesh.kind = ParticleMeshKind::kRing;
  p.particle_mesh.h = 1.0 / 35;  // R / h_p = 3.5: 4 rings of 5, 11, 16, 22 nodes and the centre
  const SceneFootprint f = EstimateFootprint(p);
  EXPECT_EQ(f.velocity_nodes, 33.0 * 33.0);
  EXPECT_GE(f.multiplier_nodes, 55.0);
  EXPECT_LE(f.multiplier_nodes, 2.0 * 55.0);
  EXPECT_EQ(f.bytes, kBytesPerNode * (f.velocity_nodes + f.multiplier_nodes));
}

// The viscous coupling around fixed particles keeps 16 PCG directions (particles/
// recycled_directions.h): 16 x 2.25 doubles a velocity node more (measured: 295 bytes a node, a
// fixed disk at R/h = 16 on 481 x 65 nodes, 57.8 MB against 48.6 MB of maximum RSS).
TEST(SceneFile, FootprintCountsTheRecycledDirectionsOfFixedParticles) {
  Params p;
  ParticleParams q;
  q.center = Vec2(0.5, 0.5);
  q.motion = Motion::kFixed;
  p.particles.push_back(q);
  p.splitting.constraint = ConstraintCoupling::kViscous;
  const SceneFootprint fixed = EstimateFootprint(p);
  p.particles[0].motion = Motion::kFree;
  const SceneFootprint free = EstimateFootprint(p);
  EXPECT_NEAR(fixed.bytes - free.bytes, 16 * 2.25 * 8.0 * fixed.velocity_nodes, 1e-9 * fixed.bytes);
}

// Cut cells (scene/scene_footprint.h): kCutCellBytesPerNode a velocity node, and a moving body's
// responses, a node array for each of its 11.25 D/h + 10 capacitance rows (measured 216 rows at
// D/h = 19.2: docs/evidence/cut_cell_boundary.md, "The memory of a cut-cell run"), plus a free
// body's three unit solves.
TEST(SceneFile, FootprintCountsAMovingCutBodysResponses) {
  Params p;  // 32 x 32 cells, h = 1/32
  ParticleParams q;
  q.center = Vec2(0.5, 0.5);
  q.diameter = 0.25;  // D/h = 8
  q.motion = Motion::kFixed;
  p.particles.push_back(q);
  p.particle_mesh.kind = ParticleMeshKind::kCutCell;
  const SceneFootprint fixed = EstimateFootprint(p);
  EXPECT_EQ(fixed.multiplier_nodes, 0.0);
  EXPECT_EQ(fixed.cut_cell_rows, 0.0);
  EXPECT_DOUBLE_EQ(fixed.bytes, kCutCellBytesPerNode * 33.0 * 33.0);
  p.particles[0].motion = Motion::kPrescribed;
  const SceneFootprint towed = EstimateFootprint(p);
  EXPECT_DOUBLE_EQ(towed.cut_cell_rows, 11.25 * 8.0 + 10.0);
  EXPECT_DOUBLE_EQ(towed.bytes, (kCutCellBytesPerNode + 8.0 * 100.0) * 33.0 * 33.0);
  p.particles[0].motion = Motion::kFree;
  const SceneFootprint free = EstimateFootprint(p);
  EXPECT_DOUBLE_EQ(free.bytes - towed.bytes, 3.0 * 2.25 * 8.0 * 33.0 * 33.0);
}

TEST(SceneFile, GammaMessageSaysOnlyGammaZeroIsSupported) {
  try {
    ParseScene("[splitting]\nalpha = 0.3\nbeta = 0.3\n");
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_THAT(e.allowed(), HasSubstr("gamma = 1 - alpha - beta must be 0"));
  }
}

// ----- good scenes
// ----------------------------------------------------------------------------------

TEST(SceneFile, PaperSceneGivesItsValues) {
  const Params p = ParseScene(kPaperScene);
  EXPECT_EQ(p.title, "Two disks in an Oldroyd-B liquid (paper 5.2)");
  EXPECT_EQ(p.domain.size, Vec2(2.0, 8.0));
  EXPECT_EQ(p.domain.h, 0.010416666666666666);
  EXPECT_EQ(p.domain.side(Side::kLeft).type, SideType::kWall);
  EXPECT_EQ(p.domain.side(Side::kTop).type, SideType::kOutflow);
  const BoundarySide& bottom = p.domain.side(Side::kBottom);
  EXPECT_EQ(bottom.type, SideType::kVelocity);
  EXPECT_EQ(bottom.profile, Profile::kPoiseuille);
  EXPECT_EQ(bottom.max, Vec2(0.0, 0.5));
  EXPECT_EQ(p.fluid.viscosity, 0.12);
  EXPECT_EQ(p.fluid.relaxation_time, 1.4);
  EXPECT_EQ(p.fluid.solvent_ratio, 0.5);
  EXPECT_FALSE(p.fluid.IsNewtonian());
  EXPECT_EQ(p.gravity, Vec2(0.0, -981.0));
  EXPECT_EQ(p.time.dt, 0.0004);
  EXPECT_EQ(p.time.end, 25.0);
  EXPECT_EQ(p.splitting.advection, AdvectionScheme::kLeastSquares);
  EXPECT_EQ(p.splitting.constraint, ConstraintCoupling::kIncremental);  // the default
  EXPECT_EQ(p.splitting.alpha, 1.0);
  EXPECT_EQ(p.splitting.beta, 0.0);
  ASSERT_EQ(p.particles.size(), 2u);
  EXPECT_EQ(p.particles[0].center, Vec2(1.0, 7.7));
  EXPECT_EQ(p.particles[1].center, Vec2(1.0, 7.3));
  EXPECT_EQ(p.particles[1].density, 1.01);
  EXPECT_EQ(p.particles[1].motion, Motion::kFree);
  EXPECT_EQ(p.particle_mesh.h, 0.014285714285714285);
  EXPECT_EQ(p.collisions.wall_stiffness, 1e-5);
  EXPECT_EQ(p.collisions.particle_stiffness, 2e-5);
  EXPECT_EQ(p.output.particles_every, 0.01);
}

TEST(SceneFile, EmptySceneIsAllDefaults) {
  const Params p = ParseScene("");
  Params d;
  // The defaults that follow other keys: h_p follows domain.h, the steady correction the liquid
  // (a Newtonian one by default). And the default preset's mesh and advection scheme, where the
  // struct keeps the paper's, which the engine's tests that build Params studied
  // (scene/numerics_preset.h).
  d.particle_mesh.h = kPaperParticleMeshRatio * d.domain.h;
  d.splitting.steady_correction = SteadyCorrection::kTendency;
  d.domain.diagonals = MeshDiagonals::kBoth;
  d.splitting.advection = AdvectionScheme::kWave;
  EXPECT_EQ(WriteScene(p), WriteScene(d));
  EXPECT_EQ(p.domain.h, d.domain.h);
  EXPECT_EQ(p.fluid.viscosity, d.fluid.viscosity);
  EXPECT_EQ(p.solvers.stokes_max_iterations, d.solvers.stokes_max_iterations);
  EXPECT_EQ(p.conformation.blend_kappa, d.conformation.blend_kappa);
  EXPECT_TRUE(p.particles.empty());
  for (int s = 0; s < 4; ++s) EXPECT_EQ(p.domain.sides[s].type, SideType::kWall);
}

TEST(SceneFile, ParticleMeshFollowsTheFluidMeshUnlessSet) {
  // Without particle_mesh.h the ring mesh keeps the paper's h_p / h = 96 / 70 on any fluid mesh, so
  // a coarse or fine scene stays inside the multiplier CG's well-conditioned range h_p / h >= 1.1
  // (bench/multiplier_conditioning.sh); the paper's own h = 1/96 gives its h_p = 1/70.
  const char* disk = "[[particles]]\ncenter = [0.5, 0.5]\nmotion = \"fixed\"\n";
  EXPECT_DOUBLE_EQ(ParseScene(disk).particle_mesh.h.value(), 96.0 / 70.0 / 32.0);
  EXPECT_DOUBLE_EQ(ParseScene(disk, {{"domain.h", "0.015625"}}).particle_mesh.h.value(),
                   96.0 / 70.0 / 64.0);
  EXPECT_EQ(ParseScene(disk, {{"domain.h", "0.010416666666666666"}}).particle_mesh.h, 1.0 / 70.0);
  // A scene that sets it keeps it, whatever domain.h.
  EXPECT_EQ(
      ParseScene(disk, {{"domain.h", "0.015625"}, {"particle_mesh.h", "0.01"}}).particle_mesh.h,
      0.01);
  EXPECT_EQ(ParseScene(std::string(disk) + "[particle_mesh]\nh = 0.03\n").particle_mesh.h, 0.03);
  // The scene as run names the value, so a resume or a rerun of it keeps the same mesh.
  const Params p = ParseScene(disk, {{"domain.h", "0.015625"}});
  EXPECT_EQ(ParseScene(WriteScene(p), {{"domain.h", "0.03125"}}).particle_mesh.h,
            p.particle_mesh.h);
}

TEST(SceneFile, IntegersAreAcceptedAsReals) {
  const Params p = ParseScene("[fluid]\nviscosity = 2\n[domain]\nsize = [4, 8]\nh = 1\n");
  EXPECT_EQ(p.fluid.viscosity, 2.0);
  EXPECT_EQ(p.domain.size, Vec2(4.0, 8.0));
}

TEST(SceneFile, PeriodicDiskMayCrossPeriodicSides) {
  const Params p = ParseScene(
      "[domain.boundary]\nleft = { type = \"periodic\" }\nright = { type = \"periodic\" }\n"
      "[[particles]]\ncenter = [0.02, 0.5]\ndensity = 1.5\n");
  EXPECT_TRUE(p.domain.PeriodicX());
  EXPECT_FALSE(p.domain.PeriodicY());
}

TEST(SceneFile, FreeParticleMayBeNeutrallyBuoyant) {
  const Params p = ParseScene("[[particles]]\ncenter = [0.5, 0.5]\ndensity = 1.0\n");
  EXPECT_EQ(p.particles[0].motion, Motion::kFree);
  EXPECT_EQ(p.particles[0].density, 1.0);
}

TEST(SceneFile, FixedParticleMayBeNeutrallyBuoyant) {
  const Params p =
      ParseScene("[[particles]]\ncenter = [0.5, 0.5]\ndensity = 1.0\nmotion = \"fixed\"\n");
  EXPECT_EQ(p.particles[0].motion, Motion::kFixed);
}

// Issue 38: a key of 20,000 dotted parts crashed the parser (dlmfd-solve exit 139, dlmfdd with
// every job); 200,000 parts crashed toml++ itself. Refused before parsing, naming the line.
TEST(SceneFile, KeysOfManyPartsAndDeepNestingAreRefusedNotACrash) {
  for (int parts : {17, 20000, 200000}) {
    std::string key = "z";
    for (int i = 1; i < parts; ++i) key += ".z";
    try {
      ParseScene("title = \"deep\"\n" + key + " = 1\n");
      FAIL() << parts << " parts accepted";
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.key(), "scene");
      EXPECT_EQ(e.value(), "line 2");
      EXPECT_THAT(e.allowed(), HasSubstr("at most 16 dotted parts"));
    }
    try {
      ParseScene("", {{key, "1"}});
      FAIL() << parts << " parts of an override accepted";
    } catch (const InvalidParameter& e) {
      EXPECT_THAT(e.what(), HasSubstr("(" + std::to_string(parts) + " parts)"));
    }
  }
  // Strings and comments hold any number of dots; numbers and dates up to two.
  EXPECT_NO_THROW(ParseScene("title = \"" + std::string(100, '.') +
                             "\" # a.b.c.d.e.f.g.h.i.j.k.l.m."
                             "n.o.p.q.r\n[time]\nend = 1.5e+0\ndt = 0.25\n"));
  const std::string deep = "[fluid]\nviscosity = " + std::string(17, '[') + std::string(17, ']');
  EXPECT_THROW(ParseScene(deep + "\n"), InvalidParameter);
  // An override value that deep is a string, which the key's reader then names.
  EXPECT_THROW(ParseScene("", {{"fluid.viscosity", std::string(300, '[') + std::string(300, ']')}}),
               InvalidParameter);
}

// ----- overrides
// ---------------------------------------------------------------------------------------

TEST(SceneFile, ParseOverrideSplitsAtTheFirstEquals) {
  const SceneOverride o = ParseOverride("title=a=b");
  EXPECT_EQ(o.key, "title");
  EXPECT_EQ(o.value, "a=b");
  EXPECT_THROW(ParseOverride("fluid.viscosity"), InvalidParameter);
  EXPECT_THROW(ParseOverride("=1"), InvalidParameter);
}

TEST(SceneFile, OverridesApplyBeforeValidation) {
  const std::vector<SceneOverride> overrides = {
      ParseOverride("fluid.relaxation_time=2"),
      ParseOverride("particles.1.density=1.02"),
      ParseOverride("domain.boundary.top.type=outflow"),
      ParseOverride("domain.boundary.bottom={ type = \"velocity\", value = [0.0, 1.0] }"),
      ParseOverride("splitting.advection=wave"),
      ParseOverride("gravity=[1.0, -2.0]"),
      ParseOverride("gravity.0=3"),
      ParseOverride("collisions.substeps=3"),
      ParseOverride("title=\"quoted title\""),
      ParseOverride("solvers.stokes_tolerance=1e-8"),
  };
  const Params p = ParseScene(
      "[domain.boundary]\ntop = { type = \"velocity\", profile = \"poiseuille\", max = [0.0, 1.0] "
      "}\n"
      "[fluid]\nrelaxation_time = 1.0\nsolvent_ratio = 0.5\n"
      "[[particles]]\ncenter = [0.3, 0.5]\ndensity = 1.5\n"
      "[[particles]]\ncenter = [0.7, 0.5]\ndensity = 1.5\n",
      overrides);
  EXPECT_EQ(p.fluid.relaxation_time, 2.0);
  EXPECT_EQ(p.particles[1].density, 1.02);
  EXPECT_EQ(p.particles[0].density, 1.5);
  EXPECT_EQ(p.domain.side(Side::kTop).type, SideType::kOutflow);
  EXPECT_EQ(p.domain.side(Side::kBottom).value, Vec2(0.0, 1.0));
  EXPECT_EQ(p.splitting.advection, AdvectionScheme::kWave);
  EXPECT_EQ(p.gravity, Vec2(3.0, -2.0));
  EXPECT_EQ(p.collisions.substeps, 3);
  EXPECT_EQ(p.title, "quoted title");
  EXPECT_EQ(p.solvers.stokes_tolerance, 1e-8);
}

TEST(SceneFile, OverrideCreatesMissingTables) {
  const Params p = ParseScene("", {ParseOverride("fluid.viscosity=0.5")});
  EXPECT_EQ(p.fluid.viscosity, 0.5);
}

TEST(SceneFile, OverrideValuesAreValidatedLikeSceneValues) {
  try {
    ParseScene("", {ParseOverride("fluid.viscosity=-1")});
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "fluid.viscosity");
    EXPECT_EQ(e.value(), "-1.0");
  }
  try {
    ParseScene("", {ParseOverride("fluid.viscosityy=1")});
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "fluid.viscosityy");
  }
}

TEST(SceneFile, OverrideOfAMissingParticleNamesTheIndex) {
  try {
    ParseScene("[[particles]]\ncenter = [0.5, 0.5]\ndensity = 1.5\n",
               {ParseOverride("particles.3.density=2")});
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "particles.3");
    EXPECT_THAT(e.allowed(), HasSubstr("below 1"));
  }
}

// issue 14: `*` in place of an index sets every entry of the array; a scene without the array
// (or with an empty one) is an error naming the key, not a silent no-op.
TEST(SceneFile, WildcardOverrideSetsEveryParticle) {
  const std::string two =
      "[[particles]]\ncenter = [0.3, 0.5]\ndensity = 1.5\n"
      "[[particles]]\ncenter = [0.7, 0.5]\ndensity = 1.5\n";
  const Params p = ParseScene(two, {ParseOverride("particles.*.density=1.02")});
  ASSERT_EQ(p.particles.size(), 2u);
  EXPECT_EQ(p.particles[0].density, 1.02);
  EXPECT_EQ(p.particles[1].density, 1.02);
  const Params q = ParseScene(two, {ParseOverride("particles.*.center.1=0.25")});
  EXPECT_EQ(q.particles[0].center, Vec2(0.3, 0.25));
  EXPECT_EQ(q.particles[1].center, Vec2(0.7, 0.25));
  try {
    ParseScene("", {ParseOverride("particles.*.density=1.02")});
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "particles.*.density");
    EXPECT_THAT(e.allowed(), HasSubstr("non-empty array"));
  }
  try {
    ParseScene(two, {ParseOverride("particles.*.densty=1.02")});
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "particles.0.densty");  // the first concrete key names the typo
  }
}

TEST(SceneFile, OverrideThroughAValueIsAnError) {
  try {
    ParseScene("[fluid]\nviscosity = 1.0\n", {ParseOverride("fluid.viscosity.x=2")});
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.key(), "fluid.viscosity");
  }
}

// ----- round trip
// -------------------------------------------------------------------------------------

void ExpectSameParams(const Params& a, const Params& b) {
  EXPECT_EQ(a.title, b.title);
  EXPECT_EQ(a.domain.size, b.domain.size);
  EXPECT_EQ(a.domain.h, b.domain.h);
  for (int s = 0; s < 4; ++s) {
    EXPECT_EQ(a.domain.sides[s].type, b.domain.sides[s].type);
    EXPECT_EQ(a.domain.sides[s].profile, b.domain.sides[s].profile);
    EXPECT_EQ(a.domain.sides[s].value, b.domain.sides[s].value);
    EXPECT_EQ(a.domain.sides[s].max, b.domain.sides[s].max);
    EXPECT_EQ(a.domain.sides[s].ramp_time, b.domain.sides[s].ramp_time);
  }
  EXPECT_EQ(a.fluid.density, b.fluid.density);
  EXPECT_EQ(a.fluid.viscosity, b.fluid.viscosity);
  EXPECT_EQ(a.fluid.relaxation_time, b.fluid.relaxation_time);
  EXPECT_EQ(a.fluid.solvent_ratio, b.fluid.solvent_ratio);
  EXPECT_EQ(a.fluid.body_force, b.fluid.body_force);
  EXPECT_EQ(a.fluid.stress_splitting, b.fluid.stress_splitting);
  EXPECT_EQ(a.gravity, b.gravity);
  EXPECT_EQ(a.time.dt, b.time.dt);
  EXPECT_EQ(a.time.end, b.time.end);
  EXPECT_EQ(a.splitting.alpha, b.splitting.alpha);
  EXPECT_EQ(a.splitting.beta, b.splitting.beta);
  EXPECT_EQ(a.splitting.advection, b.splitting.advection);
  EXPECT_EQ(a.splitting.steady_correction, b.splitting.steady_correction);
  EXPECT_EQ(a.domain.diagonals, b.domain.diagonals);
  EXPECT_EQ(a.domain.flow_rate, b.domain.flow_rate);
  EXPECT_EQ(a.solvers.stokes_tolerance, b.solvers.stokes_tolerance);
  EXPECT_EQ(a.solvers.stokes_max_iterations, b.solvers.stokes_max_iterations);
  EXPECT_EQ(a.solvers.advection_tolerance, b.solvers.advection_tolerance);
  EXPECT_EQ(a.solvers.advection_max_iterations, b.solvers.advection_max_iterations);
  EXPECT_EQ(a.solvers.wave_max_courant, b.solvers.wave_max_courant);
  EXPECT_EQ(a.solvers.multiplier_tolerance, b.solvers.multiplier_tolerance);
  EXPECT_EQ(a.solvers.multiplier_max_iterations, b.solvers.multiplier_max_iterations);
  ASSERT_EQ(a.particles.size(), b.particles.size());
  for (std::size_t i = 0; i < a.particles.size(); ++i) {
    EXPECT_EQ(a.particles[i].center, b.particles[i].center);
    EXPECT_EQ(a.particles[i].diameter, b.particles[i].diameter);
    EXPECT_EQ(a.particles[i].density, b.particles[i].density);
    EXPECT_EQ(a.particles[i].velocity, b.particles[i].velocity);
    EXPECT_EQ(a.particles[i].angular_velocity, b.particles[i].angular_velocity);
    EXPECT_EQ(a.particles[i].motion, b.particles[i].motion);
  }
  EXPECT_EQ(a.particle_mesh.kind, b.particle_mesh.kind);
  EXPECT_EQ(a.particle_mesh.h, b.particle_mesh.h);
  EXPECT_EQ(a.particle_mesh.spacing, b.particle_mesh.spacing);
  EXPECT_EQ(a.particle_mesh.interpolation, b.particle_mesh.interpolation);
  EXPECT_EQ(a.collisions.range, b.collisions.range);
  EXPECT_EQ(a.collisions.wall_stiffness, b.collisions.wall_stiffness);
  EXPECT_EQ(a.collisions.particle_stiffness, b.collisions.particle_stiffness);
  EXPECT_EQ(a.collisions.substeps, b.collisions.substeps);
  EXPECT_EQ(a.conformation.form, b.conformation.form);
  EXPECT_EQ(a.conformation.max_courant, b.conformation.max_courant);
  EXPECT_EQ(a.conformation.blend_kappa, b.conformation.blend_kappa);
  EXPECT_EQ(a.output.fields_every, b.output.fields_every);
  EXPECT_EQ(a.output.particles_every, b.output.particles_every);
  EXPECT_EQ(a.output.checkpoint_every, b.output.checkpoint_every);
}

// The defaults of alpha and beta follow splitting.constraint (docs/scenes.md): the lagged
// multiplier (the default) and the viscous coupling keep all the viscosity in (33), the paper's
// scheme shares it; a scene without particles may share it under any constraint.
TEST(SceneFile, SplittingWeightsFollowTheConstraint) {
  const char* disk = "[[particles]]\ncenter = [0.5, 0.5]\nmotion = \"fixed\"\n";
  auto weights = [&](const std::string& splitting) {
    const Params p = ParseScene("[splitting]\n" + splitting + disk);
    return std::make_tuple(p.splitting.constraint.value(), p.splitting.alpha, p.splitting.beta);
  };
  EXPECT_EQ(weights(""), std::make_tuple(ConstraintCoupling::kIncremental, 1.0, 0.0));
  EXPECT_EQ(weights("constraint = \"paper\"\n"),
            std::make_tuple(ConstraintCoupling::kPaper, 0.5, 0.5));
  EXPECT_EQ(weights("constraint = \"viscous\"\n"),
            std::make_tuple(ConstraintCoupling::kViscous, 1.0, 0.0));
  EXPECT_EQ(weights("constraint = \"paper\"\nalpha = 1.0\nbeta = 0.0\n"),
            std::make_tuple(ConstraintCoupling::kPaper, 1.0, 0.0));
  EXPECT_FALSE(Params{}.splitting.constraint);  // "auto", as an empty scene's
  const Params fluid_only = ParseScene("[splitting]\nalpha = 0.5\nbeta = 0.5\n");
  EXPECT_EQ(fluid_only.splitting.beta, 0.5);
}

// The steady correction's default follows the liquid (docs/scenes.md): the splitting's Taylor term
// is removed in a Newtonian liquid, with either advection scheme, and kept with a polymer (the
// explicit polymer stress needs its damping; docs/evidence/splitting.md). Params built in code
// leave it absent, and ResolveDefaults (the Simulation's) applies the same rule.
TEST(SceneFile, SteadyCorrectionFollowsTheLiquid) {
  auto correction = [](const std::string& scene) {
    return ParseScene(scene).splitting.steady_correction;
  };
  const std::string polymer = "[fluid]\nrelaxation_time = 1.0\nsolvent_ratio = 0.5\n";
  for (const std::string advection : {"least_squares", "wave"}) {
    const std::string scheme = "[splitting]\nadvection = \"" + advection + "\"\n";
    EXPECT_EQ(correction(scheme), SteadyCorrection::kTendency) << advection;
    EXPECT_EQ(correction(scheme + polymer), SteadyCorrection::kNone) << advection;
    EXPECT_EQ(correction(scheme + "[fluid]\nrelaxation_time = 1.0\nsolvent_ratio = 1.0\n"),
              SteadyCorrection::kTendency)
        << advection;
    EXPECT_EQ(correction(scheme + "steady_correction = \"none\"\n"), SteadyCorrection::kNone)
        << advection;
    EXPECT_EQ(correction(scheme + "steady_correction = \"taylor\"\n" + polymer),
              SteadyCorrection::kTaylor)
        << advection;
  }
  EXPECT_EQ(correction(""), SteadyCorrection::kTendency);
  EXPECT_FALSE(Params{}.splitting.steady_correction.has_value());
  for (const double beta : {0.5, 1.0}) {
    Params code;
    code.fluid.relaxation_time = 1.0;
    code.fluid.solvent_ratio = beta;
    ResolveDefaults(code);
    EXPECT_EQ(code.splitting.steady_correction,
              beta < 1.0 ? SteadyCorrection::kNone : SteadyCorrection::kTendency);
  }
  // The tendency correction is named, with or without a polymer, and the scene as run keeps it.
  const std::string tendency = "[splitting]\nsteady_correction = \"tendency\"\n";
  EXPECT_EQ(correction(tendency), SteadyCorrection::kTendency);
  EXPECT_EQ(correction(tendency + polymer), SteadyCorrection::kTendency);
  EXPECT_EQ(correction(WriteScene(ParseScene(tendency))), SteadyCorrection::kTendency);
}

TEST(SceneFile, FlowRateIsReadAndRoundTrips) {
  const Params p = ParseScene(
      "[domain]\nflow_rate = -0.25\n[domain.boundary]\nleft = { type = \"periodic\" }\n"
      "right = { type = \"periodic\" }\ntop = { type = \"velocity\", value = [1.0, 0.0] }\n");
  ASSERT_TRUE(p.domain.flow_rate.has_value());
  EXPECT_EQ(*p.domain.flow_rate, -0.25);
  const Params q = ParseScene(WriteScene(p), {}, "written");
  ASSERT_TRUE(q.domain.flow_rate.has_value());
  EXPECT_EQ(*q.domain.flow_rate, -0.25);
  EXPECT_FALSE(ParseScene("").domain.flow_rate.has_value());
  // A box periodic in both directions takes 0 (zero mean velocity along x and y).
  const Params box = ParseScene(
      "[domain]\nflow_rate = 0.0\n[domain.boundary]\nleft = { type = \"periodic\" }\n"
      "right = { type = \"periodic\" }\nbottom = { type = \"periodic\" }\n"
      "top = { type = \"periodic\" }\n");
  ASSERT_TRUE(box.domain.flow_rate.has_value());
  EXPECT_EQ(*box.domain.flow_rate, 0.0);
}

TEST(SceneFile, WriteSceneRoundTripsThePaperScene) {
  const Params p = ParseScene(kPaperScene);
  const std::string text = WriteScene(p);
  const Params q = ParseScene(text, {}, "written");
  ExpectSameParams(p, q);
  EXPECT_EQ(WriteScene(q), text);
}

TEST(SceneFile, WriteSceneRoundTripsAwkwardValues) {
  Params p;
  p.title = "quote \" backslash \\ tab \t end";
  p.domain.size = Vec2(3.0 / 7.0 * 2.0, 1.0);
  p.domain.h = 3.0 / 7.0 / 2.0;  // size.x / h = 4 (to rounding: within the 1e-9 check)
  p.domain.h = p.domain.size.x() / 4.0;
  p.domain.size.y() = p.domain.h * 6.0;
  p.domain.sides[static_cast<int>(Side::kTop)] = {SideType::kVelocity, Profile::kUniform,
                                                  Vec2(0.1 + 0.2, -1e-300), Vec2::Zero(), 0.0};
  p.domain.sides[static_cast<int>(Side::kLeft)] = {SideType::kPeriodic, Profile::kUniform,
                                                   Vec2::Zero(), Vec2::Zero(), 0.0};
  p.domain.sides[static_cast<int>(Side::kRight)] = p.domain.sides[static_cast<int>(Side::kLeft)];
  p.domain.sides[static_cast<int>(Side::kBottom)] = {SideType::kVelocity, Profile::kQuartic,
                                                     Vec2::Zero(), Vec2(1.0 / 7.0, 0.0), 1.0 / 3.0};
  p.fluid.viscosity = 1.0 / 3.0;
  p.fluid.relaxation_time = 1e22;
  p.fluid.body_force = Vec2(-5e-324, 123456789012345678.0);
  p.time.dt = 0.1 + 0.2;
  p.time.end = 2.0 * (0.1 + 0.2);  // two steps (an end of 0 was refused by issue 38)
  p.splitting.alpha = 1.0;
  p.splitting.beta = 0.0;
  p.splitting.advection = AdvectionScheme::kWave;
  p.domain.diagonals = MeshDiagonals::kBoth;
  p.collisions.substeps = 7;
  p.particle_mesh.kind = ParticleMeshKind::kCollocation;
  p.particle_mesh.spacing = 1.0 / 0.7;
  p.particle_mesh.interpolation = BoundaryInterpolation::kLinear;
  ParticleParams q;
  q.center = Vec2(p.domain.size.x() / 2.0, p.domain.size.y() / 2.0);
  q.diameter = 0.1 / 3.0;
  q.density = 2.0 / 3.0;
  q.velocity = Vec2(1.0 / 7.0, -2.0 / 9.0);
  q.angular_velocity = -1.0 / 11.0;
  q.motion = Motion::kPrescribed;
  p.particles.push_back(q);
  ResolveDefaults(p);  // the members Params{} leaves absent, as the Simulation resolves them
  const std::string text = WriteScene(p);
  const Params r = ParseScene(text, {}, "written");
  ExpectSameParams(p, r);
  EXPECT_EQ(WriteScene(r), text);
}

TEST(SceneFile, LoadSceneFileReadsAndNamesAMissingFile) {
  const std::string path = dlmfd::testing::ScratchPath("scene_file_test", ".toml");
  {
    std::ofstream out(path);
    out << "[fluid]\nviscosity = 0.25\n";
  }
  EXPECT_EQ(LoadSceneFile(path).fluid.viscosity, 0.25);
  EXPECT_EQ(LoadSceneFile(path, {ParseOverride("fluid.viscosity=0.5")}).fluid.viscosity, 0.5);
  try {
    LoadSceneFile(path + ".absent");
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(e.value(), path + ".absent");
  }
}

}  // namespace
}  // namespace dlmfd

// A --set whose text is not UTF-8 is refused (the fuzzer's finding: such a title was accepted and
// the scene written back from it could not be read again); UTF-8 text beyond ASCII is accepted.
TEST(SceneOverrides, TextThatIsNotUtf8IsRefusedNamingTheFlag) {
  const std::string bad = std::string("title=\"Paper ") + '\xa8' + '\xf5' + "\"";
  try {
    dlmfd::ParseOverride(bad);
    FAIL() << "accepted";
  } catch (const dlmfd::InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("--set"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("UTF-8"), std::string::npos) << e.what();
  }
  EXPECT_THROW(dlmfd::ParseOverride(std::string("title=\"a") + '\xc3' + "\""),
               dlmfd::InvalidParameter);                                              // cut short
  EXPECT_THROW(dlmfd::ParseOverride("title=\"\xc0\xaf\""), dlmfd::InvalidParameter);  // overlong
  EXPECT_THROW(dlmfd::ParseOverride("title=\"\xed\xa0\x80\""),
               dlmfd::InvalidParameter);  // surrogate
  const dlmfd::SceneOverride ok =
      dlmfd::ParseOverride("title=\"Z\xc3\xbcrich \xe2\x86\x92 \xf0\x9f\x8c\x8a\"");
  EXPECT_EQ(ok.key, "title");
}
