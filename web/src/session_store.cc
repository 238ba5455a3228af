#include "session_store.h"

#include <sys/random.h>

#include <stdexcept>
#include <vector>

namespace dlmfd::web {

std::string RandomHex(std::size_t bytes) {
  std::vector<unsigned char> raw(bytes);
  std::size_t got = 0;
  while (got < bytes) {
    const ssize_t n = getrandom(raw.data() + got, bytes - got, 0);
    if (n <= 0) throw std::runtime_error("getrandom gave no random bytes");
    got += static_cast<std::size_t>(n);
  }
  static const char kHex[] = "0123456789abcdef";
  std::string out;
  for (unsigned char c : raw) {
    out += kHex[c >> 4];
    out += kHex[c & 15];
  }
  return out;
}

bool SameSecret(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (std::size_t k = 0; k < a.size(); ++k) diff |= static_cast<unsigned char>(a[k] ^ b[k]);
  return diff == 0;
}

SessionStore::SessionStore(std::size_t max_sessions, std::chrono::seconds idle)
    : max_sessions_(max_sessions),
      idle_(idle) {}

std::shared_ptr<const Session> SessionStore::Create(const std::string& token) {
  auto session = std::make_shared<Session>();
  session->id = RandomHex(32);
  session->token = token;
  session->csrf = RandomHex(32);
  const auto now = std::chrono::steady_clock::now();
  session->last_used = now;
  std::lock_guard<std::mutex> lock(mutex_);
  DropExpired(now);
  while (sessions_.size() >= max_sessions_) {
    auto oldest = sessions_.begin();
    for (auto it = sessions_.begin(); it != sessions_.end(); ++it) {
      if (it->second->last_used < oldest->second->last_used) oldest = it;
    }
    sessions_.erase(oldest);
  }
  sessions_[session->id] = session;
  return session;
}

std::shared_ptr<const Session> SessionStore::Find(const std::string& id) {
  const auto now = std::chrono::steady_clock::now();
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = sessions_.find(id);
  if (it == sessions_.end()) return nullptr;
  if (now - it->second->last_used > idle_) {
    sessions_.erase(it);
    return nullptr;
  }
  it->second->last_used = now;
  return it->second;
}

void SessionStore::Remove(const std::string& id) {
  std::lock_guard<std::mutex> lock(mutex_);
  sessions_.erase(id);
}

std::size_t SessionStore::Size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return sessions_.size();
}

void SessionStore::DropExpired(std::chrono::steady_clock::time_point now) {
  for (auto it = sessions_.begin(); it != sessions_.end();) {
    it = now - it->second->last_used > idle_ ? sessions_.erase(it) : std::next(it);
  }
}

}  // namespace dlmfd::web
