#include "request_guard.h"

#include "http_reply.h"
#include "session_store.h"

namespace dlmfd::web {

std::string SessionCookieName(const WebContext& context) {
  return "dlmfd_session_" + std::to_string(context.options.port);
}

std::string SessionCookie(const WebContext& context, const std::string& id) {
  return SessionCookieName(context) + "=" + id + "; Path=/; HttpOnly; SameSite=Strict" +
         (context.options.tls() ? "; Secure" : "");
}

std::string ExpiredSessionCookie(const WebContext& context) {
  return SessionCookieName(context) + "=; Path=/; HttpOnly; SameSite=Strict; Max-Age=0" +
         (context.options.tls() ? "; Secure" : "");
}

std::string CookieValue(const httplib::Request& req, const std::string& name) {
  const size_t count = req.get_header_value_count("Cookie");
  for (size_t k = 0; k < count; ++k) {
    const std::string header = req.get_header_value("Cookie", k);
    size_t start = 0;
    while (start < header.size()) {
      size_t end = header.find(';', start);
      if (end == std::string::npos) end = header.size();
      std::string part = header.substr(start, end - start);
      const size_t first = part.find_first_not_of(' ');
      part = first == std::string::npos ? "" : part.substr(first);
      if (part.size() > name.size() && part.compare(0, name.size(), name) == 0 &&
          part[name.size()] == '=') {
        return part.substr(name.size() + 1);
      }
      start = end + 1;
    }
  }
  return {};
}

bool HostAllowed(const WebContext& context, const httplib::Request& req, httplib::Response& res) {
  if (!context.options.loopback) return true;
  const std::string host = req.get_header_value("Host");
  const std::string port = ":" + std::to_string(context.options.port);
  const std::string listen_host = context.options.host.find(':') != std::string::npos
                                      ? "[" + context.options.host + "]"
                                      : context.options.host;
  for (const std::string& allowed :
       {listen_host, std::string("127.0.0.1"), std::string("localhost"), std::string("[::1]")}) {
    if (host == allowed + port) return true;
  }
  ReplyError(res, 421,
             "Host " + host + " is not this server's (a loopback dashboard answers to " +
                 listen_host + port + ", localhost" + port + ")");
  return false;
}

bool OriginAllowed(const WebContext& context, const httplib::Request& req, httplib::Response& res) {
  if (!req.has_header("Origin")) return true;
  const std::string origin = req.get_header_value("Origin");
  const std::string own =
      (context.options.tls() ? "https://" : "http://") + req.get_header_value("Host");
  if (origin == own) return true;
  ReplyError(res, 403, "a request from another site (Origin " + origin + ") is refused");
  return false;
}

namespace {

void NoUser(WebContext& context, const httplib::Request& req, httplib::Response& res, Access access,
            const std::string& why) {
  if (access == Access::kPage) {
    res.status = 303;
    res.set_header("Location", "/login");
    res.set_header("Cache-Control", "no-store");
    return;
  }
  ReplyError(res, 401, why);
}

// A daemon that takes calls without a token, asked at most once a second.
bool DaemonNeedsNoToken(WebContext& context) {
  static std::mutex mutex;
  static std::chrono::steady_clock::time_point asked;
  static bool answer = false;
  std::lock_guard<std::mutex> lock(mutex);
  const auto now = std::chrono::steady_clock::now();
  if (now - asked < std::chrono::seconds(1)) return answer;
  asked = now;
  answer = context.link.ProbeWithoutToken().ok();
  return answer;
}

}  // namespace

std::optional<Caller> Authenticate(WebContext& context, const httplib::Request& req,
                                   httplib::Response& res, Access access) {
  const std::string authorization = req.get_header_value("Authorization");
  if (authorization.rfind("Bearer ", 0) == 0 && authorization.size() > 7) {
    return Caller{nullptr, authorization.substr(7)};
  }
  const std::string id = CookieValue(req, SessionCookieName(context));
  std::shared_ptr<const Session> session = id.empty() ? nullptr : context.sessions.Find(id);
  if (session == nullptr) {
    // Only a page visit makes a session: a POST without one could come from anywhere.
    if (access != Access::kChange && context.options.loopback && DaemonNeedsNoToken(context)) {
      session = context.sessions.Create("");
      res.set_header("Set-Cookie", SessionCookie(context, session->id));
    } else {
      NoUser(context, req, res, access,
             id.empty() ? "sign in first: POST /login with your daemon token, or send "
                          "Authorization: Bearer TOKEN"
                        : "the session has ended: sign in again");
      return std::nullopt;
    }
  }
  if (access == Access::kChange) {
    if (!OriginAllowed(context, req, res)) return std::nullopt;
    if (!SameSecret(req.get_header_value("X-CSRF-Token"), session->csrf)) {
      ReplyError(res, 403,
                 "the X-CSRF-Token header is missing or wrong (a state-changing request must come "
                 "from this dashboard's own page)");
      return std::nullopt;
    }
  }
  return Caller{session, session->token};
}

httplib::Server::Handler ForUser(WebContext& context, Access access, UserHandler handler) {
  return [&context, access, handler](const httplib::Request& req, httplib::Response& res) {
    if (auto caller = Authenticate(context, req, res, access)) handler(req, res, *caller);
  };
}

}  // namespace dlmfd::web
