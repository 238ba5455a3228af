// The solver event stream of dlmfd-solve (proto/dlmfd/v1/events.proto): SolverEvent messages
// framed by EventFileWriter (dlmfd/solver/event_file.h), written to a file descriptor and flushed
// one by one. A write failure (the reader went away) turns the stream off; the results directory
// stays the record.
//
// EventObserver turns Simulation's notifications into `particles` and `snapshot` events (trA, or
// the speed |u| for a Newtonian liquid, at the field cadence) and `progress` events every ~0.5 s.
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/observer.h"
#include "dlmfd/core/params.h"
#include "dlmfd/solver/event_file.h"
#include "dlmfd/v1/events.pb.h"

namespace dlmfd::solver {

class EventStream {
 public:
  // fd < 0: a stream that writes nothing.
  explicit EventStream(int fd);
  ~EventStream();
  EventStream(const EventStream&) = delete;
  EventStream& operator=(const EventStream&) = delete;

  bool enabled() const { return out_ != nullptr; }
  // Sets seq and wall_time, writes and flushes.
  void Send(v1::SolverEvent& event);
  void Log(const std::string& level, const std::string& text);
  // The last event; it carries the process's CPU time and peak memory (getrusage).
  void Finished(const std::string& status, const std::string& reason, long steps, double time,
                int exit_code);

 private:
  std::unique_ptr<EventFileWriter> out_;
  long seq_ = 0;
};

class EventObserver : public Observer {
 public:
  EventObserver(EventStream* stream, const Params& params, const Grid& grid);
  void OnStep(const FlowState& state, const StepReport& report) override;
  void OnParticles(const FlowState& state) override;
  void OnSnapshot(const FlowState& state) override;
  // Starts the wall clock of the progress events (call when stepping begins).
  void Begin(long first_step);

 private:
  EventStream* stream_;
  const Params& params_;
  Grid grid_;
  long total_steps_;
  long first_step_ = 0;
  std::chrono::steady_clock::time_point start_, last_progress_;
  v1::SolverEvent particles_event_, snapshot_event_,
      progress_event_;  // reused: no allocation per step
};

}  // namespace dlmfd::solver
