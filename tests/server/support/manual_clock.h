// ManualClock: a Clock (server/src/clock.h) that stands still until the test moves it, so that a
// test of what depends on time passing sets the time rather than waits for it.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>

#include "clock.h"

namespace dlmfd::testing {

class ManualClock final : public server::Clock {
 public:
  explicit ManualClock(double start = 1.0e9)
      : now_(start) {}
  double Now() const override { return now_.load(); }
  void Advance(double seconds) { now_.store(now_.load() + seconds); }
  // Looks at the clock again at each wake-up of `changed` and at least every millisecond (a
  // test's Advance notifies nobody); no real time has to pass for the deadline.
  bool WaitUntil(std::unique_lock<std::mutex>& lock, std::condition_variable& changed,
                 double deadline, const std::function<bool()>& pred) override {
    while (!pred()) {
      if (Now() >= deadline) return false;
      changed.wait_for(lock, std::chrono::milliseconds(1));
    }
    return true;
  }

 private:
  std::atomic<double> now_;
};

}  // namespace dlmfd::testing
