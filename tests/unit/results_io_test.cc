// The writers and readers of the results directory (design.md 3.2) on their own: field snapshots,
// fields.xmf, particles.h5, diagnostics.csv, checkpoint.h5, and ResultsWriter's
// resume cut-back. Values are compared bitwise: these files store doubles as doubles.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>

#include "../support/scratch_path.h"
#include "../support/viscous_channel.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/simulation.h"
#include "dlmfd/io/atomic_file.h"
#include "dlmfd/io/checkpoint.h"
#include "dlmfd/io/diagnostics_csv.h"
#include "dlmfd/io/field_snapshot.h"
#include "dlmfd/io/fields_xdmf.h"
#include "dlmfd/io/particle_history.h"
#include "dlmfd/io/results_format.h"
#include "dlmfd/io/results_writer.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string FreshDir(const std::string& name) {
  const std::string dir = dlmfd::testing::ScratchPath("results_io_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void ExpectSameBits(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_TRUE(SameBits(a[k], b[k])) << "index " << k;
}

std::vector<double> RandomField(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  std::vector<double> f(n);
  for (double& x : f) x = dist(rng);
  return f;
}

Grid SmallGrid() { return Grid{8, 6, 0.125, 0.0, 0.0}; }

FlowState RandomState(const Grid& g, bool conformation, int particles, unsigned seed) {
  FlowState s;
  s.step = 42;
  s.time = 42 * 1e-3;
  s.u = RandomField(g.NodeCount(), seed);
  s.v = RandomField(g.NodeCount(), seed + 1);
  s.p = RandomField(g.Coarse().NodeCount(), seed + 2);
  if (conformation) {
    s.a11 = RandomField(g.NodeCount(), seed + 3);
    s.a12 = RandomField(g.NodeCount(), seed + 4);
    s.a22 = RandomField(g.NodeCount(), seed + 5);
    s.d11 = RandomField(g.NodeCount(), seed + 6);
    s.d12 = RandomField(g.NodeCount(), seed + 7);
    s.d22 = RandomField(g.NodeCount(), seed + 8);
  }
  for (int i = 0; i < particles; ++i) {
    ParticleState q;
    q.id = i;
    q.position = Vec2(0.1 * i + 0.3, 0.2);
    q.velocity = Vec2(-1.0 / 3.0, i);
    q.angular_velocity = std::ldexp(1.0, -1070);  // subnormal
    q.force = Vec2(-0.0, 1e300);
    q.torque = -i - 0.5;
    q.radius = 0.05;
    q.density = 1.5;
    q.motion = i == 1 ? Motion::kFixed : Motion::kFree;
    q.multiplier = RandomField(static_cast<std::size_t>(2 * (i + 3)), seed + 10 + i);
    s.particles.push_back(q);
  }
  return s;
}

TEST(FieldSnapshot, WritesShapesAttributesAndValues) {
  const std::string dir = FreshDir("snapshot");
  const Grid g = SmallGrid();
  const FlowState s = RandomState(g, true, 0, 1);
  const std::string path = dir + "/" + SnapshotFileName(s.step);
  EXPECT_EQ(SnapshotFileName(s.step), "snap_000042.h5");
  WriteFieldSnapshot(path, g, s);
  EXPECT_FALSE(fs::exists(TemporaryPath(path)));
  const FieldSnapshot r = ReadFieldSnapshot(path);
  EXPECT_EQ(r.step, 42);
  EXPECT_TRUE(SameBits(r.time, s.time));
  EXPECT_EQ(r.h, g.h);
  ASSERT_EQ(r.fields.size(), 8u);
  EXPECT_EQ(r.fields.at("u").shape, (std::vector<std::size_t>{7, 9}));
  EXPECT_EQ(r.fields.at("velocity").shape, (std::vector<std::size_t>{7, 9, 3}));
  EXPECT_EQ(r.fields.at("p").shape, (std::vector<std::size_t>{4, 5}));
  EXPECT_EQ(r.fields.at("A12").shape, (std::vector<std::size_t>{7, 9}));
  ExpectSameBits(r.fields.at("u").values, s.u);
  ExpectSameBits(r.fields.at("v").values, s.v);
  ExpectSameBits(r.fields.at("p").values, s.p);
  ExpectSameBits(r.fields.at("A22").values, s.a22);
  for (std::size_t k = 0; k < g.NodeCount(); ++k) {
    EXPECT_EQ(r.fields.at("trA").values[k], s.a11[k] + s.a22[k]);
    // The vector ParaView reads (fields.xmf): (u, v, 0) at each node, x fastest.
    EXPECT_TRUE(SameBits(r.fields.at("velocity").values[3 * k], s.u[k])) << k;
    EXPECT_TRUE(SameBits(r.fields.at("velocity").values[3 * k + 1], s.v[k])) << k;
    EXPECT_TRUE(SameBits(r.fields.at("velocity").values[3 * k + 2], 0.0)) << k;
  }
}

TEST(FieldSnapshot, NewtonianSnapshotHasNoConformation) {
  const std::string dir = FreshDir("snapshot_newtonian");
  const Grid g = SmallGrid();
  const FlowState s = RandomState(g, false, 0, 2);
  WriteFieldSnapshot(dir + "/s.h5", g, s);
  const FieldSnapshot r = ReadFieldSnapshot(dir + "/s.h5");
  EXPECT_EQ(r.fields.size(), 4u);  // u, v, velocity, p
  EXPECT_EQ(r.fields.count("trA"), 0u);
}

TEST(FieldSnapshot, MismatchedStateIsAnError) {
  const std::string dir = FreshDir("snapshot_bad");
  FlowState s = RandomState(SmallGrid(), false, 0, 3);
  s.p.pop_back();
  EXPECT_THROW(WriteFieldSnapshot(dir + "/s.h5", SmallGrid(), s), Error);
  EXPECT_THROW(ReadFieldSnapshot(dir + "/absent.h5"), Error);
}

// Results format 2: the scene, the coordinates and the particles at the snapshot's own step.
TEST(FieldSnapshot, DescribesItselfAndHoldsItsParticles) {
  const std::string dir = FreshDir("snapshot_v2");
  const Grid g{8, 6, 0.125, 0.5, -1.0};
  const FlowState s = RandomState(g, true, 2, 11);
  const std::string scene = "title = \"two disks\"\n[domain]\nh = 0.125\n";
  WriteFieldSnapshot(dir + "/s.h5", g, s, SnapshotExtras{scene, {0.25, -1.5}});
  const FieldSnapshot r = ReadFieldSnapshot(dir + "/s.h5");
  EXPECT_EQ(r.format_version, kResultsFormatVersion);
  EXPECT_EQ(r.scene_text, scene);
  ASSERT_TRUE(r.has_particles);
  ASSERT_EQ(r.particles.Count(), 2u);
  EXPECT_EQ(r.particles.id, (std::vector<std::int64_t>{0, 1}));
  EXPECT_EQ(r.particles.angle, (std::vector<double>{0.25, -1.5}));
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_TRUE(SameBits(r.particles.position[2 * k], s.particles[k].position.x()));
    EXPECT_TRUE(SameBits(r.particles.position[2 * k + 1], s.particles[k].position.y()));
    EXPECT_TRUE(SameBits(r.particles.velocity[2 * k], s.particles[k].velocity.x()));
    EXPECT_TRUE(SameBits(r.particles.angular_velocity[k], s.particles[k].angular_velocity));
    EXPECT_TRUE(SameBits(r.particles.torque[k], s.particles[k].torque));
    EXPECT_TRUE(SameBits(r.particles.radius[k], s.particles[k].radius));
  }
  // Without angles the group has none; without particles it is empty but present.
  WriteFieldSnapshot(dir + "/t.h5", g, s);
  EXPECT_TRUE(ReadFieldSnapshot(dir + "/t.h5").particles.angle.empty());
  WriteFieldSnapshot(dir + "/n.h5", g, RandomState(g, false, 0, 12));
  EXPECT_TRUE(ReadFieldSnapshot(dir + "/n.h5").has_particles);
  EXPECT_EQ(ReadFieldSnapshot(dir + "/n.h5").particles.Count(), 0u);
}

TEST(ResultsFormat, EveryWrittenDatasetHasUnitsAndADescription) {
  for (const char* name : {"x",
                           "y",
                           "x_pressure",
                           "y_pressure",
                           "u",
                           "v",
                           "velocity",
                           "p",
                           "trA",
                           "A11",
                           "A12",
                           "A22",
                           "scene",
                           "particles/id",
                           "particles/radius",
                           "particles/position",
                           "particles/velocity",
                           "particles/angle",
                           "particles/angular_velocity",
                           "particles/force",
                           "particles/torque",
                           "particles/position_xyz",
                           "particles/velocity_xyz"}) {
    const DatasetMeaning* m = MeaningOfDataset(ResultsFile::kSnapshot, name);
    ASSERT_NE(m, nullptr) << name;
    EXPECT_GT(std::strlen(m->description), 10u) << name;
  }
  for (const char* name : {"time", "step", "id", "radius", "position", "velocity",
                           "angular_velocity", "force", "torque", "angle", "scene"}) {
    ASSERT_NE(MeaningOfDataset(ResultsFile::kParticles, name), nullptr) << name;
  }
  EXPECT_EQ(MeaningOfDataset(ResultsFile::kParticles, "trA"), nullptr);
  EXPECT_STREQ(MeaningOfDataset(ResultsFile::kSnapshot, "velocity")->units, "L T-1");
  EXPECT_STREQ(MeaningOfDataset(ResultsFile::kParticles, "force")->units, "M T-2");
  EXPECT_EQ(UnitsIn("L T-1", "cgs"), "cm s-1");
  EXPECT_EQ(UnitsIn("M L-1 T-2", "si"), "kg m-1 s-2");
  EXPECT_EQ(UnitsIn("1", "cgs"), "");
  EXPECT_EQ(UnitsIn("L T-1", ""), "L T-1");
  EXPECT_THROW(UnitsIn("L", "imperial"), InvalidParameter);
  EXPECT_NO_THROW(CheckFormatVersion("a.h5", kResultsFormatVersion));
  try {
    CheckFormatVersion("a.h5", kResultsFormatVersion + 1);
    FAIL() << "a newer version must be refused";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("version " + std::to_string(kResultsFormatVersion + 1)));
  }
}

TEST(FieldsXdmf, KeepsGridNamesAndAddsTheParticles) {
  const Grid g{8, 6, 0.125, 0.0, 0.0};
  const std::string text = FieldsXdmfText(
      g, {{"fields/snap_000000.h5", 0.0, 2, true}, {"fields/snap_000010.h5", 0.25, 2, false}},
      false);
  EXPECT_EQ(text.find("Name=\"step\""), std::string::npos);
  // One temporal collection per grid, the uniform grids named as their collection at every time.
  EXPECT_THAT(text, HasSubstr("<Grid Name=\"particles\" GridType=\"Collection\" "
                              "CollectionType=\"Temporal\">"));
  EXPECT_THAT(text, HasSubstr("<Grid Name=\"velocity_mesh\" GridType=\"Collection\" "
                              "CollectionType=\"Temporal\">"));
  EXPECT_THAT(text, HasSubstr("TopologyType=\"Polyvertex\" NumberOfElements=\"2\""));
  EXPECT_THAT(text, HasSubstr("Dimensions=\"2 3\" NumberType=\"Float\" Precision=\"8\" "
                              "Format=\"HDF\">fields/snap_000010.h5:/particles/position_xyz"));
  EXPECT_THAT(text, HasSubstr("fields/snap_000000.h5:/particles/angle"));
  EXPECT_EQ(text.find("fields/snap_000010.h5:/particles/angle"), std::string::npos);
  EXPECT_THAT(text, HasSubstr("fields/snap_000010.h5:/particles/radius"));
  EXPECT_EQ(FieldsXdmfText(g, {{"a.h5", 0.0}}, false).find("particles"), std::string::npos);
}

TEST(FieldsXdmf, NamesEverySnapshotWithTheMeshes) {
  const Grid g{8, 6, 0.125, 0.5, -1.0};  // an origin off zero shows the order z, y, x
  const std::string text =
      FieldsXdmfText(g, {{"fields/snap_000000.h5", 0.0}, {"fields/snap_000010.h5", 0.25}}, true);
  EXPECT_THAT(text, HasSubstr("CollectionType=\"Temporal\""));
  // One layer in the X-Y plane: 3DCoRectMesh "1 ny+1 nx+1", ORIGIN_DXDYDZ z first; the pressure
  // mesh has 2h.
  EXPECT_THAT(text, HasSubstr("TopologyType=\"3DCoRectMesh\" Dimensions=\"1 7 9\""));
  EXPECT_THAT(text, HasSubstr("TopologyType=\"3DCoRectMesh\" Dimensions=\"1 4 5\""));
  EXPECT_THAT(text, HasSubstr("GeometryType=\"ORIGIN_DXDYDZ\""));
  EXPECT_THAT(text, HasSubstr(">0 -1 0.5</DataItem>"));
  EXPECT_THAT(text, HasSubstr(">1 0.125 0.125</DataItem>"));
  EXPECT_THAT(text, HasSubstr(">1 0.25 0.25</DataItem>"));
  EXPECT_THAT(text, HasSubstr("AttributeType=\"Vector\""));
  EXPECT_THAT(text, HasSubstr("Dimensions=\"1 7 9 3\" NumberType=\"Float\" Precision=\"8\" "
                              "Format=\"HDF\">fields/snap_000010.h5:/velocity"));
  EXPECT_EQ(text.find("JOIN"), std::string::npos);
  EXPECT_THAT(text, HasSubstr("fields/snap_000000.h5:/u"));
  EXPECT_THAT(text, HasSubstr("fields/snap_000010.h5:/trA"));
  EXPECT_THAT(text, HasSubstr("fields/snap_000010.h5:/p"));
  EXPECT_THAT(text, HasSubstr("<Time Value=\"0.25\"/>"));
  // Balanced elements: every opened Grid, Attribute and DataItem is closed.
  auto count = [&](const std::string& s) {
    std::size_t n = 0;
    for (std::size_t at = text.find(s); at != std::string::npos; at = text.find(s, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("<Grid "), count("</Grid>"));
  EXPECT_EQ(count("<Attribute "), count("</Attribute>"));
  EXPECT_EQ(count("<DataItem "), count("</DataItem>"));
  EXPECT_EQ(FieldsXdmfText(g, {{"a.h5", 0.0}}, false).find("trA"), std::string::npos);
}

TEST(ParticleHistory, AppendsReadsAndCutsBackOnResume) {
  const std::string dir = FreshDir("particles");
  const std::string path = dir + "/particles.h5";
  FlowState s = RandomState(SmallGrid(), false, 3, 4);
  {
    auto w = ParticleHistoryWriter::Create(path, s);
    for (long n = 0; n < 100; ++n) {  // more than one chunk of 64 records
      s.step = n;
      s.time = n * 0.5;
      s.particles[2].position.x() = static_cast<double>(n);
      s.particles[1].torque = -static_cast<double>(n);
      w->Append(s, {0.5 * n, -0.5 * n, 1.0});
    }
    EXPECT_EQ(w->records(), 100u);
  }
  ParticleHistory h = ReadParticleHistory(path);
  ASSERT_EQ(h.records, 100u);
  ASSERT_EQ(h.particles, 3u);
  EXPECT_EQ(h.position.size(), 100u * 3 * 2);
  EXPECT_EQ(h.torque.size(), 100u * 3);
  EXPECT_EQ(h.id, (std::vector<std::int64_t>{0, 1, 2}));
  EXPECT_EQ(h.time[99], 49.5);
  EXPECT_EQ(h.step[70], 70);
  EXPECT_EQ(h.position[(70 * 3 + 2) * 2], 70.0);
  EXPECT_EQ(h.torque[70 * 3 + 1], -70.0);
  EXPECT_TRUE(SameBits(h.angular_velocity[5], s.particles[0].angular_velocity));
  EXPECT_TRUE(SameBits(h.force[2 * 3 * 4], -0.0));
  EXPECT_EQ(h.format_version, kResultsFormatVersion);
  ASSERT_EQ(h.angle.size(), 100u * 3);
  EXPECT_EQ(h.angle[70 * 3 + 1], -35.0);
  EXPECT_THROW(ParticleHistoryWriter::Create(dir + "/other.h5", s)->Append(s), Error);  // no angles

  {
    auto w = ParticleHistoryWriter::Resume(path, 59);
    EXPECT_EQ(w->records(), 60u);
    s.step = 60;
    s.time = 1234.0;
    w->Append(s, {1.0, 2.0, 3.0});
  }
  h = ReadParticleHistory(path);
  ASSERT_EQ(h.records, 61u);
  EXPECT_EQ(h.step[59], 59);
  EXPECT_EQ(h.step[60], 60);
  EXPECT_EQ(h.time[60], 1234.0);
}

TEST(ParticleHistory, NoParticlesStillRecordsTime) {
  const std::string dir = FreshDir("particles_none");
  FlowState s = RandomState(SmallGrid(), false, 0, 5);
  {
    auto w = ParticleHistoryWriter::Create(dir + "/p.h5", s);
    w->Append(s);
    w->Append(s);
  }
  const ParticleHistory h = ReadParticleHistory(dir + "/p.h5");
  EXPECT_EQ(h.records, 2u);
  EXPECT_EQ(h.particles, 0u);
  EXPECT_TRUE(h.position.empty());
}

StepReport Report(long step) {
  StepReport r;
  r.step = step;
  r.time = step * 0.1;
  r.wall_seconds = 0.001;
  r.Set("stokes_iterations", 10.0 + step);
  r.Set("divergence", 1e-9);
  return r;
}

TEST(Diagnostics, HeaderFromTheFirstReportAndOneRowPerStep) {
  const std::string dir = FreshDir("diagnostics");
  const std::string path = dir + "/diagnostics.csv";
  {
    DiagnosticsWriter w(path);
    for (long n = 1; n <= 10; ++n) w.Append(Report(n));
  }
  DiagnosticsTable t = ReadDiagnostics(path);
  EXPECT_EQ(t.header, (std::vector<std::string>{"step", "time", "wall_seconds", "stokes_iterations",
                                                "divergence"}));
  ASSERT_EQ(t.rows.size(), 10u);
  EXPECT_EQ(t.rows[4][0], 5.0);
  EXPECT_EQ(t.rows[4][1], 0.5);
  EXPECT_EQ(t.rows[4][t.Column("stokes_iterations")], 15.0);
  {
    DiagnosticsWriter w(path, 6);
    w.Append(Report(7));
  }
  t = ReadDiagnostics(path);
  ASSERT_EQ(t.rows.size(), 7u);
  EXPECT_EQ(t.rows[6][0], 7.0);
  EXPECT_EQ(t.header.size(), 5u);
}

TEST(Checkpoint, RoundTripsEveryFieldBitForBit) {
  const std::string dir = FreshDir("checkpoint");
  const Grid g = SmallGrid();
  FlowState s = RandomState(g, true, 3, 6);
  s.particles[0].multiplier.clear();  // an empty multiplier vector survives too
  s.u[3] = std::numeric_limits<double>::denorm_min();
  s.v[4] = -0.0;
  const std::string path = dir + "/checkpoint.h5";
  WriteCheckpoint(path, s, "scene text");
  EXPECT_FALSE(fs::exists(TemporaryPath(path)));
  const Checkpoint c = ReadCheckpoint(path);
  EXPECT_EQ(c.scene_text, "scene text");
  EXPECT_EQ(c.state.step, s.step);
  EXPECT_TRUE(SameBits(c.state.time, s.time));
  ExpectSameBits(c.state.u, s.u);
  ExpectSameBits(c.state.v, s.v);
  ExpectSameBits(c.state.p, s.p);
  ExpectSameBits(c.state.a11, s.a11);
  ExpectSameBits(c.state.a12, s.a12);
  ExpectSameBits(c.state.a22, s.a22);
  ExpectSameBits(c.state.d11, s.d11);
  ExpectSameBits(c.state.d12, s.d12);
  ExpectSameBits(c.state.d22, s.d22);
  ASSERT_EQ(c.state.particles.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const ParticleState& a = c.state.particles[i];
    const ParticleState& b = s.particles[i];
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.motion, b.motion);
    EXPECT_TRUE(SameBits(a.position.x(), b.position.x()) &&
                SameBits(a.position.y(), b.position.y()));
    EXPECT_TRUE(SameBits(a.velocity.x(), b.velocity.x()) &&
                SameBits(a.velocity.y(), b.velocity.y()));
    EXPECT_TRUE(SameBits(a.force.x(), b.force.x()) && SameBits(a.force.y(), b.force.y()));
    EXPECT_TRUE(SameBits(a.angular_velocity, b.angular_velocity));
    EXPECT_TRUE(SameBits(a.torque, b.torque));
    EXPECT_TRUE(SameBits(a.radius, b.radius));
    EXPECT_TRUE(SameBits(a.density, b.density));
    ExpectSameBits(a.multiplier, b.multiplier);
  }
}

TEST(Checkpoint, NewtonianStateHasNoConformation) {
  const std::string dir = FreshDir("checkpoint_newtonian");
  const FlowState s = RandomState(SmallGrid(), false, 0, 7);
  WriteCheckpoint(dir + "/c.h5", s, "");
  const Checkpoint c = ReadCheckpoint(dir + "/c.h5");
  EXPECT_TRUE(c.state.a11.empty());
  EXPECT_TRUE(c.state.particles.empty());
  ExpectSameBits(c.state.p, s.p);
  EXPECT_THROW(ReadCheckpoint(dir + "/absent.h5"), Error);
}

// A viscoelastic run under the default devss (the viscosity rule's channel and disk at lambda =
// 1e-3, where the devss share w = 0.91) stopped after 10 steps, written to a checkpoint and read
// back into a new Simulation, goes on as the run that was not stopped: the strain rate D_h of
// FlowState::d11, d12, d22 is part of the state. A checkpoint without it is refused.
TEST(Checkpoint, ViscoelasticRunResumesBitForBit) {
  const std::string dir = FreshDir("checkpoint_devss");
  Params p = testing::ChannelWithFixedDisk(16, 2e-3, 1e-3, 0.59);
  p.time.end = 20 * p.time.dt;
  ASSERT_EQ(p.fluid.stress_splitting, StressSplitting::kDevss);
  Simulation whole(p);
  whole.Run();
  Simulation first(p);
  for (int n = 0; n < 10; ++n) first.Step();
  WriteCheckpoint(dir + "/c.h5", first.state(), "");
  const Checkpoint c = ReadCheckpoint(dir + "/c.h5");
  ASSERT_EQ(c.state.d11.size(), first.grid().NodeCount());
  Simulation resumed(p);
  resumed.Restore(c.state);
  resumed.Run();
  for (const auto& [a, b] : {std::pair{&whole.state().u, &resumed.state().u},
                             std::pair{&whole.state().a12, &resumed.state().a12},
                             std::pair{&whole.state().d12, &resumed.state().d12}}) {
    ExpectSameBits(*b, *a);
  }
  EXPECT_TRUE(
      SameBits(resumed.state().particles[0].force.x(), whole.state().particles[0].force.x()));
  FlowState without = c.state;
  without.d11.clear();
  without.d12.clear();
  without.d22.clear();
  Simulation refused(p);
  EXPECT_THROW(refused.Restore(without), InvalidParameter);
}

// ResultsWriter driven by hand (no Simulation): snapshots at steps 0, 4, 8; checkpoint at step 5;
// resume drops the step-8 snapshot and the rows after step 5.
TEST(ResultsWriter, ResumeCutsBackToTheCheckpoint) {
  const std::string dir = FreshDir("writer");
  Params params = ParseScene(
      "[domain]\nsize = [1.0, 0.75]\nh = 0.125\n[time]\ndt = 0.1\nend = 1.0\n"
      "[output]\ncheckpoint_every = 0.5\nfields_every = 0.4\nparticles_every = 0.0\n"
      "[[particles]]\ncenter = [0.5, 0.4]\ndensity = 2.0\n"
      "[particle_mesh]\nh = 0.1\n");  // at most the disk's radius (a ring mesh that resolves it)
  const Grid g{8, 6, 0.125, 0.0, 0.0};
  FlowState s = RandomState(g, false, 1, 8);
  s.step = 0;
  s.time = 0.0;
  std::vector<long> checkpoints;
  {
    auto w = ResultsWriter::Start(dir, params, g, s);
    w->SetCheckpointCallback([&](long step, double, const std::string& file) {
      checkpoints.push_back(step);
      EXPECT_EQ(file, "checkpoint.h5");
    });
    w->OnParticles(s);
    w->OnSnapshot(s);
    for (long n = 1; n <= 9; ++n) {
      s.step = n;
      s.time = n * 0.1;
      s.u[0] = static_cast<double>(n);
      w->OnStep(s, Report(n));
      w->OnParticles(s);
      if (n % 4 == 0) w->OnSnapshot(s);
      w->OnStepEnd(s);
    }
    EXPECT_EQ(w->last_report().step, 9);
    EXPECT_EQ(w->last_report().Get("stokes_iterations"), 19.0);
    w->Finish();
  }
  EXPECT_EQ(checkpoints, (std::vector<long>{5}));
  EXPECT_TRUE(fs::exists(dir + "/fields/snap_000008.h5"));
  EXPECT_EQ(ParseScene(ReadTextFile(dir + "/scene.toml")).time.end, 1.0);

  const Checkpoint c = ReadCheckpoint(dir + "/checkpoint.h5");
  EXPECT_EQ(c.state.step, 5);
  EXPECT_EQ(c.state.u[0], 5.0);
  EXPECT_EQ(c.scene_text, WriteScene(params));
  { auto w = ResultsWriter::Resume(dir, params, g, c.state.step); }
  EXPECT_FALSE(fs::exists(dir + "/fields/snap_000008.h5"));
  EXPECT_TRUE(fs::exists(dir + "/fields/snap_000004.h5"));
  const std::string xmf = ReadTextFile(dir + "/fields.xmf");
  EXPECT_THAT(xmf, HasSubstr("fields/snap_000004.h5"));
  EXPECT_EQ(xmf.find("snap_000008"), std::string::npos);
  EXPECT_EQ(ReadDiagnostics(dir + "/diagnostics.csv").rows.size(), 5u);
  const ParticleHistory h = ReadParticleHistory(dir + "/particles.h5");
  EXPECT_EQ(h.records, 6u);  // the initial record and steps 1..5
  EXPECT_EQ(h.step.back(), 5);
}

// The writer writes each particle's angle, the engine's (ParticleState::angle, integrated by the
// corrector: particles/particle_step.h; here set as the engine would for omega = 2 + 10 t), with
// every record, snapshot and checkpoint, and a resumed writer goes on from the checkpoint's angle.
TEST(ResultsWriter, WritesTheEnginesAngleAndResumesIt) {
  const std::string dir = FreshDir("writer_angle");
  Params params = ParseScene(
      "[domain]\nsize = [1.0, 0.75]\nh = 0.125\n[time]\ndt = 0.1\nend = 1.0\n"
      "[output]\ncheckpoint_every = 0.5\nfields_every = 0.3\nparticles_every = 0.2\n"
      "[[particles]]\ncenter = [0.5, 0.4]\ndensity = 2.0\n"
      "[particle_mesh]\nh = 0.1\n");  // at most the disk's radius (a ring mesh that resolves it)
  const Grid g{8, 6, 0.125, 0.0, 0.0};
  FlowState s = RandomState(g, false, 1, 9);
  const auto omega = [](double t) { return 2.0 + 10.0 * t; };  // angle 2t + 5t^2
  const auto run = [&](ResultsWriter& w, long from, long to) {
    for (long n = from; n <= to; ++n) {
      s.step = n;
      s.time = n * 0.1;
      s.particles[0].angular_velocity = omega(s.time);
      s.particles[0].angle = 2.0 * s.time + 5.0 * s.time * s.time;
      w.OnStep(s, Report(n));
      if (n % 2 == 0) w.OnParticles(s);
      if (n % 3 == 0) w.OnSnapshot(s);
      w.OnStepEnd(s);
    }
  };
  s.step = 0;
  s.time = 0.0;
  s.particles[0].angular_velocity = omega(0.0);
  {
    auto w = ResultsWriter::Start(dir, params, g, s);
    w->OnParticles(s);
    w->OnSnapshot(s);
    run(*w, 1, 7);
  }
  const FieldSnapshot at6 = ReadFieldSnapshot(dir + "/fields/snap_000006.h5");
  EXPECT_NEAR(at6.particles.angle.at(0), 2.0 * 0.6 + 5.0 * 0.36, 1e-12);
  EXPECT_EQ(at6.scene_text, WriteScene(params));
  EXPECT_NEAR(ReadCheckpoint(dir + "/checkpoint.h5").particle_angles.at(0), 1.0 + 1.25, 1e-12);
  {
    auto w = ResultsWriter::Resume(dir, params, g, 5);
    EXPECT_NEAR(w->particle_angles().at(0), 1.0 + 1.25, 1e-12);
    s.particles[0].angular_velocity = omega(0.5);
    run(*w, 6, 10);
    EXPECT_NEAR(w->particle_angles().at(0), 2.0 + 5.0, 1e-12);
  }
  const ParticleHistory h = ReadParticleHistory(dir + "/particles.h5");
  ASSERT_EQ(h.angle.size(), h.records);
  for (std::size_t r = 0; r < h.records; ++r)
    EXPECT_NEAR(h.angle[r], 2.0 * h.time[r] + 5.0 * h.time[r] * h.time[r], 1e-12) << r;
  EXPECT_EQ(h.scene_text, WriteScene(params));
  const std::string xmf = ReadTextFile(dir + "/fields.xmf");
  EXPECT_THAT(xmf, HasSubstr("fields/snap_000009.h5:/particles/angle"));
}

}  // namespace
}  // namespace dlmfd
