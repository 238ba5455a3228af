// UnreadableRequestFactory: a server interceptor that names an unreadable request body.
//
// gRPC's callback API answers a request whose bytes do not parse as the rpc's message (bad wire
// format, a string field that is not UTF-8) with UNIMPLEMENTED and no message, before any handler
// runs (grpcpp/impl/codegen/server_callback_handlers.h: the reactor of a failed deserialization).
// This interceptor sees the failed parse (POST_RECV_MESSAGE with no message) and rewrites that
// status, as it is sent (PRE_SEND_STATUS), to INVALID_ARGUMENT naming the rpc and its request type.
// Every other status passes unchanged. A call of a method the daemon does not serve gets no
// interceptor (gRPC answers it UNIMPLEMENTED; scripts/tsan.supp says why that matters).
#pragma once

#include <grpcpp/support/server_interceptor.h>

#include <map>
#include <string>
#include <vector>

namespace dlmfd::server {

class UnreadableRequestFactory final
    : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  // `services`: the full names of the services of the generated descriptor pool that the server
  // registers (dlmfd.v1.Jobs). Their methods' request types are looked up here, once, before
  // gRPC's threads start (the pool builds descriptors lazily, behind locks TSan cannot see).
  explicit UnreadableRequestFactory(const std::vector<std::string>& services);

  grpc::experimental::Interceptor* CreateServerInterceptor(
      grpc::experimental::ServerRpcInfo* info) override;

 private:
  std::map<std::string, std::string> request_types_;  // "/dlmfd.v1.Jobs/Get" -> its input type
};

}  // namespace dlmfd::server
