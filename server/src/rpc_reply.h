// What every unary handler of JobsService shares: the reply under Guarded (so no exception
// escapes into gRPC) and the check of a job id field.
#pragma once

#include <grpcpp/server_context.h>
#include <grpcpp/support/server_callback.h>

#include <spdlog/spdlog.h>

#include <string>
#include <utility>

#include "service_error.h"

namespace dlmfd::server {

// A unary reply: runs body under Guarded and finishes the default reactor with its status.
template <class Body>
grpc::ServerUnaryReactor* Reply(grpc::CallbackServerContext* context, const char* rpc,
                                Body&& body) {
  auto* reactor = context->DefaultReactor();
  grpc::Status status = Guarded(std::forward<Body>(body));
  if (!status.ok() && status.error_code() == grpc::StatusCode::INTERNAL) {
    spdlog::error("{}: {}", rpc, status.error_message());
  }
  reactor->Finish(status);
  return reactor;
}

// Priorities run from -kMaxPriority to kMaxPriority; throws INVALID_ARGUMENT outside.
inline constexpr int kMaxPriority = 1000;
void CheckPriority(int priority);

// Throws INVALID_ARGUMENT naming `field` for an empty id, a NUL byte or more than 64 bytes.
void CheckJobId(const std::string& id, const char* field = "job_id");

}  // namespace dlmfd::server
