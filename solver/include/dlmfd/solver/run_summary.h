// summary.json of the results directory (design.md 3.2, docs/results.md): how a run ended and its
// final state. The solver writes it once, when the run ends; the daemon reads it (the reason of a
// failed run). This header is the one definition of the file, writer and reader.
//
// Keys, in this order: status (completed | failed | cancelled), reason, exit_code, steps, time,
// end_time, wall_seconds, ms_per_step, resumed_from_step, title, version, then the statistics of
// the whole run (dlmfd/io/run_statistics.h): fall_window [t_a, t_b], fall_speed, diameter, min_gap,
// min_wall_gap, max_trA, min_eig_A, reynolds, deborah, mach, elasticity; particles [{id, radius,
// position, angle, velocity, angular_velocity, force, torque, fall_speed}], diagnostics {the last
// StepReport's columns},
// warnings [{setting, value, allowed, key, current, suggested, source}] (the scene's settings
// outside the accuracy envelope, dlmfd/scene/accuracy_envelope.h; a summary without the key, from
// an older solver, reads as none; the statistics and the particles' radius and fall_speed of an
// older solver read as NaN, so does a particle's angle), numerics [{key, value, rule, numbers
// {name: value}}] (what each "auto" of the scene became, dlmfd/scene/auto_coupling.h; written only
// when there is one, and absent reads as none). One key per line, one line per particle. Integers
// stay JSON integers; a double is written as the shortest text that reads back as the same double
// (an integral one without ".0"); non-finite numbers are written as null (JSON has no NaN) and read
// back as NaN. Written through a temporary file (dlmfd/io/atomic_file.h).
#pragma once

#include <array>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace dlmfd::solver {

// The file name inside a results directory.
inline constexpr const char* kRunSummaryFile = "summary.json";

struct RunSummary {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  struct Particle {
    long id = 0;
    double radius = kNone;
    std::array<double, 2> position{};
    double angle = kNone;  // theta, the body's x axis from the domain's (radians, unwrapped)
    std::array<double, 2> velocity{};
    double angular_velocity = 0.0;
    std::array<double, 2> force{};  // what the fluid exerts over the last step
    double torque = 0.0;
    double fall_speed = kNone;  // mean speed along gravity over the fall window
  };

  std::string status;  // completed, failed, cancelled
  std::string reason;
  int exit_code = 0;
  long steps = 0;  // the step reached
  double time = 0.0;
  double end_time = 0.0;
  double wall_seconds = 0.0;    // of stepping in this process
  double ms_per_step = 0.0;     // over the steps of this process
  long resumed_from_step = -1;  // -1: not resumed
  std::string title;
  std::string version;
  // The whole run (dlmfd/io/run_statistics.h); NaN where undefined.
  std::array<double, 2> fall_window{kNone, kNone};
  double fall_speed = kNone;  // U: mean over the free particles
  double diameter = kNone;    // D: mean over the free particles
  double min_gap = kNone, min_wall_gap = kNone;
  double max_trA = kNone, min_eig_A = kNone;
  double reynolds = kNone, deborah = kNone, mach = kNone, elasticity = kNone;
  std::vector<Particle> particles;
  std::vector<std::pair<std::string, double>> diagnostics;
  // A setting outside the accuracy envelope: which key to change, and to what.
  struct Warning {
    std::string setting;  // "nu dt / h^2"
    double value = 0.0;
    std::string allowed;    // "<= 0.195"
    std::string key;        // the scene key to change
    std::string current;    // its value in the scene
    std::string suggested;  // a value that satisfies the bound
    std::string source;     // where the bound was measured
  };
  std::vector<Warning> warnings;
  // What an "auto" of the scene became: the key, the value chosen, the rule that chose it and
  // the dimensionless numbers the rule read.
  struct Choice {
    std::string key;    // "splitting.constraint"
    std::string value;  // "incremental"
    std::string rule;
    std::vector<std::pair<std::string, double>> numbers;
  };
  std::vector<Choice> numerics;
};

// A summary.json that cannot be read or does not have the contract's shape.
class RunSummaryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string RunSummaryJson(const RunSummary& summary);
// Throws RunSummaryError when the text is not a summary (keys missing or of the wrong type).
RunSummary ParseRunSummary(const std::string& json);

// Writes through a temporary file; throws dlmfd::Error when the file cannot be written.
void WriteRunSummary(const std::string& path, const RunSummary& summary);
// Throws RunSummaryError when the file cannot be read or parsed.
RunSummary ReadRunSummary(const std::string& path);

}  // namespace dlmfd::solver
