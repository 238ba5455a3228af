// The contract between dlmfd-solve and whoever runs it (solver/include/dlmfd/solver): the exit
// codes of design.md 3.1, summary.json (the writer's keys, null for non-finite numbers, the reader
// giving back what was written) and the event-file framing (what the writer frames, the reader
// unframes, and a truncated stream ends without a partial event).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "../support/scratch_path.h"
#include "dlmfd/io/atomic_file.h"
#include "dlmfd/solver/event_file.h"
#include "dlmfd/solver/exit_codes.h"
#include "dlmfd/solver/run_summary.h"

namespace dlmfd::solver {
namespace {

using ::testing::HasSubstr;

TEST(ExitCodes, AreTheDocumentedOnes) {
  EXPECT_EQ(kExitCompleted, 0);
  EXPECT_EQ(kExitFailed, 1);
  EXPECT_EQ(kExitInvalid, 2);
  EXPECT_EQ(kExitCancelled, 130);
}

RunSummary FailedRun() {
  RunSummary s;
  s.status = "failed";
  s.reason = "solver \"stokes\" did not converge\n";
  s.exit_code = kExitFailed;
  s.steps = 12;
  s.time = 0.012;
  s.end_time = 1.0;
  s.wall_seconds = 0.25;
  s.ms_per_step = std::numeric_limits<double>::quiet_NaN();
  s.resumed_from_step = 4;
  s.title = "two disks";
  s.version = "0.1.0";
  RunSummary::Particle q;
  q.id = 3;
  q.position = {0.5, 0.25};
  q.angle = -2.5;
  q.velocity = {-0.125, 1e-300};
  q.angular_velocity = 0.1;
  q.force = {std::numeric_limits<double>::infinity(), 2.0};
  q.torque = -3.5;
  s.particles.push_back(q);
  s.diagnostics = {{"stokes_iterations", 11.0}, {"max_trA", 2.0000000000000004}};
  return s;
}

TEST(RunSummary, JsonHasTheContractKeysAndNoNaN) {
  const std::string json = RunSummaryJson(FailedRun());
  for (const char* key : {"\"status\": \"failed\"",
                          "\"reason\": \"solver \\\"stokes\\\" did not converge\\n\"",
                          "\"exit_code\": 1",
                          "\"steps\": 12",
                          "\"time\": 0.012",
                          "\"end_time\"",
                          "\"wall_seconds\"",
                          "\"ms_per_step\": null",
                          "\"resumed_from_step\": 4",
                          "\"title\": \"two disks\"",
                          "\"version\": \"0.1.0\"",
                          "\"particles\": [",
                          "\"id\": 3",
                          "\"position\"",
                          "\"velocity\"",
                          "\"angular_velocity\"",
                          "\"force\"",
                          "\"torque\"",
                          "\"diagnostics\"",
                          "\"stokes_iterations\": 11"}) {
    EXPECT_THAT(json, HasSubstr(key));
  }
  EXPECT_EQ(json.find("nan"), std::string::npos);
  EXPECT_EQ(json.find("inf"), std::string::npos);
  // The contract's order: how the run ended first, the final state after.
  EXPECT_LT(json.find("\"status\""), json.find("\"reason\""));
  EXPECT_LT(json.find("\"version\""), json.find("\"particles\""));
  EXPECT_LT(json.find("\"particles\""), json.find("\"diagnostics\""));
}

// What "auto" chose (numerics) round-trips with its numbers, in order, one line each.
TEST(RunSummary, NumericsChoicesRoundTrip) {
  RunSummary s;
  s.status = "completed";
  s.numerics = {{"splitting.constraint",
                 "paper",
                 "fast particles",
                 {{"nu dt / h^2", 0.0921}, {"U_p dt / h", 1.19136}}}};
  const std::string json = RunSummaryJson(s);
  EXPECT_THAT(json, HasSubstr("\"numerics\": [\n    {\"key\": \"splitting.constraint\", \"value\": "
                              "\"paper\", \"rule\": \"fast particles\", \"numbers\": {\"nu dt / "
                              "h^2\": 0.0921, \"U_p dt / h\": 1.19136}}\n  ]"));
  const RunSummary back = ParseRunSummary(json);
  ASSERT_EQ(back.numerics.size(), 1u);
  EXPECT_EQ(back.numerics[0].key, "splitting.constraint");
  EXPECT_EQ(back.numerics[0].value, "paper");
  EXPECT_EQ(back.numerics[0].rule, "fast particles");
  EXPECT_EQ(back.numerics[0].numbers, s.numerics[0].numbers);
}

// The layout scripts and readers have seen since the first summary: one key per line, one line per
// particle, integral numbers without ".0", the shortest text that reads back for the others.
TEST(RunSummary, TextKeepsTheLayoutOfTheResultsDirectory) {
  RunSummary s;
  s.status = "completed";
  s.steps = 2500;
  s.time = 1.0;
  s.end_time = 1.0;
  s.wall_seconds = 0.1 + 0.2;
  s.ms_per_step = 49.2;
  s.title = "pair";
  s.version = "0.1.0";
  s.fall_window = {0.5, 1.0};
  s.fall_speed = 0.135;
  s.diameter = 0.2;
  s.min_gap = 0.202;
  s.min_wall_gap = 0.9;
  s.max_trA = 3.25;
  s.min_eig_A = 0.5;
  s.reynolds = 0.225;
  s.deborah = 0.945;
  s.mach = 0.5;
  s.elasticity = 4.2;
  RunSummary::Particle q;
  q.radius = 0.1;
  q.position = {0.5, 7.25};
  q.velocity = {-0.0014494669113040463, 1e-05};
  q.angle = 0.75;
  q.fall_speed = 0.125;
  s.particles = {q, q};
  s.particles[1].id = 1;
  s.particles[1].angle = RunSummary::kNone;
  s.particles[1].fall_speed = RunSummary::kNone;
  s.diagnostics = {{"stokes_iterations", 11.0}, {"divergence", 0.0011162864979271413}};
  EXPECT_EQ(
      RunSummaryJson(s),
      "{\n"
      "  \"status\": \"completed\",\n"
      "  \"reason\": \"\",\n"
      "  \"exit_code\": 0,\n"
      "  \"steps\": 2500,\n"
      "  \"time\": 1,\n"
      "  \"end_time\": 1,\n"
      "  \"wall_seconds\": 0.30000000000000004,\n"
      "  \"ms_per_step\": 49.2,\n"
      "  \"resumed_from_step\": -1,\n"
      "  \"title\": \"pair\",\n"
      "  \"version\": \"0.1.0\",\n"
      "  \"fall_window\": [0.5, 1],\n"
      "  \"fall_speed\": 0.135,\n"
      "  \"diameter\": 0.2,\n"
      "  \"min_gap\": 0.202,\n"
      "  \"min_wall_gap\": 0.9,\n"
      "  \"max_trA\": 3.25,\n"
      "  \"min_eig_A\": 0.5,\n"
      "  \"reynolds\": 0.225,\n"
      "  \"deborah\": 0.945,\n"
      "  \"mach\": 0.5,\n"
      "  \"elasticity\": 4.2,\n"
      "  \"particles\": [\n"
      "    {\"id\": 0, \"radius\": 0.1, \"position\": [0.5, 7.25], \"angle\": 0.75, \"velocity\": "
      "[-0.0014494669113040463, 1e-05], \"angular_velocity\": 0, \"force\": [0, 0], \"torque\": 0, "
      "\"fall_speed\": 0.125},\n"
      "    {\"id\": 1, \"radius\": 0.1, \"position\": [0.5, 7.25], \"angle\": null, \"velocity\": "
      "[-0.0014494669113040463, 1e-05], \"angular_velocity\": 0, \"force\": [0, 0], \"torque\": 0, "
      "\"fall_speed\": null}\n"
      "  ],\n"
      "  \"diagnostics\": {\"stokes_iterations\": 11, \"divergence\": 0.0011162864979271413},\n"
      "  \"warnings\": []\n"
      "}\n");
  s.particles.clear();
  EXPECT_THAT(RunSummaryJson(s), HasSubstr("  \"particles\": [],\n"));
  // One line per accuracy warning, as per particle.
  s.warnings = {{"U dt / h", 1.6, "<= 0.64", "time.dt", "0.1", "0.03333333333333333", "(b)"},
                {"D / h (particles.0)", 19.2, ">= 120", "domain.h", "0.01", "0.0015", "(d)"}};
  EXPECT_THAT(RunSummaryJson(s),
              HasSubstr("  \"warnings\": [\n"
                        "    {\"setting\": \"U dt / h\", \"value\": 1.6, \"allowed\": \"<= 0.64\", "
                        "\"key\": \"time.dt\", \"current\": \"0.1\", \"suggested\": "
                        "\"0.03333333333333333\", \"source\": \"(b)\"},\n"
                        "    {\"setting\": \"D / h (particles.0)\", \"value\": 19.2, "));
}

TEST(RunSummary, WarningsReadBackAndAnOlderSummaryHasNone) {
  RunSummary in = FailedRun();
  in.warnings = {{"nu dt / h^2", 0.44236800000000003, "<= 0.195", "time.dt", "0.0004",
                  "0.00013333333333333334", "docs/evidence/work_precision.md (d) dt ladder"}};
  const RunSummary out = ParseRunSummary(RunSummaryJson(in));
  ASSERT_EQ(out.warnings.size(), 1u);
  EXPECT_EQ(out.warnings[0].setting, "nu dt / h^2");
  EXPECT_EQ(out.warnings[0].value, 0.44236800000000003);
  EXPECT_EQ(out.warnings[0].allowed, "<= 0.195");
  EXPECT_EQ(out.warnings[0].key, "time.dt");
  EXPECT_EQ(out.warnings[0].current, "0.0004");
  EXPECT_EQ(out.warnings[0].suggested, "0.00013333333333333334");
  EXPECT_EQ(out.warnings[0].source, "docs/evidence/work_precision.md (d) dt ladder");
  std::string older = RunSummaryJson(FailedRun());
  const auto at = older.find(",\n  \"warnings\": []");
  ASSERT_NE(at, std::string::npos);
  older.erase(at, std::string(",\n  \"warnings\": []").size());
  EXPECT_TRUE(ParseRunSummary(older).warnings.empty());
}

TEST(RunSummary, ReadsBackWhatWasWritten) {
  const RunSummary in = FailedRun();
  const RunSummary out = ParseRunSummary(RunSummaryJson(in));
  EXPECT_EQ(out.status, in.status);
  EXPECT_EQ(out.reason, in.reason);
  EXPECT_EQ(out.exit_code, in.exit_code);
  EXPECT_EQ(out.steps, in.steps);
  EXPECT_EQ(out.time, in.time);
  EXPECT_EQ(out.end_time, in.end_time);
  EXPECT_EQ(out.wall_seconds, in.wall_seconds);
  EXPECT_TRUE(std::isnan(out.ms_per_step));
  EXPECT_EQ(out.resumed_from_step, in.resumed_from_step);
  EXPECT_EQ(out.title, in.title);
  EXPECT_EQ(out.version, in.version);
  ASSERT_EQ(out.particles.size(), 1u);
  const RunSummary::Particle& p = out.particles[0];
  EXPECT_EQ(p.id, 3);
  EXPECT_EQ(p.position, in.particles[0].position);
  EXPECT_EQ(p.angle, in.particles[0].angle);
  EXPECT_EQ(p.velocity, in.particles[0].velocity);  // shortest round-trip text: bit for bit
  EXPECT_EQ(p.angular_velocity, in.particles[0].angular_velocity);
  EXPECT_TRUE(std::isnan(p.force[0]));  // written as null: the number is gone, not its place
  EXPECT_EQ(p.force[1], 2.0);
  EXPECT_EQ(p.torque, in.particles[0].torque);
  EXPECT_EQ(out.diagnostics, in.diagnostics);
}

// The statistics of the whole run read back bit for bit; an older summary without them reads NaN.
TEST(RunSummary, StatisticsReadBackAndAnOlderSummaryHasNaN) {
  RunSummary in = FailedRun();
  in.fall_window = {12.5, 25.0};
  in.fall_speed = 0.13512345678901234;
  in.diameter = 0.2;
  in.min_gap = 0.0202;
  in.min_wall_gap = 0.7;
  in.max_trA = 31.5;
  in.min_eig_A = 0.01;
  in.reynolds = 0.225;
  in.deborah = 0.945;
  in.mach = 0.46;
  in.elasticity = 4.2;
  in.particles[0].radius = 0.1;
  in.particles[0].fall_speed = 0.14;
  const RunSummary out = ParseRunSummary(RunSummaryJson(in));
  EXPECT_EQ(out.fall_window, in.fall_window);
  EXPECT_EQ(out.fall_speed, in.fall_speed);
  EXPECT_EQ(out.diameter, in.diameter);
  EXPECT_EQ(out.min_gap, in.min_gap);
  EXPECT_EQ(out.min_wall_gap, in.min_wall_gap);
  EXPECT_EQ(out.max_trA, in.max_trA);
  EXPECT_EQ(out.min_eig_A, in.min_eig_A);
  EXPECT_EQ(out.reynolds, in.reynolds);
  EXPECT_EQ(out.deborah, in.deborah);
  EXPECT_EQ(out.mach, in.mach);
  EXPECT_EQ(out.elasticity, in.elasticity);
  ASSERT_EQ(out.particles.size(), 1u);
  EXPECT_EQ(out.particles[0].radius, 0.1);
  EXPECT_EQ(out.particles[0].fall_speed, 0.14);
  const RunSummary older = ParseRunSummary(
      "{\"status\": \"completed\", \"reason\": \"\", \"exit_code\": 0, \"steps\": 1, \"time\": 1, "
      "\"end_time\": 1, \"wall_seconds\": 1, \"ms_per_step\": 1, \"resumed_from_step\": -1, "
      "\"title\": \"\", \"version\": \"0.1.0\", \"particles\": [{\"id\": 0, \"position\": [0, 0], "
      "\"velocity\": [0, 0], \"angular_velocity\": 0, \"force\": [0, 0], \"torque\": 0}], "
      "\"diagnostics\": {}}");
  EXPECT_TRUE(std::isnan(older.min_gap));
  EXPECT_TRUE(std::isnan(older.fall_speed));
  EXPECT_TRUE(std::isnan(older.fall_window[0]));
  EXPECT_TRUE(std::isnan(older.particles[0].radius));
  EXPECT_TRUE(std::isnan(older.particles[0].fall_speed));
  EXPECT_TRUE(std::isnan(older.particles[0].angle));
}

TEST(RunSummary, FileRoundTripAndErrors) {
  const std::string dir = dlmfd::testing::ScratchPath("dlmfd_solver_contract");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + kRunSummaryFile;
  WriteRunSummary(path, FailedRun());
  EXPECT_EQ(ReadRunSummary(path).reason, FailedRun().reason);
  EXPECT_THROW(ReadRunSummary(dir + "/absent.json"), RunSummaryError);
  WriteTextAtomically(path, "{\"status\": \"completed\"}");
  EXPECT_THROW(ReadRunSummary(path), RunSummaryError);  // keys missing
  WriteTextAtomically(path, "{\"status\": ");
  EXPECT_THROW(ReadRunSummary(path), RunSummaryError);  // not JSON
}

class Pipe {
 public:
  Pipe() { EXPECT_EQ(pipe(fds_), 0); }
  ~Pipe() {
    CloseWrite();
    close(fds_[0]);
  }
  int read_end() const { return fds_[0]; }
  int write_end() const { return fds_[1]; }
  void CloseWrite() {
    if (fds_[1] >= 0) close(fds_[1]);
    fds_[1] = -1;
  }

 private:
  int fds_[2] = {-1, -1};
};

TEST(EventFile, ReaderGetsWhatTheWriterFramed) {
  Pipe pipe;
  {
    EventFileWriter writer(pipe.write_end());
    v1::SolverEvent e;
    e.set_seq(1);
    e.mutable_started()->set_end_time(2.5);
    EXPECT_TRUE(writer.Write(e));
    e.Clear();
    e.set_seq(2);
    e.mutable_finished()->set_status("completed");
    e.mutable_finished()->set_exit_code(kExitCompleted);
    EXPECT_TRUE(writer.Write(e));
  }
  pipe.CloseWrite();
  EventFileReader reader(pipe.read_end());
  v1::SolverEvent e;
  ASSERT_TRUE(reader.Next(&e));
  EXPECT_EQ(e.seq(), 1);
  EXPECT_EQ(e.started().end_time(), 2.5);
  ASSERT_TRUE(reader.Next(&e));
  EXPECT_EQ(e.seq(), 2);
  EXPECT_FALSE(e.has_started());  // each event replaces the last, never merges into it
  EXPECT_EQ(e.finished().status(), "completed");
  EXPECT_FALSE(reader.Next(&e));
}

TEST(EventFile, TruncatedEventEndsTheStream) {
  Pipe pipe;
  v1::SolverEvent e;
  e.set_seq(7);
  e.mutable_log()->set_text("a line that will be cut");
  const std::string body = e.SerializeAsString();
  const std::string framed = std::string(1, static_cast<char>(body.size())) + body;
  ASSERT_LT(body.size(), 128u);  // one varint byte
  const std::string cut = framed.substr(0, framed.size() - 3);
  ASSERT_EQ(write(pipe.write_end(), cut.data(), cut.size()), static_cast<ssize_t>(cut.size()));
  pipe.CloseWrite();
  EventFileReader reader(pipe.read_end());
  EXPECT_FALSE(reader.Next(&e));
}

}  // namespace
}  // namespace dlmfd::solver
