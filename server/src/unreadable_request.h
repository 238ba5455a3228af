// UnreadableRequestFactory: a server interceptor that names an unreadable request body.
//
// gRPC's callback API answers a request whose bytes do not parse as the rpc's message (bad wire
// format, a string field that is not UTF-8) with UNIMPLEMENTED and no message, before any handler
// runs (grpcpp/impl/codegen/server_callback_handlers.h: the reactor of a failed deserialization).
// This interceptor sees the failed parse (POST_RECV_MESSAGE with no message) and rewrites that
// status, as it is sent (PRE_SEND_STATUS), to INVALID_ARGUMENT naming the rpc and its request type.
// Every other status passes unchanged.
#pragma once

#include <grpcpp/support/server_interceptor.h>

namespace dlmfd::server {

class UnreadableRequestFactory final
    : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  grpc::experimental::Interceptor* CreateServerInterceptor(
      grpc::experimental::ServerRpcInfo* info) override;
};

}  // namespace dlmfd::server
