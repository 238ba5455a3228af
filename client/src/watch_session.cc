// WatchJob: the resuming read loop, and a watchdog thread that turns SIGINT/SIGTERM into a
// cancelled stream (a blocking Read cannot be interrupted any other way).
#include "watch_session.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <mutex>
#include <thread>

#include "job_text.h"

namespace dlmfd::cli {
namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void OnInterrupt(int) { g_interrupted.store(true); }

bool Retryable(grpc::StatusCode code) {
  return code == grpc::StatusCode::UNAVAILABLE || code == grpc::StatusCode::ABORTED ||
         code == grpc::StatusCode::INTERNAL || code == grpc::StatusCode::UNKNOWN ||
         code == grpc::StatusCode::DEADLINE_EXCEEDED;
}

// Cancels the current stream's context once an interrupt arrives.
class InterruptWatchdog {
 public:
  InterruptWatchdog()
      : thread_([this] { Run(); }) {}
  ~InterruptWatchdog() {
    done_.store(true);
    thread_.join();
  }
  void Attach(grpc::ClientContext* context) {
    std::lock_guard<std::mutex> lock(mutex_);
    context_ = context;
  }

 private:
  void Run() {
    while (!done_.load()) {
      if (g_interrupted.load()) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (context_ != nullptr) context_->TryCancel();
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  std::atomic<bool> done_{false};
  std::mutex mutex_;
  grpc::ClientContext* context_ = nullptr;
  std::thread thread_;
};

}  // namespace

WatchOutcome WatchJob(Connection& connection, const WatchOptions& options,
                      const std::function<bool(const v1::WatchEvent&)>& on_event,
                      const std::function<void(const grpc::Status&, double delay)>& on_reconnect) {
  g_interrupted.store(false);
  std::signal(SIGINT, OnInterrupt);
  std::signal(SIGTERM, OnInterrupt);
  InterruptWatchdog watchdog;
  WatchOutcome outcome;
  outcome.last_seq = options.from_seq;
  using Clock = std::chrono::steady_clock;
  auto last_contact = Clock::now();
  double delay = 0.25;
  for (;;) {
    v1::WatchRequest request;
    request.set_job_id(options.job_id);
    request.set_from_seq(outcome.last_seq);
    request.set_include_snapshots(options.include_snapshots);
    request.set_snapshot_max_width(options.snapshot_max_width);
    request.set_snapshot_max_height(options.snapshot_max_height);
    auto context = connection.StreamContext();
    watchdog.Attach(context.get());
    auto reader = connection.jobs().Watch(context.get(), request);
    v1::WatchEvent event;
    bool received = false;
    while (reader->Read(&event)) {
      received = true;
      last_contact = Clock::now();
      delay = 0.25;
      if (event.seq() > outcome.last_seq) outcome.last_seq = event.seq();
      if (event.has_state()) {
        outcome.job = event.state().job();
        outcome.job.set_state(event.state().state());
        if (!event.state().reason().empty()) outcome.job.set_reason(event.state().reason());
        if (IsFinal(event.state().state())) outcome.finished = true;
      }
      if (!on_event(event)) {
        outcome.stopped = true;
        context->TryCancel();
        break;
      }
    }
    const grpc::Status status = reader->Finish();
    watchdog.Attach(nullptr);
    if (g_interrupted.load()) {
      outcome.interrupted = true;
      break;
    }
    if (outcome.stopped || outcome.finished) break;
    if (status.ok() && received) continue;  // ended without a final state: ask again from last_seq
    if (!status.ok() && !Retryable(status.error_code())) {
      outcome.status = status;
      break;
    }
    const double waited = std::chrono::duration<double>(Clock::now() - last_contact).count();
    if (waited + delay > options.reconnect_seconds) {
      outcome.status = status.ok()
                           ? grpc::Status(grpc::StatusCode::UNAVAILABLE, "the stream ended early")
                           : status;
      break;
    }
    if (on_reconnect) on_reconnect(status, delay);
    ++outcome.reconnects;
    for (double slept = 0; slept < delay && !g_interrupted.load(); slept += 0.05) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    if (g_interrupted.load()) {
      outcome.interrupted = true;
      break;
    }
    delay = std::min(delay * 2.0, 4.0);
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  return outcome;
}

}  // namespace dlmfd::cli
