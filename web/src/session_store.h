// Who a browser is: a session made when a user signs in with their daemon token (or, on a
// loopback address in front of a daemon that takes calls without a token, on the first visit).
// The browser holds only the session's id, in an HttpOnly, SameSite=Strict cookie (Secure under
// TLS) named after the port, so two dashboards on one host keep apart; the token stays in this
// process's memory and goes to the daemon with each call made for the session. Every
// state-changing request must carry the session's CSRF token (a header the page's script copies
// from /api/session, which another site can neither read nor send).
//
// Bounds: at most max_sessions (the least recently used is forgotten first); a session unused for
// `idle` is forgotten. Ids and CSRF tokens are 256 random bits from getrandom(2), compared in
// constant time.
#pragma once

#include <chrono>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace dlmfd::web {

struct Session {
  std::string id;
  std::string token;  // the daemon token, "" for a daemon that needs none
  std::string csrf;
  std::chrono::steady_clock::time_point last_used;
};

class SessionStore {
 public:
  SessionStore(std::size_t max_sessions, std::chrono::seconds idle);
  std::shared_ptr<const Session> Create(const std::string& token);
  // The live session of this id (its use recorded), or null.
  std::shared_ptr<const Session> Find(const std::string& id);
  void Remove(const std::string& id);
  std::size_t Size() const;

 private:
  void DropExpired(std::chrono::steady_clock::time_point now);
  std::size_t max_sessions_;
  std::chrono::seconds idle_;
  mutable std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Session>> sessions_;
};

// `bytes` random bytes as lower-case hex; throws std::runtime_error when the kernel gives none.
std::string RandomHex(std::size_t bytes);
// Equal texts, in a time that does not depend on where they differ.
bool SameSecret(const std::string& a, const std::string& b);

}  // namespace dlmfd::web
