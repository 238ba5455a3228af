// What `watch` and `submit --wait` print while a job runs.
//   live (stdout is a terminal): one status line rewritten in place -- state, step, simulated time
//     / end, steps/s, ETA, particle count, held to the terminal's width (terminal_width.h) -- with
//     state changes, warnings and gaps on lines above it;
//   plain (a pipe or file): state changes, warnings and a progress line at most every 10 s;
//   json: every event as one JSON line (NDJSON), nothing else on stdout.
#pragma once

#include <chrono>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "terminal_width.h"
#include "watch_session.h"

namespace dlmfd::cli {

enum class PrintMode { kLive, kPlain, kJson };

class ProgressPrinter {
 public:
  ProgressPrinter(std::string job_id, PrintMode mode, std::ostream& out);
  bool OnEvent(const v1::WatchEvent& event);
  void OnReconnect(const grpc::Status& status, double delay);
  // Prints the final line; returns the exit code for the outcome (0 completed, 1 failed/cancelled).
  int Finish(const WatchOutcome& outcome, const std::string& command);

 private:
  std::vector<LineField> StatusFields() const;
  std::string StatusLine() const;  // every field, for plain output
  void PrintAbove(const std::string& line);
  void Redraw();

  std::string job_id_;
  PrintMode mode_;
  std::ostream& out_;
  std::string state_ = "?";
  std::int64_t step_ = 0;
  double time_ = 0.0;
  double end_time_ = 0.0;
  double steps_per_second_ = 0.0;
  double eta_seconds_ = -1.0;
  int particles_ = -1;
  bool line_shown_ = false;
  std::chrono::steady_clock::time_point last_plain_;
  std::chrono::steady_clock::time_point last_redraw_;
};

}  // namespace dlmfd::cli
