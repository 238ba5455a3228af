// ServiceError: an rpc failure with its gRPC status code, thrown by handlers and the store and
// turned into a grpc::Status by ToStatus, the one place where exceptions become status codes
// (design.md 5: handlers never throw out; every error of a job or a client ends in a status, not a
// crash).
#pragma once

#include <grpcpp/support/status.h>

#include <cstddef>
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>

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

// Throws ServiceError INVALID_ARGUMENT naming `field` when text holds a NUL byte: the C interfaces
// a text reaches (paths, logs) would end it there, so what is checked would not be what is used.
void RequireNoNul(std::string_view field, std::string_view text);

// How many bytes of one value an error message echoes, and of a whole message: a status message
// travels in gRPC metadata (a client refuses more than 8 KiB of it), and a megabyte of a bad value
// helps nobody.
inline constexpr size_t kMessageValueBytes = 80;
inline constexpr size_t kMessageBytes = 1024;

// A value as a message shows it: control bytes (NUL, line breaks) written \xNN, and past `keep`
// bytes cut, with its full size said.
std::string CutForMessage(std::string_view value, size_t keep = kMessageValueBytes);

// A whole message held to kMessageBytes: its head (the key comes first) and its tail (what is
// allowed comes last) are kept, and the middle is cut at UTF-8 character boundaries.
std::string BoundMessage(std::string_view message);

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
