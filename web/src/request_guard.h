// Who is asking, and may they: the session cookie or bearer header of a request, the CSRF and
// Origin checks of state-changing requests, and the Host check of a loopback server (web_server.h
// states the rules).
#pragma once

#include <httplib.h>

#include <functional>
#include <optional>
#include <string>

#include "web_context.h"

namespace dlmfd::web {

// The cookie that holds the session id: named after the port, so that two dashboards on one
// host (cookies ignore ports) keep their sessions apart.
std::string SessionCookieName(const WebContext& context);
// The Set-Cookie value of a new session (HttpOnly, SameSite=Strict, Path=/, Secure under TLS).
std::string SessionCookie(const WebContext& context, const std::string& id);
std::string ExpiredSessionCookie(const WebContext& context);
// The value of a cookie of the request, or "".
std::string CookieValue(const httplib::Request& req, const std::string& name);

// False (and a 421 reply) when a loopback server is asked under a Host that is not its own.
bool HostAllowed(const WebContext& context, const httplib::Request& req, httplib::Response& res);
// False (and a 403 reply) when an Origin header names another site.
bool OriginAllowed(const WebContext& context, const httplib::Request& req, httplib::Response& res);

enum class Access {
  kPage,    // GET of a page: no user -> redirect to /login
  kRead,    // GET of data: no user -> 401
  kChange,  // POST: as kRead, and the CSRF token of a session
};

// The caller of the request, or nullopt after replying (redirect, 401, 403). May create a session
// (a loopback server in front of a daemon that needs no token) and set its cookie.
std::optional<Caller> Authenticate(WebContext& context, const httplib::Request& req,
                                   httplib::Response& res, Access access);

using UserHandler =
    std::function<void(const httplib::Request&, httplib::Response&, const Caller& caller)>;
// A route's handler behind Authenticate.
httplib::Server::Handler ForUser(WebContext& context, Access access, UserHandler handler);

}  // namespace dlmfd::web
