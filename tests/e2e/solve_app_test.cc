// dlmfd-solve end to end (design.md 3.1-3.2): the real binary on a 16 x 16 lid-driven cavity.
// Exit statuses 0 / 2 / 130, every file of the results directory, the event stream, and a run
// killed with SIGKILL after a checkpoint and resumed giving results bitwise equal to an
// uninterrupted run.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "../support/build_paths.h"
#include "../support/scratch_path.h"
#include "dlmfd/io/atomic_file.h"
#include "dlmfd/io/checkpoint.h"
#include "dlmfd/io/diagnostics_csv.h"
#include "dlmfd/io/field_snapshot.h"
#include "dlmfd/io/particle_history.h"
#include "dlmfd/solver/run_summary.h"

namespace dlmfd {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// A cavity of 16 x 16 cells (h = 1/16) unless h is given; `end` and the output cadence vary per
// test.
std::string CavityScene(double end, double fields_every, double checkpoint_every,
                        const std::string& h = "0.0625") {
  return "title = \"e2e cavity\"\n"
         "[domain]\nsize = [1.0, 1.0]\nh = " +
         h +
         "\n"
         "[domain.boundary]\ntop = { type = \"velocity\", profile = \"uniform\", value = [1.0, "
         "0.0] }\n"
         "[fluid]\nviscosity = 0.01\n"
         "[time]\ndt = 0.001\nend = " +
         std::to_string(end) +
         "\n"
         "[splitting]\nadvection = \"wave\"\n"
         "[output]\nfields_every = " +
         std::to_string(fields_every) +
         "\nparticles_every = 0.0\n"
         "checkpoint_every = " +
         std::to_string(checkpoint_every) + "\n";
}

std::string Fresh(const std::string& name) {
  const std::string dir = dlmfd::testing::ScratchPath("solve_app_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string WriteFile(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

// A child running dlmfd-solve; stderr goes to a file; `events_fd` is inherited when >= 0.
struct Child {
  pid_t pid = -1;
  std::string stderr_path;
};

Child Start(const std::vector<std::string>& args, const std::string& stderr_path,
            int events_fd = -1) {
  Child c;
  c.stderr_path = stderr_path;
  c.pid = fork();
  if (c.pid == 0) {
    const int err = open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (err >= 0) dup2(err, 2);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(testing::kSolver.c_str()));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    (void)events_fd;
    execv(testing::kSolver.c_str(), argv.data());
    _exit(127);
  }
  return c;
}

// The exit status, or 1000 + the signal that ended the child.
int Wait(const Child& c) {
  int status = 0;
  waitpid(c.pid, &status, 0);
  if (WIFSIGNALED(status)) return 1000 + WTERMSIG(status);
  return WEXITSTATUS(status);
}

int RunToEnd(const std::vector<std::string>& args, const std::string& stderr_path,
             int events_fd = -1) {
  return Wait(Start(args, stderr_path, events_fd));
}

void WaitFor(const std::function<bool()>& ready, const Child& c) {
  while (!ready()) {
    int status = 0;
    ASSERT_EQ(waitpid(c.pid, &status, WNOHANG), 0) << "the solver ended before the awaited moment";
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

std::string LastSnapshot(const std::string& dir) {
  std::string last;
  for (const auto& e : fs::directory_iterator(dir + "/fields")) {
    const std::string name = e.path().filename().string();
    if (name.rfind("snap_", 0) == 0 && name > last) last = name;
  }
  return dir + "/fields/" + last;
}

// stdout of a shell command and its exit status.
std::pair<std::string, int> Shell(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = pclose(pipe);
  return {out, WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status)};
}

// Issue 38: a scene of one key with 20,000 dotted parts ended dlmfd-solve with status 139; and a
// run to t = 0, once the only way to see a scene's accuracy warnings, is refused: --check says it.
TEST(SolveApp, ADeepKeyIsAnInvalidSceneAndCheckDescribesAScene) {
  const std::string dir = Fresh("check");
  std::string key = "z";
  for (int i = 1; i < 20000; ++i) key += ".z";
  const std::string deep = WriteFile(dir + "/deep.toml", key + " = 1\n");
  EXPECT_EQ(RunToEnd({deep, "--out", dir + "/deep"}, dir + "/deep.txt"), 2);
  EXPECT_THAT(ReadTextFile(dir + "/deep.txt"), HasSubstr("at most 16 dotted parts"));
  const std::string scene = WriteFile(dir + "/cavity.toml", CavityScene(0.02, 0.005, 0.01));
  const auto [text, status] =
      Shell(testing::kSolver + " " + scene + " --check --set time.dt=0.05 --set time.end=0.1");
  EXPECT_EQ(status, 0);
  EXPECT_THAT(text, HasSubstr("mesh: 16 x 16 cells"));
  EXPECT_THAT(text, HasSubstr("steps: 2 to t = 0.1"));
  EXPECT_THAT(text, HasSubstr("warning: "));  // dt = 0.05 is outside the envelope
  // What `auto` resolves is said before a run too (a liquid alone: the lagged multiplier).
  EXPECT_THAT(text, HasSubstr("numerics: splitting.constraint = \"incremental\""));
  EXPECT_FALSE(fs::exists(dir + "/out"));
  EXPECT_EQ(Shell(testing::kSolver + " " + scene + " --check --set time.end=0 2>&1").second, 2);
  EXPECT_EQ(Shell(testing::kSolver + " " + scene + " 2>&1").second,
            2);  // neither --out nor --check
}

TEST(SolveApp, CompletesAndWritesTheResultsDirectory) {
  const std::string dir = Fresh("complete");
  const std::string scene = WriteFile(dir + "/cavity.toml", CavityScene(0.02, 0.005, 0.01));
  const std::string out = dir + "/out";
  ASSERT_EQ(RunToEnd({scene, "--out", out, "--quiet"}, dir + "/stderr.txt"), 0)
      << ReadTextFile(dir + "/stderr.txt");
  for (const char* f :
       {"scene.toml", "summary.json", "particles.h5", "diagnostics.csv", "fields.xmf",
        "checkpoint.h5", "fields/snap_000000.h5", "fields/snap_000020.h5"}) {
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  }
  // Snapshots at t = 0, 0.005, ..., 0.02: steps 0, 5, 10, 15, 20.
  const FieldSnapshot s = ReadFieldSnapshot(out + "/fields/snap_000020.h5");
  EXPECT_EQ(s.step, 20);
  EXPECT_DOUBLE_EQ(s.time, 0.02);
  EXPECT_EQ(s.h, 0.0625);
  EXPECT_EQ(s.fields.at("u").shape, (std::vector<std::size_t>{17, 17}));
  EXPECT_EQ(s.fields.at("v").shape, (std::vector<std::size_t>{17, 17}));
  EXPECT_EQ(s.fields.at("p").shape, (std::vector<std::size_t>{9, 9}));
  EXPECT_EQ(s.fields.count("trA"), 0u);                  // Newtonian
  EXPECT_EQ(s.fields.at("u").values[16 * 17 + 8], 1.0);  // the lid
  const std::string xmf = ReadTextFile(out + "/fields.xmf");
  for (const char* step : {"000000", "000005", "000010", "000015", "000020"}) {
    EXPECT_THAT(xmf, HasSubstr(std::string("fields/snap_") + step + ".h5:/u"));
  }
  EXPECT_THAT(xmf, HasSubstr("</Xdmf>"));
  const DiagnosticsTable d = ReadDiagnostics(out + "/diagnostics.csv");
  ASSERT_EQ(d.rows.size(), 20u);
  EXPECT_EQ(d.header[0], "step");
  EXPECT_GE(d.Column("stokes_iterations"), 3);
  EXPECT_EQ(d.rows.back()[0], 20.0);
  const ParticleHistory h = ReadParticleHistory(out + "/particles.h5");
  EXPECT_EQ(h.records, 21u);  // the initial state and every step (particles_every = 0)
  const std::string summary = ReadTextFile(out + "/summary.json");
  EXPECT_THAT(summary, HasSubstr("\"status\": \"completed\""));
  EXPECT_THAT(summary, HasSubstr("\"steps\": 20"));
  EXPECT_THAT(summary, HasSubstr("\"warnings\": []"));  // inside the accuracy envelope
  EXPECT_THAT(ReadTextFile(out + "/scene.toml"), HasSubstr("stokes_max_iterations = 200"));
  EXPECT_EQ(ReadCheckpoint(out + "/checkpoint.h5").state.step, 20);
}

TEST(SolveApp, InvalidSceneExitsWithTwoNamingTheKey) {
  const std::string dir = Fresh("invalid");
  const std::string scene = WriteFile(dir + "/cavity.toml", CavityScene(0.02, 0.005, 0.01));
  const std::string out = dir + "/out";
  EXPECT_EQ(RunToEnd({scene, "--out", out, "--set", "fluid.viscosity=-1"}, dir + "/stderr.txt"), 2);
  const std::string err = ReadTextFile(dir + "/stderr.txt");
  EXPECT_THAT(err, HasSubstr("fluid.viscosity"));
  EXPECT_THAT(err, HasSubstr("-1"));
  EXPECT_THAT(err, HasSubstr("> 0"));
  EXPECT_FALSE(fs::exists(out + "/summary.json"));
  EXPECT_EQ(RunToEnd({scene, "--out", out, "--bogus"}, dir + "/stderr2.txt"), 2);
  WriteFile(dir + "/typo.toml", "[fluid]\nviscosty = 0.1\n");
  EXPECT_EQ(RunToEnd({dir + "/typo.toml", "--out", out}, dir + "/stderr3.txt"), 2);
  EXPECT_THAT(ReadTextFile(dir + "/stderr3.txt"), HasSubstr("fluid.viscosty"));
}

// dt = 0.1 on the 16 x 16 cavity: U dt / h = 1.6, outside the envelope's 0.64
// (dlmfd/scene/accuracy_envelope.h). The run warns, completes and lists the warning in
// summary.json; with accuracy.strict = true it is an invalid scene naming time.dt.
TEST(SolveApp, SceneOutsideTheAccuracyEnvelopeWarnsAndStrictRejectsIt) {
  const std::string dir = Fresh("accuracy");
  const std::string scene = WriteFile(dir + "/cavity.toml", CavityScene(0.2, 0.1, 0.0));
  const std::string out = dir + "/out";
  ASSERT_EQ(RunToEnd({scene, "--out", out, "--quiet", "--set", "time.dt=0.1"}, dir + "/err.txt"), 0)
      << ReadTextFile(dir + "/err.txt");
  EXPECT_THAT(ReadTextFile(dir + "/err.txt"), HasSubstr("accuracy: U dt / h = 1.6"));
  const solver::RunSummary summary = solver::ReadRunSummary(out + "/summary.json");
  EXPECT_EQ(summary.status, "completed");
  ASSERT_EQ(summary.warnings.size(), 1u);
  const solver::RunSummary::Warning& w = summary.warnings[0];
  EXPECT_EQ(w.setting, "U dt / h");
  EXPECT_DOUBLE_EQ(w.value, 1.6);
  EXPECT_EQ(w.allowed, "<= 0.64");
  EXPECT_EQ(w.key, "time.dt");
  EXPECT_EQ(w.current, "0.1");
  EXPECT_LE(std::stod(w.suggested) / 0.0625, 0.64);
  EXPECT_THAT(ReadTextFile(out + "/summary.json"), HasSubstr("\"key\": \"time.dt\""));

  const std::string strict = dir + "/strict";
  EXPECT_EQ(
      RunToEnd({scene, "--out", strict, "--set", "time.dt=0.1", "--set", "accuracy.strict=true"},
               dir + "/strict_err.txt"),
      2);
  const std::string err = ReadTextFile(dir + "/strict_err.txt");
  EXPECT_THAT(err, HasSubstr("time.dt = 0.1 is not allowed"));
  EXPECT_THAT(err, HasSubstr("accuracy.strict"));
  EXPECT_FALSE(fs::exists(strict + "/summary.json"));
}

TEST(SolveApp, SigtermCancelsWithReadableFiles) {
  const std::string dir = Fresh("sigterm");
  const std::string scene = WriteFile(dir + "/cavity.toml", CavityScene(1000.0, 0.01, 0.0));
  const std::string out = dir + "/out";
  const Child c = Start({scene, "--out", out, "--quiet"}, dir + "/stderr.txt");
  WaitFor([&] { return fs::exists(out + "/fields/snap_000010.h5"); }, c);
  kill(c.pid, SIGTERM);
  ASSERT_EQ(Wait(c), 130) << ReadTextFile(dir + "/stderr.txt");
  const std::string summary = ReadTextFile(out + "/summary.json");
  EXPECT_THAT(summary, HasSubstr("\"status\": \"cancelled\""));
  const Checkpoint ck = ReadCheckpoint(out + "/checkpoint.h5");
  EXPECT_GE(ck.state.step, 10);
  const DiagnosticsTable d = ReadDiagnostics(out + "/diagnostics.csv");
  EXPECT_EQ(static_cast<long>(d.rows.size()), ck.state.step);
  EXPECT_EQ(ReadParticleHistory(out + "/particles.h5").records,
            static_cast<std::size_t>(ck.state.step + 1));
  EXPECT_EQ(ReadFieldSnapshot(LastSnapshot(out)).fields.at("u").shape,
            (std::vector<std::size_t>{17, 17}));
}

void ExpectSameDoubles(const std::vector<double>& a, const std::vector<double>& b,
                       const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  if (a.empty()) return;  // memcmp must not see the null data() of an empty vector
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << what;
}

TEST(SolveApp, ResumeAfterSigkillEqualsAnUninterruptedRun) {
  const std::string dir = Fresh("resume");
  // 300 steps, a checkpoint every 10, on 64 x 64 cells: the killed run is far from its end
  // when it dies. (On 16 x 16 cells the whole run took a few tens of ms, and under load it could
  // finish between the first checkpoint's appearance and the kill.)
  const std::string scene =
      WriteFile(dir + "/cavity.toml", CavityScene(0.3, 0.1, 0.01, "0.015625"));
  const std::string whole = dir + "/whole", resumed = dir + "/resumed";
  ASSERT_EQ(RunToEnd({scene, "--out", whole, "--quiet"}, dir + "/stderr1.txt"), 0);

  const Child c = Start({scene, "--out", resumed, "--quiet"}, dir + "/stderr2.txt");
  WaitFor([&] { return fs::exists(resumed + "/checkpoint.h5"); }, c);
  kill(c.pid, SIGKILL);
  ASSERT_EQ(Wait(c), 1000 + SIGKILL);
  const long checkpoint_step = ReadCheckpoint(resumed + "/checkpoint.h5").state.step;
  EXPECT_LT(checkpoint_step, 300);
  ASSERT_EQ(RunToEnd({scene, "--out", resumed, "--resume", "--quiet"}, dir + "/stderr3.txt"), 0)
      << ReadTextFile(dir + "/stderr3.txt");

  const FieldSnapshot a = ReadFieldSnapshot(whole + "/fields/snap_000300.h5");
  const FieldSnapshot b = ReadFieldSnapshot(resumed + "/fields/snap_000300.h5");
  for (const char* f : {"u", "v", "p"})
    ExpectSameDoubles(a.fields.at(f).values, b.fields.at(f).values, f);
  const ParticleHistory pa = ReadParticleHistory(whole + "/particles.h5");
  const ParticleHistory pb = ReadParticleHistory(resumed + "/particles.h5");
  EXPECT_EQ(pa.records, pb.records);
  EXPECT_EQ(pa.step, pb.step);
  ExpectSameDoubles(pa.time, pb.time, "particles.h5:/time");
  ExpectSameDoubles(pa.position, pb.position, "particles.h5:/position");
  ExpectSameDoubles(pa.velocity, pb.velocity, "particles.h5:/velocity");
  ExpectSameDoubles(pa.force, pb.force, "particles.h5:/force");
  EXPECT_EQ(ReadDiagnostics(resumed + "/diagnostics.csv").rows.size(), 300u);
  std::vector<std::string> names_a, names_b;
  for (const auto& e : fs::directory_iterator(whole + "/fields"))
    names_a.push_back(e.path().filename().string());
  for (const auto& e : fs::directory_iterator(resumed + "/fields"))
    names_b.push_back(e.path().filename().string());
  std::sort(names_a.begin(), names_a.end());
  std::sort(names_b.begin(), names_b.end());
  EXPECT_EQ(names_a, names_b);
  EXPECT_THAT(ReadTextFile(resumed + "/summary.json"),
              HasSubstr("\"resumed_from_step\": " + std::to_string(checkpoint_step)));
  // The statistics of the whole run (io/run_statistics.h) are those of the uninterrupted run.
  auto statistics = [](const std::string& out) {
    const solver::RunSummary s = solver::ReadRunSummary(out + "/summary.json");
    std::vector<double> v = {s.min_gap,    s.min_wall_gap, s.max_trA,        s.min_eig_A,
                             s.fall_speed, s.reynolds,     s.fall_window[0], s.fall_window[1]};
    for (const auto& p : s.particles) v.push_back(p.fall_speed);
    return v;
  };
  ExpectSameDoubles(statistics(whole), statistics(resumed), "summary.json statistics");

  // A different scene is refused on resume.
  EXPECT_EQ(RunToEnd({scene, "--out", resumed, "--resume", "--set", "fluid.viscosity=0.02"},
                     dir + "/stderr4.txt"),
            2);
  EXPECT_THAT(ReadTextFile(dir + "/stderr4.txt"), HasSubstr("--resume"));
}

// Runs `scene` (a run of `steps` steps, a checkpoint every few of them, its fields at the end)
// whole, and killed at its first checkpoint and resumed: the same fields at the end and the same
// forces at every step, bit for bit.
void ExpectResumedRunEqualsTheWhole(const std::string& dir, const std::string& scene, long steps) {
  const std::string whole = dir + "/whole", resumed = dir + "/resumed";
  ASSERT_EQ(RunToEnd({scene, "--out", whole, "--quiet"}, dir + "/stderr1.txt"), 0)
      << ReadTextFile(dir + "/stderr1.txt");
  const Child c = Start({scene, "--out", resumed, "--quiet"}, dir + "/stderr2.txt");
  WaitFor([&] { return fs::exists(resumed + "/checkpoint.h5"); }, c);
  kill(c.pid, SIGKILL);
  ASSERT_EQ(Wait(c), 1000 + SIGKILL);
  EXPECT_LT(ReadCheckpoint(resumed + "/checkpoint.h5").state.step, steps);
  ASSERT_EQ(RunToEnd({scene, "--out", resumed, "--resume", "--quiet"}, dir + "/stderr3.txt"), 0)
      << ReadTextFile(dir + "/stderr3.txt");
  char last[32];
  std::snprintf(last, sizeof last, "/fields/snap_%06ld.h5", steps);
  const FieldSnapshot a = ReadFieldSnapshot(whole + last);
  const FieldSnapshot b = ReadFieldSnapshot(resumed + last);
  for (const char* f : {"u", "v", "p"})
    ExpectSameDoubles(a.fields.at(f).values, b.fields.at(f).values, f);
  const ParticleHistory pa = ReadParticleHistory(whole + "/particles.h5");
  const ParticleHistory pb = ReadParticleHistory(resumed + "/particles.h5");
  EXPECT_EQ(pa.step, pb.step);
  ExpectSameDoubles(pa.force, pb.force, "particles.h5:/force");
}

// A fixed disk cut out of the mesh: the cut-cell Stokes solver starts each step's pressure
// iteration from the span of the earlier steps' pressure corrections (particles/
// pressure_correction_basis.h), which checkpoint.h5 holds (/cut_cell_start). Without them the
// resumed run's force differed from the 7th digit.
TEST(SolveApp, ResumeWithCutCellsEqualsAnUninterruptedRun) {
  const std::string dir = Fresh("resume_cut_cells");
  // 1000 steps on 128 x 32 cells, a checkpoint every 10: the killed run is far from its end.
  const std::string scene = WriteFile(dir + "/channel.toml", R"(title = "e2e disk in a channel"
[domain]
size = [2.0, 0.5]
h = 0.015625
[domain.boundary]
left = { type = "velocity", profile = "poiseuille", max = [1.0, 0.0] }
right = { type = "outflow" }
bottom = { type = "wall" }
top = { type = "wall" }
[fluid]
viscosity = 0.01
[time]
dt = 0.002
end = 2.0
[[particles]]
center = [0.5, 0.25]
diameter = 0.2
motion = "fixed"
[particle_mesh]
kind = "cut_cell"
[output]
fields_every = 1.0
particles_every = 0.0
checkpoint_every = 0.02
)");
  ExpectResumedRunEqualsTheWhole(dir, scene, 1000);
}

// A disk towed across the mesh: its pressure iteration starts from 2 p^n - p^{n-1}, and
// checkpoint.h5 holds p^{n-1} (/cut_cell_start/previous_pressure).
TEST(SolveApp, ResumeWithATowedCutCellDiskEqualsAnUninterruptedRun) {
  const std::string dir = Fresh("resume_towed_cut_cell");
  // 200 steps on 80 x 40 cells, the disk 0.4 cells a step, a checkpoint every 5 steps.
  const std::string scene = WriteFile(dir + "/towed.toml", R"(title = "e2e towed disk"
[domain]
size = [4.0, 2.0]
h = 0.05
[domain.boundary]
left = { type = "periodic" }
right = { type = "periodic" }
bottom = { type = "wall" }
top = { type = "wall" }
[fluid]
viscosity = 1.0
[time]
dt = 0.02
end = 4.0
[[particles]]
center = [2.0, 1.0]
diameter = 1.0
motion = "prescribed"
velocity = [1.0, 0.0]
[particle_mesh]
kind = "cut_cell"
[output]
fields_every = 2.0
particles_every = 0.0
checkpoint_every = 0.1
)");
  ExpectResumedRunEqualsTheWhole(dir, scene, 200);
}

// Issue 38: on the paper's grid the FFTW plans were timed (FFTW_MEASURE), so two runs of a scene,
// or a run and its resumption, could differ in the last bits; and the OpenMP sums added the
// threads' parts in the order they finished. The paper's 5.2 pair on its grid (193 x 769 nodes),
// three threads: two whole runs and a run killed after a checkpoint and resumed give the same
// particles.h5 and fields, bit for bit.
TEST(SolveApp, ThePapersGridRunsTwiceAndResumedToTheSameBits) {
  const std::string dir = Fresh("paper_bits");
  const std::string scene = std::string(DLMFD_SOURCE_DIR) + "/cases/paper/5.2_pair_oldroyd_b.toml";
  // 6 steps of dt = 4e-4; particles every step, fields and checkpoints every 2 steps.
  const std::vector<std::string> sets = {"--set",     "time.end=0.0024",
                                         "--set",     "output.particles_every=0.0004",
                                         "--set",     "output.fields_every=0.0008",
                                         "--set",     "output.checkpoint_every=0.0008",
                                         "--threads", "3",
                                         "--quiet"};
  auto args = [&](const std::string& out, bool resume) {
    std::vector<std::string> a = {scene, "--out", out};
    a.insert(a.end(), sets.begin(), sets.end());
    if (resume) a.push_back("--resume");
    return a;
  };
  const std::string first = dir + "/first", second = dir + "/second", resumed = dir + "/resumed";
  ASSERT_EQ(RunToEnd(args(first, false), dir + "/1.txt"), 0) << ReadTextFile(dir + "/1.txt");
  ASSERT_EQ(RunToEnd(args(second, false), dir + "/2.txt"), 0) << ReadTextFile(dir + "/2.txt");
  const Child c = Start(args(resumed, false), dir + "/3.txt");
  WaitFor([&] { return fs::exists(resumed + "/checkpoint.h5"); }, c);
  kill(c.pid, SIGKILL);
  Wait(c);
  ASSERT_EQ(RunToEnd(args(resumed, true), dir + "/4.txt"), 0) << ReadTextFile(dir + "/4.txt");
  const ParticleHistory reference = ReadParticleHistory(first + "/particles.h5");
  EXPECT_EQ(reference.records, 7u);
  for (const std::string& other : {second, resumed}) {
    const ParticleHistory h = ReadParticleHistory(other + "/particles.h5");
    EXPECT_EQ(h.step, reference.step) << other;
    ExpectSameDoubles(h.position, reference.position, other + " particles.h5:/position");
    ExpectSameDoubles(h.velocity, reference.velocity, other + " particles.h5:/velocity");
    ExpectSameDoubles(h.angular_velocity, reference.angular_velocity,
                      other + " particles.h5:/angular_velocity");
    ExpectSameDoubles(h.force, reference.force, other + " particles.h5:/force");
    ExpectSameDoubles(h.torque, reference.torque, other + " particles.h5:/torque");
    for (const char* snap : {"snap_000004.h5", "snap_000006.h5"}) {
      const FieldSnapshot a = ReadFieldSnapshot(first + "/fields/" + snap);
      const FieldSnapshot b = ReadFieldSnapshot(other + "/fields/" + snap);
      for (const char* f : {"u", "v", "p", "trA", "A11", "A12", "A22"}) {
        ExpectSameDoubles(a.fields.at(f).values, b.fields.at(f).values,
                          other + " " + snap + ":/" + f);
      }
    }
  }
}

// Minimal protobuf wire reading, enough to walk the SolverEvent stream without linking protobuf.
struct Wire {
  const unsigned char* p;
  const unsigned char* end;
  bool Varint(std::uint64_t* out) {
    std::uint64_t v = 0;
    for (int shift = 0; p < end && shift < 64; shift += 7) {
      const unsigned char b = *p++;
      v |= std::uint64_t(b & 0x7f) << shift;
      if (!(b & 0x80)) {
        *out = v;
        return true;
      }
    }
    return false;
  }
  // Calls field(number, wire_type, payload pointer, payload length or varint value).
  template <typename F>
  bool Fields(F field) {
    while (p < end) {
      std::uint64_t key = 0, value = 0;
      if (!Varint(&key)) return false;
      const int type = int(key & 7);
      const int number = int(key >> 3);
      if (type == 0) {
        if (!Varint(&value)) return false;
        field(number, type, nullptr, value);
      } else if (type == 1) {
        if (end - p < 8) return false;
        field(number, type, p, 8);
        p += 8;
      } else if (type == 2) {
        if (!Varint(&value) || std::uint64_t(end - p) < value) return false;
        field(number, type, p, value);
        p += value;
      } else if (type == 5) {
        if (end - p < 4) return false;
        field(number, type, p, 4);
        p += 4;
      } else {
        return false;
      }
    }
    return true;
  }
};

TEST(SolveApp, EventStreamParsesAndEndsWithFinished) {
  const std::string dir = Fresh("events");
  const std::string scene = WriteFile(dir + "/cavity.toml", CavityScene(0.02, 0.01, 0.01));
  const std::string events_path = dir + "/events.bin";
  const int fd = open(events_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(fd, 0);
  const int code =
      RunToEnd({scene, "--out", dir + "/out", "--quiet", "--events", std::to_string(fd)},
               dir + "/stderr.txt", fd);
  close(fd);
  ASSERT_EQ(code, 0) << ReadTextFile(dir + "/stderr.txt");
  const std::string bytes = ReadTextFile(events_path);
  Wire stream{reinterpret_cast<const unsigned char*>(bytes.data()),
              reinterpret_cast<const unsigned char*>(bytes.data()) + bytes.size()};
  std::vector<int> kinds;  // the oneof field number of each event
  std::vector<std::uint64_t> seqs;
  std::string finished_status, snapshot_quantity;
  std::uint64_t finished_exit = 0;  // proto3 leaves a zero field out of the wire
  while (stream.p < stream.end) {
    std::uint64_t length = 0;
    ASSERT_TRUE(stream.Varint(&length));
    ASSERT_LE(length, std::uint64_t(stream.end - stream.p));
    Wire event{stream.p, stream.p + length};
    stream.p += length;
    int kind = 0;
    ASSERT_TRUE(event.Fields([&](int number, int type, const unsigned char* data, std::uint64_t n) {
      if (number == 1 && type == 0) seqs.push_back(n);
      if (number < 10 || type != 2) return;
      kind = number;
      Wire body{data, data + n};
      body.Fields([&](int f, int t, const unsigned char* d, std::uint64_t m) {
        if (number == 16 && f == 1 && t == 2)
          finished_status.assign(reinterpret_cast<const char*>(d), m);
        if (number == 16 && f == 5 && t == 0) finished_exit = m;
        if (number == 13 && f == 6 && t == 2)
          snapshot_quantity.assign(reinterpret_cast<const char*>(d), m);
      });
    }));
    kinds.push_back(kind);
  }
  ASSERT_GE(kinds.size(), 4u);
  EXPECT_EQ(kinds.front(), 10);  // started
  EXPECT_EQ(kinds.back(), 16);   // finished, last
  EXPECT_EQ(std::count(kinds.begin(), kinds.end(), 16), 1);
  EXPECT_EQ(std::count(kinds.begin(), kinds.end(), 13), 3);  // snapshots at steps 0, 10, 20
  EXPECT_GE(std::count(kinds.begin(), kinds.end(), 15), 1);  // checkpointed
  EXPECT_GE(std::count(kinds.begin(), kinds.end(), 11),
            1);  // progress (the last step always reports)
  EXPECT_EQ(finished_status, "completed");
  EXPECT_EQ(finished_exit, 0u);
  EXPECT_EQ(snapshot_quantity, "speed");
  for (std::size_t k = 0; k < seqs.size(); ++k) EXPECT_EQ(seqs[k], k + 1);
}

}  // namespace
}  // namespace dlmfd
