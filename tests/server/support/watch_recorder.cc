#include "watch_recorder.h"

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <set>

namespace dlmfd::testing {

ReconnectingWatcher::ReconnectingWatcher(std::string address, std::string job_id, bool snapshots,
                                         int64_t from_seq)
    : address_(std::move(address)),
      job_id_(std::move(job_id)),
      snapshots_(snapshots),
      from_seq_(from_seq) {
  thread_ = std::thread([this] { Run(); });
}

ReconnectingWatcher::~ReconnectingWatcher() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void ReconnectingWatcher::Run() {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
  int64_t last = from_seq_;
  while (!stop_ && std::chrono::steady_clock::now() < deadline) {
    auto stub =
        v1::Jobs::NewStub(grpc::CreateChannel(address_, grpc::InsecureChannelCredentials()));
    grpc::ClientContext context;
    v1::WatchRequest request;
    request.set_job_id(job_id_);
    request.set_from_seq(last);
    request.set_include_snapshots(snapshots_);
    request.set_snapshot_max_width(9);
    request.set_snapshot_max_height(9);
    ++connections_;
    auto reader = stub->Watch(&context, request);
    v1::WatchEvent event;
    bool final_state = false;
    while (reader->Read(&event)) {
      if (event.has_state() && event.state().state() >= v1::COMPLETED) final_state = true;
      if (event.seq() == 0 && !event.has_gap()) continue;  // the summary of the current state
      if (event.seq() > last) last = event.seq();
      if (event.has_gap()) last = std::max(last, event.gap().to_seq());
      std::lock_guard lock(mutex_);
      events_.push_back(event);
    }
    const grpc::Status status = reader->Finish();
    if (final_state && status.ok()) {
      done_ = true;
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

void ReconnectingWatcher::Join() {
  if (thread_.joinable()) thread_.join();
  EXPECT_TRUE(done_.load()) << "watcher of " << job_id_ << " did not see the final state";
}

std::vector<v1::WatchEvent> ReconnectingWatcher::Events() const {
  std::lock_guard lock(mutex_);
  return events_;
}

size_t ReconnectingWatcher::Count() const {
  std::lock_guard lock(mutex_);
  return events_.size();
}

std::vector<v1::WatchEvent> ReferenceEvents(v1::Jobs::Stub& stub, const std::string& job_id) {
  grpc::ClientContext context;
  v1::WatchRequest request;
  request.set_job_id(job_id);
  request.set_include_snapshots(true);
  request.set_snapshot_max_width(9);
  request.set_snapshot_max_height(9);
  auto reader = stub.Watch(&context, request);
  std::vector<v1::WatchEvent> events;
  v1::WatchEvent event;
  bool head = true;
  while (reader->Read(&event)) {
    if (head) {
      EXPECT_EQ(event.seq(), 0) << "the first message is the summary, numbered 0";
      EXPECT_TRUE(event.has_state());
      head = false;
      continue;
    }
    events.push_back(event);
  }
  EXPECT_TRUE(reader->Finish().ok());
  std::map<std::string, int64_t> last_step;
  for (size_t i = 0; i < events.size(); ++i) {
    const v1::WatchEvent& e = events[i];
    EXPECT_FALSE(e.has_gap()) << job_id << ": " << e.DebugString();
    EXPECT_EQ(e.seq(), static_cast<int64_t>(i + 1)) << job_id << ": numbers with a hole";
    if (e.has_state()) {
      EXPECT_EQ(e.state().job().last_seq(), e.seq());
    }
    auto check_step = [&](const char* lane, int64_t step) {
      auto it = last_step.find(lane);
      if (it != last_step.end()) {
        EXPECT_GT(step, it->second) << job_id << ": " << lane << " of step " << step
                                    << " sent again (seq " << e.seq() << ")";
      }
      last_step[lane] = step;
    };
    if (e.has_particles()) check_step("particles", e.particles().step());
    if (e.has_progress()) check_step("progress", e.progress().step());
    if (e.has_snapshot()) check_step("snapshot", e.snapshot().step());
  }
  return events;
}

void ExpectExactlyOnce(const std::vector<v1::WatchEvent>& reference,
                       const ReconnectingWatcher& watcher) {
  const std::string who = watcher.job_id() + " (from " + std::to_string(watcher.from_seq()) +
                          (watcher.snapshots() ? ", snapshots)" : ")");
  std::map<int64_t, const v1::WatchEvent*> by_seq;
  for (const auto& e : reference) by_seq[e.seq()] = &e;
  std::set<int64_t> covered;
  int64_t previous = watcher.from_seq();
  for (const v1::WatchEvent& e : watcher.Events()) {
    if (e.has_gap()) {
      ASSERT_TRUE(watcher.snapshots()) << who << ": " << e.DebugString();
      for (int64_t seq = e.gap().from_seq(); seq <= e.gap().to_seq(); ++seq) {
        ASSERT_TRUE(by_seq.count(seq) && by_seq[seq]->has_snapshot())
            << who << ": a Gap over event " << seq
            << " that is not a snapshot: " << e.DebugString();
        EXPECT_TRUE(covered.insert(seq).second) << who << ": " << seq << " twice";
      }
      continue;
    }
    EXPECT_GT(e.seq(), previous) << who << ": out of order or repeated";
    previous = e.seq();
    EXPECT_TRUE(covered.insert(e.seq()).second) << who << ": " << e.seq() << " twice";
    auto it = by_seq.find(e.seq());
    ASSERT_NE(it, by_seq.end()) << who << ": " << e.seq() << " is no event of the job";
    EXPECT_EQ(e.SerializeAsString(), it->second->SerializeAsString())
        << who << ": event " << e.seq() << " differs:\n"
        << e.DebugString() << "against\n"
        << it->second->DebugString();
  }
  for (const auto& e : reference) {
    if (e.seq() <= watcher.from_seq()) continue;
    if (e.has_snapshot() && !watcher.snapshots()) {
      EXPECT_FALSE(covered.count(e.seq())) << who << ": got snapshot " << e.seq();
      continue;
    }
    EXPECT_TRUE(covered.count(e.seq()))
        << who << ": missed event " << e.seq() << " " << e.DebugString();
  }
}

Watchers WatchersOf(const std::string& address, const std::vector<std::string>& job_ids) {
  Watchers watchers;
  for (const std::string& id : job_ids) {
    watchers.push_back(std::make_unique<ReconnectingWatcher>(address, id, false));
    watchers.push_back(std::make_unique<ReconnectingWatcher>(address, id, true));
  }
  return watchers;
}

size_t EventsSeen(const Watchers& watchers) {
  size_t count = 0;
  for (const auto& w : watchers) count += w->Count();
  return count;
}

void ExpectExactlyOnce(const std::vector<v1::WatchEvent>& reference, const Watchers& watchers,
                       const std::string& job_id) {
  for (const auto& w : watchers) {
    if (w->job_id() == job_id) ExpectExactlyOnce(reference, *w);
  }
}

size_t Reconnected(const Watchers& watchers) {
  size_t reconnected = 0;
  for (const auto& w : watchers) reconnected += w->Connections() > 1;
  return reconnected;
}

}  // namespace dlmfd::testing
