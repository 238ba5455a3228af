// TSan canary for scripts/tsan.sh: proves that the TSan setup still reports a race in our own
// callback code when gRPC calls it. scripts/tsan.sh compiles this file with the same compiler and
// flags as the daemon (-fsanitize=thread) against build-tsan's generated jobs.grpc.pb.cc, runs it
// with the same preload (scripts/tsan_absl_sync.cc, whose annotations add happens-before edges) and
// TSAN_OPTIONS (scripts/tsan.supp), and requires exactly one data-race report, naming OnWriteDone.
//
// The race: a Jobs.Watch stream served by a write reactor of the same shape as dlmfdd's
// WatchReactor, through the same handler (CallbackServerStreamingHandler<WatchRequest, WatchEvent>,
// compiled into our binary). Its OnWriteDone runs on a gRPC thread, called from
// grpc::internal::CallbackWithSuccessTag::Run after the annotated completion-queue hand-off, and
// increments `g_unguarded`; a thread started before the server increments it once it sees a relaxed
// flag, which gives TSan no happens-before edge. A real race, reported on every run. That the
// setup gives no other report also shows that the canary's own gRPC traffic is clean.
// Exit status: TSan's exitcode (66) when it reported; 0 when it did not (the script then fails);
// 1 when the RPC itself failed.
#include <grpcpp/grpcpp.h>

#include <atomic>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>

#include "dlmfd/v1/jobs.grpc.pb.h"

namespace {

int g_unguarded = 0;                 // incremented by two threads with no synchronisation
std::atomic<bool> g_written{false};  // relaxed only: no happens-before for TSan

class CanaryReactor final : public grpc::ServerWriteReactor<dlmfd::v1::WatchEvent> {
 public:
  CanaryReactor() {
    event_.set_seq(1);
    StartWrite(&event_);
  }

  void OnWriteDone(bool ok) override {
    ++g_unguarded;  // the deliberate race (first access)
    g_written.store(true, std::memory_order_relaxed);
    Finish(ok ? grpc::Status::OK : grpc::Status(grpc::StatusCode::CANCELLED, "write failed"));
  }

  void OnDone() override { delete this; }

 private:
  dlmfd::v1::WatchEvent event_;
};

class CanaryService final : public dlmfd::v1::Jobs::CallbackService {
  grpc::ServerWriteReactor<dlmfd::v1::WatchEvent>* Watch(grpc::CallbackServerContext*,
                                                         const dlmfd::v1::WatchRequest*) override {
    return new CanaryReactor;
  }
};

}  // namespace

int main() {
  std::thread other([] {
    while (!g_written.load(std::memory_order_relaxed)) std::this_thread::yield();
    ++g_unguarded;  // the deliberate race (second access)
  });

  CanaryService service;
  int port = 0;
  grpc::ServerBuilder builder;
  builder.AddListeningPort("127.0.0.1:0", grpc::InsecureServerCredentials(), &port);
  builder.RegisterService(&service);
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  if (!server || port == 0) {
    std::fprintf(stderr, "tsan_canary: server did not start\n");
    g_written.store(true, std::memory_order_relaxed);
    other.join();
    return 1;
  }

  auto stub = dlmfd::v1::Jobs::NewStub(
      grpc::CreateChannel("127.0.0.1:" + std::to_string(port), grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  dlmfd::v1::WatchRequest request;
  request.set_job_id("canary");
  auto reader = stub->Watch(&context, request);
  dlmfd::v1::WatchEvent event;
  int events = 0;
  while (reader->Read(&event)) ++events;
  const grpc::Status status = reader->Finish();
  const bool ok = status.ok() && events == 1;
  if (!ok) {
    std::fprintf(stderr, "tsan_canary: Watch failed (%d events): %s\n", events,
                 status.error_message().c_str());
    g_written.store(true, std::memory_order_relaxed);
  }
  other.join();
  server->Shutdown();
  // Printed so that the compiler keeps both increments (a global only written would be dropped).
  std::printf("tsan_canary: counter %d\n", g_unguarded);
  return ok ? 0 : 1;
}
