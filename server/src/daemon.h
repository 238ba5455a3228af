// Daemon: dlmfdd put together. Takes the data directory's lock (one daemon per directory), opens
// the store (DATA/jobs.db), re-queues the jobs a previous daemon left RUNNING (they resume from
// their checkpoints), starts the scheduler and the gRPC server with the Jobs service, the standard
// health service and server reflection. Shutdown stops the server (open streams are cancelled after
// a short grace) and then the scheduler (running solvers checkpoint and stay RUNNING in the store).
#pragma once

#include <grpcpp/server.h>

#include <memory>

#include "config.h"
#include "event_hub.h"
#include "executor.h"
#include "job_store.h"
#include "jobs_service.h"
#include "loopback_port.h"
#include "scheduler.h"

namespace dlmfd::server {

class Daemon {
 public:
  explicit Daemon(Config config);
  ~Daemon();
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  // Throws ConfigError or StoreError when it cannot start.
  void Start();
  void Shutdown();
  int port() const { return port_; }

 private:
  Config config_;
  int lock_fd_ = -1;
  std::unique_ptr<Executor> executor_;
  std::unique_ptr<JobStore> store_;
  std::unique_ptr<EventHub> hub_;
  std::unique_ptr<Scheduler> scheduler_;
  std::unique_ptr<JobsService> service_;
  std::unique_ptr<grpc::Server> server_;
  LoopbackPortGuard port_guard_;  // the other loopback address of the port (loopback_port.h)
  int port_ = 0;
  bool stopped_ = false;
};

}  // namespace dlmfd::server
