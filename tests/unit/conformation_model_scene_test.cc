// fluid.model, its parameters and fluid.conformation in scenes (relaxation_model.h: the module's
// scene rule, applied by ValidateScene for the solver and the daemon alike), and the models wired
// into step (35), the inflow state and the polymer force.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "../support/shear_start_up.h"
#include "dlmfd/conformation/conformation_step.h"
#include "dlmfd/conformation/giesekus_relaxation.h"
#include "dlmfd/conformation/inflow_state.h"
#include "dlmfd/conformation/model_pointwise_update.h"
#include "dlmfd/conformation/oldroyd_b_polymer.h"
#include "dlmfd/conformation/polymer_force.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

const std::string kPolymer = "[fluid]\nrelaxation_time = 1.0\nsolvent_ratio = 0.5\n";

struct BadScene {
  const char* name;
  std::string fluid_lines;  // appended to kPolymer (or replacing it when newtonian)
  bool newtonian;
  const char* key;
  const char* value;
};

TEST(ConformationModelScene, EachErrorNamesTheKey) {
  const std::vector<BadScene> cases = {
      {"UnknownModel", "model = \"maxwell\"\n", false, "fluid.model", "\"maxwell\""},
      {"UnknownRepresentation", "conformation = \"cholesky\"\n", false, "fluid.conformation",
       "\"cholesky\""},
      {"GiesekusWithoutMobility", "model = \"giesekus\"\n", false, "fluid.mobility", "(absent)"},
      {"MobilityAboveHalf", "model = \"giesekus\"\nmobility = 0.6\n", false, "fluid.mobility",
       "0.6"},
      {"MobilityNegative", "model = \"giesekus\"\nmobility = -0.1\n", false, "fluid.mobility",
       "-0.1"},
      {"MobilityForOldroydB", "mobility = 0.1\n", false, "fluid.mobility", "0.1"},
      {"ExtensibilityTwo", "model = \"fene_p\"\nextensibility = 2.0\n", false,
       "fluid.extensibility", "2.0"},
      {"ExtensibilityForGiesekus", "model = \"giesekus\"\nmobility = 0.1\nextensibility = 100\n",
       false, "fluid.extensibility", "1e+02"},
      {"EpsilonNegative", "model = \"ptt_linear\"\nptt_epsilon = -0.1\n", false,
       "fluid.ptt_epsilon", "-0.1"},
      {"EpsilonForFeneP", "model = \"fene_p\"\nextensibility = 100\nptt_epsilon = 0.1\n", false,
       "fluid.ptt_epsilon", "0.1"},
      {"ModelForNewtonian", "[fluid]\nmodel = \"giesekus\"\nmobility = 0.1\n", true, "fluid.model",
       "\"giesekus\""},
  };
  for (const BadScene& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string text = c.newtonian ? c.fluid_lines : kPolymer + c.fluid_lines;
    try {
      ParseScene(text);
      ADD_FAILURE() << "accepted";
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.key(), c.key) << e.what();
      EXPECT_EQ(e.value(), c.value) << e.what();
    }
  }
}

TEST(ConformationModelScene, ModelsParseAndWriteBack) {
  const std::vector<std::string> lines = {
      "",
      "model = \"giesekus\"\nmobility = 0.1\n",
      "model = \"fene_p\"\nextensibility = 100\n",
      "model = \"ptt_linear\"\nptt_epsilon = 0.25\n",
      "model = \"ptt_exponential\"\nptt_epsilon = 0.02\n",
  };
  for (const std::string& l : lines) {
    SCOPED_TRACE(l);
    const Params p = ParseScene(kPolymer + l);
    const Params q = ParseScene(WriteScene(p));
    EXPECT_EQ(q.fluid.model, p.fluid.model);
    EXPECT_EQ(q.fluid.conformation, p.fluid.conformation);
    EXPECT_EQ(q.fluid.mobility, p.fluid.mobility);
    EXPECT_EQ(q.fluid.extensibility, p.fluid.extensibility);
    EXPECT_EQ(q.fluid.ptt_epsilon, p.fluid.ptt_epsilon);
    EXPECT_EQ(WriteScene(q), WriteScene(p));
  }
  EXPECT_EQ(ParseScene(kPolymer).fluid.model, ConstitutiveModel::kOldroydB);
  EXPECT_EQ(ParseScene(kPolymer + "model = \"fene_p\"\nextensibility = 100\n").fluid.extensibility,
            100.0);
}

// A periodic-x channel of walls, n x n cells of 1/n, with fluid.model = giesekus.
Params GiesekusChannel(int n, double alpha) {
  Params p;
  p.domain.size = Vec2(1.0, 1.0);
  p.domain.h = 1.0 / n;
  p.domain.sides[int(Side::kLeft)].type = SideType::kPeriodic;
  p.domain.sides[int(Side::kRight)].type = SideType::kPeriodic;
  p.fluid.relaxation_time = 1.0;
  p.fluid.solvent_ratio = 0.5;
  p.fluid.viscosity = 1.0;
  p.fluid.model = ConstitutiveModel::kGiesekus;
  p.fluid.mobility = alpha;
  return p;
}

TEST(ConformationModelScene, StepReachesTheModelsSteadyShearAtEveryNode) {
  // u = Wi (y - 1/2): the P1 gradient of a linear field is exact, advection of a field uniform in x
  // along x does nothing, so every node follows the homogeneous start-up; after t = 20 lambda the
  // transient is below e^{-20} ~ 2e-9 of the steady state.
  const int n = 8;
  const double wi = 3.0, dt = 0.05;
  const testing::ShearRun run = testing::ShearStartUp(GiesekusChannel(n, 0.3), wi, dt, 400);
  const GiesekusRelaxation model(0.3);
  const SymTensor want = SteadyModelConformation(model, Mat2{0.0, wi, 0.0, 0.0}, 1.0);
  for (std::size_t k = 0; k < run.a11.size(); ++k) {
    EXPECT_NEAR(run.a11[k], want.a11, 1e-7 * want.a11);
    EXPECT_NEAR(run.a12[k], want.a12, 1e-7 * want.a12);
    EXPECT_NEAR(run.a22[k], want.a22, 1e-7);
  }
  EXPECT_NEAR(run.report.Get("max_trA"), want.a11 + want.a22, 1e-6 * want.a11);
}

TEST(ConformationModelScene, InflowStateIsTheModelsSteadyShear) {
  // A bottom poiseuille side v = U 4 x (1 - x): L = [[0, 0], [g, 0]] with g = dv/dx, a simple
  // shear along y. Its steady state is the steady shear of rate g with the axes exchanged.
  Params p = GiesekusChannel(16, 0.1);
  p.domain.sides[int(Side::kLeft)].type = SideType::kWall;
  p.domain.sides[int(Side::kRight)].type = SideType::kWall;
  p.domain.sides[int(Side::kBottom)].type = SideType::kVelocity;
  p.domain.sides[int(Side::kBottom)].profile = Profile::kPoiseuille;
  p.domain.sides[int(Side::kBottom)].max = Vec2(0.0, 2.0);
  p.domain.sides[int(Side::kTop)].type = SideType::kOutflow;
  const Grid grid = p.domain.VelocityGrid();
  const GiesekusRelaxation model(0.1);
  for (int k : {0, 3, 8, 13, 16}) {
    const double x = k * grid.h, g = 2.0 * 4.0 * (1.0 - 2.0 * x);
    const SymTensor got = InflowConformation(grid, p.domain, Side::kBottom, k, 1.0, model);
    const SymTensor shear = SteadyModelConformation(model, Mat2{0.0, std::abs(g), 0.0, 0.0}, 1.0);
    EXPECT_NEAR(got.a22, shear.a11, 1e-12 * shear.a11) << k;
    EXPECT_NEAR(got.a11, shear.a22, 1e-12) << k;
    EXPECT_NEAR(std::abs(got.a12), shear.a12, 1e-12 * (1.0 + shear.a12)) << k;
    EXPECT_GE(got.a12 * g, 0.0) << k;
  }
  EXPECT_NO_THROW(ValidateInflowStates(p, grid));
}

TEST(ConformationModelScene, FenePForceReadsTheStressWithThePeterlinFunction) {
  // The FENE-P polymer force equals the force that an Oldroyd-B polymer gives for S = T(A) + I.
  const int n = 8;
  Params p = GiesekusChannel(n, 0.0);
  p.fluid.model = ConstitutiveModel::kFeneP;
  p.fluid.mobility.reset();
  p.fluid.extensibility = 20.0;
  // The stress alone: devss would also subtract its share of the strain rate (FlowState::d11...).
  p.fluid.stress_splitting = StressSplitting::kExplicit;
  const Grid grid = p.domain.VelocityGrid();
  OldroydBPolymer polymer(p, grid);
  FlowState state;
  const std::size_t count = grid.NodeCount();
  state.u.assign(count, 0.0);
  state.v.assign(count, 0.0);
  state.a11.resize(count);
  state.a12.resize(count);
  state.a22.resize(count);
  std::vector<double> s11(count), s12(count), s22(count);
  const double l2 = 20.0, ra = 1.0 / (1.0 - 2.0 / l2);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const std::size_t k = grid.Index(i, j);
      const double x = grid.X(i), y = grid.Y(j);
      state.a11[k] = 1.0 + 6.0 * y * y;
      state.a12[k] = std::sin(2.0 * x) * y;
      state.a22[k] = 1.0 + x;
      const double f = 1.0 / (1.0 - (state.a11[k] + state.a22[k]) / l2);
      s11[k] = f * state.a11[k] - ra + 1.0;
      s12[k] = f * state.a12[k];
      s22[k] = f * state.a22[k] - ra + 1.0;
    }
  }
  const NodeForce force = polymer.MomentumForce(state);
  std::vector<double> fx(count, 0.0), fy(count, 0.0);
  AddPolymerForce(grid, p.domain, polymer.modulus(), s11.data(), s12.data(), s22.data(), fx.data(),
                  fy.data());
  double largest = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    EXPECT_NEAR(force.x[k], fx[k], 1e-13);
    EXPECT_NEAR(force.y[k], fy[k], 1e-13);
    largest = std::max(largest, std::abs(fx[k]));
  }
  EXPECT_GT(largest, 1e-3);  // a force worth comparing
}

}  // namespace
}  // namespace dlmfd
