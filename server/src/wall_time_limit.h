// WallTimeLimit: calls `on_over` once when a solver start has run `seconds` of wall time (0:
// never) on `clock` (clock.h), from a thread of its own; End() stops the clock and tells whether
// the limit was reached.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>

#include "clock.h"

namespace dlmfd::server {

class WallTimeLimit {
 public:
  WallTimeLimit(int64_t seconds, std::function<void()> on_over, Clock& clock = SystemClock()) {
    if (seconds <= 0) return;
    const double deadline = clock.Now() + static_cast<double>(seconds);
    thread_ = std::thread([this, &clock, deadline, on_over = std::move(on_over)] {
      std::unique_lock lock(mutex_);
      if (!clock.WaitUntil(lock, ended_changed_, deadline, [this] { return ended_; })) {
        over_ = true;
        on_over();
      }
    });
  }
  ~WallTimeLimit() { End(); }
  WallTimeLimit(const WallTimeLimit&) = delete;
  WallTimeLimit& operator=(const WallTimeLimit&) = delete;

  // Stops the clock; true when the limit was reached before.
  bool End() {
    {
      std::lock_guard lock(mutex_);
      ended_ = true;
    }
    ended_changed_.notify_all();
    if (thread_.joinable()) thread_.join();
    std::lock_guard lock(mutex_);
    return over_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable ended_changed_;
  bool ended_ = false, over_ = false;
  std::thread thread_;
};

}  // namespace dlmfd::server
