#include "clock.h"

#include <chrono>

namespace dlmfd::server {
namespace {

class SystemTime final : public Clock {
 public:
  double Now() const override {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
        .count();
  }
  bool WaitUntil(std::unique_lock<std::mutex>& lock, std::condition_variable& changed,
                 double deadline, const std::function<bool()>& pred) override {
    // The wait is measured on the steady clock: a step of the wall clock does not move it.
    const auto left = std::chrono::duration<double>(deadline - Now());
    const auto until = std::chrono::steady_clock::now() +
                       std::chrono::duration_cast<std::chrono::steady_clock::duration>(left);
    return changed.wait_until(lock, until, pred);
  }
};

}  // namespace

Clock& SystemClock() {
  static SystemTime clock;
  return clock;
}

}  // namespace dlmfd::server
