// summary.json of the results directory (design.md 3.2): how the run ended and its final state.
// Keys: status (completed | failed | cancelled), reason, exit_code, steps, time, end_time,
// wall_seconds, ms_per_step, resumed_from_step, particles [{id, position, velocity,
// angular_velocity, force, torque}], diagnostics {the last StepReport's columns}, version, title.
// Written through a temporary file. Non-finite numbers are written as null (JSON has no NaN).
#pragma once

#include <string>
#include <vector>

#include "dlmfd/core/state.h"

namespace dlmfd {

struct RunSummary {
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
  std::vector<ParticleState> particles;
  std::vector<std::pair<std::string, double>> diagnostics;
};

std::string RunSummaryJson(const RunSummary& summary);
void WriteRunSummary(const std::string& path, const RunSummary& summary);

}  // namespace dlmfd
