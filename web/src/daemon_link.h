// The web process's one channel to dlmfdd and the contexts of calls made for a browser user: each
// carries that user's own bearer token, so the daemon applies its own rules unchanged (a user
// sees and acts on their own jobs only; another's job is NOT_FOUND). Unary calls have the
// --timeout deadline; Watch and Fetch streams none (they end with the job, the file, or the page).
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <memory>
#include <string>

#include "connection.h"
#include "dlmfd/v1/jobs.grpc.pb.h"

namespace dlmfd::web {

class DaemonLink {
 public:
  DaemonLink(const cli::Endpoint& endpoint, double timeout_seconds);
  const std::string& address() const { return address_; }
  v1::Jobs::Stub& jobs() { return *jobs_; }
  std::unique_ptr<grpc::ClientContext> Unary(const std::string& token) const;
  std::unique_ptr<grpc::ClientContext> Stream(const std::string& token) const;
  // The daemon answers a call that carries no token (it has no tokens file): OK; UNAUTHENTICATED
  // when it wants one; UNAVAILABLE when it cannot be reached.
  grpc::Status ProbeWithoutToken();

 private:
  std::string address_;
  std::chrono::milliseconds timeout_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::Jobs::Stub> jobs_;
};

}  // namespace dlmfd::web
