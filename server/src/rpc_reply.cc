#include "rpc_reply.h"

namespace dlmfd::server {

void CheckJobId(const std::string& id, const char* field) {
  constexpr size_t kMaxJobIdBytes = 64;
  Require(!id.empty(), std::string(field) + ": empty");
  RequireNoNul(field, id);
  Require(id.size() <= kMaxJobIdBytes,
          std::string(field) + ": longer than " + std::to_string(kMaxJobIdBytes) + " bytes");
}

void CheckPriority(int priority) {
  Require(priority >= -kMaxPriority && priority <= kMaxPriority,
          "priority = " + std::to_string(priority) + " is not allowed: expected " +
              std::to_string(-kMaxPriority) + " to " + std::to_string(kMaxPriority));
}

}  // namespace dlmfd::server
