// A solver's event (dlmfd.v1.SolverEvent, solver/) as the Watch event the daemon publishes for it
// (dlmfd.v1.WatchEvent), with the lane and step that order it against a resumed solver's events
// (watch_log.h) and the progress it reports. Started and progress events become Progress, a
// snapshot gains its physical size (nx h by ny h), a checkpoint and the end become log lines.
#pragma once

#include <cstdint>
#include <optional>

#include "dlmfd/v1/events.pb.h"
#include "dlmfd/v1/jobs.pb.h"
#include "watch_log.h"

namespace dlmfd::server {

struct PublishedSolverEvent {
  v1::WatchEvent event;
  LogOrigin origin;  // lane and step; the caller sets where it was read
  // Started, progress, finished: where the run is (step, time, end_time; end_time 0 for the end).
  bool reports_progress = false;
  int64_t step = 0;
  double time = 0, end_time = 0;
};

// Nothing for an event kind the daemon does not publish.
std::optional<PublishedSolverEvent> PublishedEventOf(const v1::SolverEvent& in);

}  // namespace dlmfd::server
