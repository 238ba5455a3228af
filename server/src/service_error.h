// ServiceError: an rpc failure with its gRPC status code, thrown by handlers and the store and
// turned into a grpc::Status by ToStatus, the one place where exceptions become status codes
// (design.md 5: handlers never throw out; every error of a job or a client ends in a status, not a
// crash).
#pragma once

#include <grpcpp/support/status.h>

#include <exception>
#include <stdexcept>
#include <string>

namespace dlmfd::server {

class ServiceError : public std::runtime_error {
 public:
  ServiceError(grpc::StatusCode code, const std::string& message)
      : std::runtime_error(message),
        code_(code) {}
  grpc::StatusCode code() const { return code_; }

 private:
  grpc::StatusCode code_;
};

// Throws ServiceError INVALID_ARGUMENT with `message` (which names the field first) unless ok.
inline void Require(bool ok, const std::string& message) {
  if (!ok) throw ServiceError(grpc::StatusCode::INVALID_ARGUMENT, message);
}

// Maps the exception in flight (ServiceError, dlmfd::InvalidParameter, StoreError, anything else)
// to a status; never throws.
grpc::Status ToStatus(std::exception_ptr error);

// Runs body and returns OK, or the mapped status of whatever it threw.
template <class Body>
grpc::Status Guarded(Body&& body) {
  try {
    body();
    return grpc::Status::OK;
  } catch (...) {
    return ToStatus(std::current_exception());
  }
}

}  // namespace dlmfd::server
