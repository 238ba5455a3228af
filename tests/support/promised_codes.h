// The status codes jobs.proto promises for any request, however hostile: what the hostile-input
// test and the rpc fuzz target accept from the daemon (UNKNOWN, INTERNAL, UNIMPLEMENTED and
// UNAVAILABLE are not among them).
#pragma once

#include <grpcpp/grpcpp.h>

#include <set>

namespace dlmfd::testing {

inline const std::set<grpc::StatusCode> kPromisedCodes = {grpc::StatusCode::OK,
                                                          grpc::StatusCode::INVALID_ARGUMENT,
                                                          grpc::StatusCode::NOT_FOUND,
                                                          grpc::StatusCode::RESOURCE_EXHAUSTED,
                                                          grpc::StatusCode::ALREADY_EXISTS,
                                                          grpc::StatusCode::FAILED_PRECONDITION,
                                                          grpc::StatusCode::OUT_OF_RANGE};

}  // namespace dlmfd::testing
