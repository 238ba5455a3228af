#include "auth.h"

#include "service_error.h"

namespace dlmfd::server {
namespace {

bool ConstantTimeEqual(const std::string& a, const std::string& b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (size_t i = 0; i < a.size(); ++i) {
    diff |= static_cast<unsigned char>(a[i] ^ (i < b.size() ? b[i] : 0));
  }
  return diff == 0;
}

}  // namespace

std::string Authenticator::UserOfHeader(const std::string* authorization) const {
  if (tokens_.empty()) return kLocalUser;
  if (!authorization) {
    throw ServiceError(grpc::StatusCode::UNAUTHENTICATED,
                       "missing \"authorization: Bearer <token>\" metadata");
  }
  static const std::string kPrefix = "Bearer ";
  if (authorization->compare(0, kPrefix.size(), kPrefix) != 0) {
    throw ServiceError(grpc::StatusCode::UNAUTHENTICATED,
                       "the authorization metadata must be \"Bearer <token>\"");
  }
  const std::string token = authorization->substr(kPrefix.size());
  const std::string* user = nullptr;
  for (const auto& [known, name] : tokens_) {
    if (ConstantTimeEqual(known, token)) user = &name;
  }
  if (!user) throw ServiceError(grpc::StatusCode::UNAUTHENTICATED, "unknown token");
  return *user;
}

std::string Authenticator::User(const grpc::ServerContextBase& context) const {
  const auto& metadata = context.client_metadata();
  auto it = metadata.find("authorization");
  if (it == metadata.end()) return UserOfHeader(nullptr);
  std::string value(it->second.data(), it->second.size());
  return UserOfHeader(&value);
}

}  // namespace dlmfd::server
