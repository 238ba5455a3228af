// Clock: the service's time, injected (Scheduler, EventHub, JobsService, WallTimeLimit) so that a
// test of what depends on time passing sets the time rather than waits for it
// (tests/server/support/manual_clock.h). Now() is wall time in seconds since the epoch: the
// store's created, started and finished times, the wall_time of Watch events, a running job's
// elapsed time. WaitUntil blocks a thread on its condition variable until the predicate holds or
// the clock reaches a deadline.
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>

namespace dlmfd::server {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual double Now() const = 0;
  // Waits on `changed`, whose mutex `lock` holds, until pred() or Now() >= deadline; returns
  // pred(). Whoever makes pred() true notifies `changed` while holding that mutex.
  virtual bool WaitUntil(std::unique_lock<std::mutex>& lock, std::condition_variable& changed,
                         double deadline, const std::function<bool()>& pred) = 0;
};

// The system's clock (std::chrono::system_clock), shared.
Clock& SystemClock();

}  // namespace dlmfd::server
