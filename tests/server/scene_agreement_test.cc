// One validation path (design.md 2; issue 12, point 3): one table of scenes, valid and invalid,
// goes both to the real dlmfd-solve and to the daemon's admission (AdmitScene, its errors mapped by
// ToStatus as Submit maps them). Scene by scene they agree: both reject it naming the same key (the
// solver exits with status 2 and the key on stderr; the daemon answers INVALID_ARGUMENT with a
// message that starts with the key), or the daemon admits it and the solver runs it to its end (one
// step). Then the daemon's own limits take the same footprint as the engine's.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "config.h"
#include "dlmfd/scene/scene_file.h"
#include "dlmfd/scene/scene_footprint.h"
#include "scene_admission.h"
#include "service_error.h"
#include "support/daemon_process.h"

namespace dlmfd::server {
namespace {

namespace fs = std::filesystem;

// A 16 x 16 cavity that ends after one step and writes no fields or checkpoints.
constexpr char kCavity[] =
    "title = \"agreement\"\n"
    "[domain]\nsize = [1.0, 1.0]\nh = 0.0625\n"
    "[domain.boundary]\ntop = { type = \"velocity\", value = [1.0, 0.0] }\n"
    "[time]\ndt = 0.01\nend = 0.01\n"
    "[output]\nfields_every = 0.0\nparticles_every = 0.0\ncheckpoint_every = 0.0\n";

std::string Disk(double x, double y, double density, const char* motion = "free") {
  std::ostringstream s;
  s << "[[particles]]\ncenter = [" << x << ", " << y << "]\ndiameter = 0.2\ndensity = " << density
    << "\nmotion = \"" << motion << "\"\n";
  return s.str();
}

const char kOldroydB[] = "fluid.relaxation_time=1.0";
const char kHalfSolvent[] = "fluid.solvent_ratio=0.5";
const char kOutflowTop[] = "domain.boundary.top={ type = \"outflow\" }";

struct SceneCase {
  std::string name;
  std::string particles;               // [[particles]] tables after the cavity
  std::vector<std::string> overrides;  // --set for the solver, overrides for Submit
  std::string key;                     // the key both name; empty: a valid scene
};

// Failures name the case, not its bytes.
void PrintTo(const SceneCase& c, std::ostream* os) { *os << c.name; }

// What cut cells do not hold yet (particles/particle_rules.h, RequireCutCellScene: a moving
// ellipse in a polymer or with a tip thinner than 1.6 cells among them), and the fixed, prescribed
// and free disks (of any density), the polymer around each of them, and the fixed and moving
// ellipses, that they do.
std::vector<SceneCase> CutCellCases() {
  return {
      {"CutCellFixedDisk", Disk(0.5, 0.5, 1.5, "fixed"), {"particle_mesh.kind=cut_cell"}, ""},
      {"CutCellPrescribedDisk",
       Disk(0.5, 0.5, 1.5, "prescribed"),
       {"particle_mesh.kind=cut_cell"},
       ""},
      {"CutCellWithAPolymer",
       Disk(0.5, 0.5, 1.5, "fixed"),
       {"particle_mesh.kind=cut_cell", kOldroydB, kHalfSolvent},
       ""},
      {"CutCellWithAPolymerAroundAPrescribedBody",
       Disk(0.5, 0.5, 1.5, "prescribed"),
       {"particle_mesh.kind=cut_cell", kOldroydB, kHalfSolvent},
       ""},
      {"CutCellFreeDisk", Disk(0.5, 0.5, 1.5), {"particle_mesh.kind=cut_cell"}, ""},
      // Lighter than the liquid: refused with multipliers (LightFreeDisk), taken by cut cells.
      {"CutCellLightFreeDisk", Disk(0.5, 0.5, 0.9), {"particle_mesh.kind=cut_cell"}, ""},
      {"CutCellWithAPolymerAroundAFreeBody",
       Disk(0.5, 0.5, 1.5),
       {"particle_mesh.kind=cut_cell", kOldroydB, kHalfSolvent},
       ""},
      {"CutCellFixedEllipse",
       "[[particles]]\ncenter = [0.5, 0.5]\nshape = \"ellipse\"\nsemi_axes = [0.1, 0.05]\n"
       "density = 1.5\nmotion = \"fixed\"\n",
       {"particle_mesh.kind=cut_cell"},
       ""},
      {"CutCellPrescribedEllipse",
       "[[particles]]\ncenter = [0.5, 0.5]\nshape = \"ellipse\"\nsemi_axes = [0.1, 0.05]\n"
       "density = 1.5\nmotion = \"prescribed\"\n",
       {"particle_mesh.kind=cut_cell", "domain.h=0.015625"},
       ""},
      {"CutCellFreeEllipse",
       "[[particles]]\ncenter = [0.5, 0.5]\nshape = \"ellipse\"\nsemi_axes = [0.1, 0.05]\n"
       "density = 1.5\n",
       {"particle_mesh.kind=cut_cell", "domain.h=0.015625"},
       ""},
      {"CutCellMovingEllipseWithATipThinnerThanItsCells",
       "[[particles]]\ncenter = [0.5, 0.5]\nshape = \"ellipse\"\nsemi_axes = [0.1, 0.05]\n"
       "density = 1.5\n",
       {"particle_mesh.kind=cut_cell", "domain.h=0.03125"},
       "domain.h"},
      {"CutCellWithAPolymerAroundAMovingEllipse",
       "[[particles]]\ncenter = [0.5, 0.5]\nshape = \"ellipse\"\nsemi_axes = [0.1, 0.05]\n"
       "density = 1.5\nmotion = \"prescribed\"\n",
       {"particle_mesh.kind=cut_cell", kOldroydB, kHalfSolvent},
       "particles.0.shape"},
      {"CutCellWithViscosityInTheAdvection",
       Disk(0.5, 0.5, 1.5, "fixed"),
       {"particle_mesh.kind=cut_cell", "splitting.alpha=0.5", "splitting.beta=0.5"},
       "splitting.beta"},
      {"CutCellWithAFlowRate",
       Disk(0.5, 0.5, 1.5, "fixed"),
       {"particle_mesh.kind=cut_cell", "domain.boundary.left={ type = \"periodic\" }",
        "domain.boundary.right={ type = \"periodic\" }", "domain.flow_rate=0.1"},
       "domain.flow_rate"},
  };
}

std::vector<SceneCase> Cases() {
  const std::string normal_inflow =
      "domain.boundary.bottom={ type = \"velocity\", profile = \"poiseuille\", max = [0.0, 1.0] }";
  const std::string tangential_inflow =
      "domain.boundary.bottom={ type = \"velocity\", profile = \"poiseuille\", max = [0.5, 1.0] }";
  return {
      // Valid scenes, each near a rule that one of the engine's constructors also checks.
      {"NewtonianCavity", "", {}, ""},
      {"OldroydBNormalPoiseuilleInflow",
       "",
       {kOldroydB, kHalfSolvent, normal_inflow, kOutflowTop},
       ""},
      // 2 lambda max Re eig(L) = 2 (0.2) (4 (0.5) / 1) = 0.8 < 1.
      {"OldroydBTangentialInflowBelowTheLimit",
       "",
       {"fluid.relaxation_time=0.2", kHalfSolvent, tangential_inflow, kOutflowTop},
       ""},
      {"AlphaOneBetaZero", "", {"splitting.alpha=1.0", "splitting.beta=0.0"}, ""},
      {"HeavyNeutralAndFixedLightDisks",
       Disk(0.25, 0.5, 1.5) + Disk(0.5, 0.5, 1.0) + Disk(0.75, 0.5, 0.5, "fixed"),
       {},
       ""},
      {"OldroydBWithADisk", Disk(0.5, 0.5, 1.5), {kOldroydB, kHalfSolvent}, ""},
      {"DiskAcrossPeriodicSides",
       Disk(0.02, 0.5, 1.5),
       {"domain.boundary.left={ type = \"periodic\" }",
        "domain.boundary.right={ type = \"periodic\" }"},
       ""},
      // Invalid scenes: one broken rule each.
      {"AlphaZero", "", {"splitting.alpha=0.0", "splitting.beta=1.0"}, "splitting.alpha"},
      {"GammaNonZero", "", {"splitting.alpha=0.5", "splitting.beta=0.4"}, "splitting.beta"},
      {"LightFreeDisk", Disk(0.5, 0.5, 0.9), {}, "particles.0.density"},
      {"DiskTooSmallForItsExcessMass",
       Disk(0.5, 0.5, 1.5),
       {"particles.0.diameter=1e-200"},
       "particles.0.diameter"},
      {"InflowWithoutSteadyState",
       "",
       {kOldroydB, kHalfSolvent, tangential_inflow, kOutflowTop},
       "fluid.relaxation_time"},
      {"OverlappingDisks", Disk(0.5, 0.5, 1.5) + Disk(0.5, 0.65, 1.5), {}, "particles.1.center"},
      {"DiskCrossingAWall", Disk(0.5, 0.05, 1.5), {}, "particles.0.center"},
      {"HugeGrid", "", {"domain.h=0.0001"}, "domain.h"},
      {"TinyGrid", "", {"domain.h=1e-300"}, "domain.h"},
      {"TinyParticleMesh",
       Disk(0.5, 0.5, 1.5),
       {"particle_mesh.kind=ring", "particle_mesh.h=1e-300"},
       "particle_mesh.h"},
      {"CollocationSpacingTooSmall",
       Disk(0.5, 0.5, 1.5),
       {"particle_mesh.kind=collocation", "particle_mesh.spacing=0.1"},
       "particle_mesh.spacing"},
      {"CollocationPoints", Disk(0.5, 0.5, 1.5), {"particle_mesh.kind=collocation"}, ""},
      {"ParticleMeshKindUnknown",
       Disk(0.5, 0.5, 1.5),
       {"particle_mesh.kind=cut_cells"},
       "particle_mesh.kind"},
      // The accuracy envelope (scene/accuracy_envelope.h): a warning for both, a rejection for
      // both with accuracy.strict = true.
      // U dt / h = 0.8 > 0.64; D / h = 3.2 < 120.
      {"OutsideTheAccuracyEnvelope", "", {"time.dt=0.05", "time.end=0.05"}, ""},
      {"StrictOutsideTheAccuracyEnvelope",
       "",
       {"accuracy.strict=true", "time.dt=0.05", "time.end=0.05"},
       "time.dt"},
      {"DiskOutsideTheAccuracyEnvelope", Disk(0.5, 0.5, 1.5), {}, ""},
      {"StrictDiskOutsideTheAccuracyEnvelope",
       Disk(0.5, 0.5, 1.5),
       {"accuracy.strict=true"},
       "domain.h"},
      {"StrictInsideTheAccuracyEnvelope", "", {"accuracy.strict=true"}, ""},
      {"StepCountBeyond2To53", "", {"time.dt=1e-300", "time.end=1e300"}, "time.dt"},
      {"FieldPeriodBeyond2To53", "", {"output.fields_every=1e-300"}, "output.fields_every"},
      {"TooFewCellsForThePressureMesh", "", {"domain.h=0.5"}, "domain.size"},
      {"UnpairedPeriodicSide",
       "",
       {"domain.boundary.left={ type = \"periodic\" }"},
       "domain.boundary.right.type"},
  };
}

std::vector<SceneCase> AllCases() {
  std::vector<SceneCase> all = Cases();
  const std::vector<SceneCase> cut = CutCellCases();
  all.insert(all.end(), cut.begin(), cut.end());
  return all;
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs dlmfd-solve on the scene file with the overrides; returns its exit status (1000 + the signal
// that ended it) and leaves its stderr in `stderr_path`.
int RunSolver(const std::string& scene_path, const std::string& out,
              const std::vector<std::string>& overrides, const std::string& stderr_path) {
  std::vector<std::string> args = {
      dlmfd::testing::kSolverPath, scene_path, "--out", out, "--quiet", "--threads", "1"};
  for (const auto& o : overrides) {
    args.push_back("--set");
    args.push_back(o);
  }
  const pid_t pid = fork();
  if (pid == 0) {
    const int err = open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (err >= 0) dup2(err, 2);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) return 1000 + WTERMSIG(status);
  return WEXITSTATUS(status);
}

class SceneAgreement : public ::testing::TestWithParam<SceneCase> {};

TEST_P(SceneAgreement, SolverAndDaemonAgree) {
  if (!dlmfd::testing::SolverAvailable()) {
    GTEST_SKIP() << "dlmfd-solve is not built: " << dlmfd::testing::kSolverPath;
  }
  const SceneCase& c = GetParam();
  const std::string scene = std::string(kCavity) + c.particles;
  dlmfd::testing::TempDir dir;
  const std::string scene_path = dir.path() + "/scene.toml";
  std::ofstream(scene_path) << scene;

  const grpc::Status admitted = Guarded([&] { AdmitScene(scene, c.overrides, Config{}); });
  const int exit_code =
      RunSolver(scene_path, dir.path() + "/out", c.overrides, dir.path() + "/stderr.txt");
  const std::string solver_stderr = ReadAll(dir.path() + "/stderr.txt");

  if (c.key.empty()) {
    EXPECT_TRUE(admitted.ok()) << admitted.error_message();
    EXPECT_EQ(exit_code, 0) << solver_stderr;
  } else {
    EXPECT_EQ(admitted.error_code(), grpc::StatusCode::INVALID_ARGUMENT)
        << admitted.error_message();
    EXPECT_EQ(admitted.error_message().rfind(c.key + " = ", 0), 0u) << admitted.error_message();
    EXPECT_EQ(exit_code, 2) << solver_stderr;
    EXPECT_NE(solver_stderr.find(c.key + " = "), std::string::npos) << solver_stderr;
    EXPECT_FALSE(fs::exists(dir.path() + "/out/summary.json"));
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, SceneAgreement, ::testing::ValuesIn(AllCases()),
                         [](const ::testing::TestParamInfo<SceneCase>& param_info) {
                           return param_info.param.name;
                         });

TEST(SceneAdmission, DaemonLimitsHoldTheEngineFootprint) {
  Config config;
  config.max_memory_mb = 1;
  const std::string scene = kCavity;  // 17 x 17 nodes
  const SceneEstimate small = AdmitScene(scene, {}, config);
  const SceneFootprint footprint = EstimateFootprint(ParseScene(scene));
  EXPECT_EQ(small.nodes, 17 * 17);
  EXPECT_EQ(small.memory_mb, static_cast<int64_t>(std::ceil(footprint.bytes / (1024.0 * 1024.0))));
  // 65 x 65 nodes at kBytesPerNode each: over one MiB.
  const grpc::Status larger = Guarded([&] { AdmitScene(scene, {"domain.h=0.015625"}, config); });
  EXPECT_EQ(larger.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(larger.error_message().rfind("domain.h: the run needs an estimated 3 MiB", 0), 0u)
      << larger.error_message();
  config.max_grid_nodes = 1000;
  const grpc::Status nodes = Guarded([&] { AdmitScene(scene, {"domain.h=0.015625"}, config); });
  EXPECT_EQ(nodes.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(nodes.error_message(),
            "domain.h: the grid has 4225 velocity nodes, over the limit of 1000");
}

// Twenty free disks cut out of the mesh at D/h = 19.2 hold 4,520 capacitance rows, a grid array
// each (scene/scene_footprint.h): that, not the grid, is most of the estimate, and the refusal
// names particle_mesh.kind.
TEST(SceneAdmission, MovingCutCellBodiesNameTheParticleMesh) {
  std::string scene =
      "[domain]\nsize = [2.0, 2.0]\nh = 0.010416666666666666\n"
      "[particle_mesh]\nkind = \"cut_cell\"\n";
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 5; ++j) {
      scene += "[[particles]]\ncenter = [" + std::to_string(0.3 + 0.4 * i) + ", " +
               std::to_string(0.2 + 0.4 * j) + "]\ndiameter = 0.2\ndensity = 1.1\n";
    }
  }
  const SceneFootprint footprint = EstimateFootprint(ParseScene(scene));
  EXPECT_DOUBLE_EQ(footprint.cut_cell_rows, 20 * (11.25 * 19.2 + 10.0));
  Config config;
  config.max_memory_mb = 1000;
  const grpc::Status refused = Guarded([&] { AdmitScene(scene, {}, config); });
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(refused.error_message().rfind("particle_mesh.kind: the run needs an estimated", 0), 0u)
      << refused.error_message();
  EXPECT_THAT(refused.error_message(), ::testing::HasSubstr("4520 rows"));
}

}  // namespace
}  // namespace dlmfd::server
