// Authenticator: who is calling. Without tokens (loopback only, enforced by ValidateConfig) every
// caller is the user "local". With tokens every rpc must carry "authorization: Bearer <token>"; an
// absent, malformed or unknown token is UNAUTHENTICATED. Tokens are compared in constant time.
// Not supported: TLS client certificates, token expiry (edit the tokens file and restart).
#pragma once

#include <grpcpp/server_context.h>

#include <map>
#include <string>

namespace dlmfd::server {

inline constexpr char kLocalUser[] = "local";

class Authenticator {
 public:
  explicit Authenticator(std::map<std::string, std::string> tokens)
      : tokens_(std::move(tokens)) {}
  // The user of the call; throws ServiceError UNAUTHENTICATED.
  std::string User(const grpc::ServerContextBase& context) const;
  std::string UserOfHeader(const std::string* authorization) const;

 private:
  std::map<std::string, std::string> tokens_;
};

}  // namespace dlmfd::server
