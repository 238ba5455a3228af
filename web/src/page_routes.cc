// Pages, static files and the session: sign in with a daemon token, sign out, the CSRF token.
#include <nlohmann/json.hpp>

#include "http_reply.h"
#include "job_watch_set.h"
#include "request_guard.h"
#include "routes.h"
#include "web_assets.h"

namespace dlmfd::web {
namespace {

const Asset* FindAsset(const std::string& name) {
  for (const Asset& asset : Assets()) {
    if (asset.name == name) return &asset;
  }
  return nullptr;
}

void ServeAsset(httplib::Response& res, const std::string& name) {
  const Asset* asset = FindAsset(name);
  if (asset == nullptr) return ReplyError(res, 404, "no such file: /static/" + name);
  res.set_header("Cache-Control", "no-cache");
  res.set_content(std::string(asset->body), std::string(asset->content_type));
}

void Page(httplib::Server& server, WebContext& context, const std::string& pattern,
          const std::string& asset) {
  server.Get(pattern, ForUser(context, Access::kPage,
                              [asset](const httplib::Request&, httplib::Response& res,
                                      const Caller&) { ServeAsset(res, asset); }));
}

}  // namespace

void InstallPageRoutes(httplib::Server& server, WebContext& context) {
  Page(server, context, "/", "studies.html");
  Page(server, context, std::string("/studies/") + kIdPattern, "study.html");
  Page(server, context, std::string("/jobs/") + kIdPattern, "job.html");
  server.Get("/login", [](const httplib::Request&, httplib::Response& res) {
    ServeAsset(res, "login.html");
  });
  server.Get("/static/([A-Za-z0-9_.-]{1,64})",
             [](const httplib::Request& req, httplib::Response& res) {
               ServeAsset(res, req.matches[1].str());
             });

  // Sign in: the token is checked by the daemon itself (one call made with it).
  server.Post("/login", [&context](const httplib::Request& req, httplib::Response& res) {
    if (!OriginAllowed(context, req, res)) return;
    const std::string token = req.get_param_value("token");
    auto fail = [&res](const char* reason) {
      res.status = 303;
      res.set_header("Location", std::string("/login?error=") + reason);
    };
    if (token.empty() || token.size() > 4096) return fail("empty");
    auto call = context.link.Unary(token);
    v1::ListStudiesRequest request;
    request.set_page_size(1);
    v1::ListStudiesResponse response;
    const grpc::Status status = context.link.jobs().ListStudies(call.get(), request, &response);
    if (status.error_code() == grpc::StatusCode::UNAUTHENTICATED) return fail("rejected");
    if (!status.ok()) return fail("unreachable");
    const auto session = context.sessions.Create(token);
    res.status = 303;
    res.set_header("Set-Cookie", SessionCookie(context, session->id));
    res.set_header("Location", "/");
  });
  server.Post("/logout", ForUser(context, Access::kChange,
                                 [&context](const httplib::Request&, httplib::Response& res,
                                            const Caller& caller) {
                                   if (caller.session) context.sessions.Remove(caller.session->id);
                                   res.set_header("Set-Cookie", ExpiredSessionCookie(context));
                                   ReplyJson(res, "{\"signed_out\":true}");
                                 }));
  // What this process holds open now: pages with live events and the daemon's Watch streams
  // that feed them (a page that closes gives both back within seconds).
  server.Get("/api/status",
             ForUser(context, Access::kRead,
                     [&context](const httplib::Request&, httplib::Response& res, const Caller&) {
                       nlohmann::json body;
                       body["live_pages"] = context.live_pages.load();
                       body["watch_streams"] = JobWatchSet::OpenStreams();
                       body["sessions"] = context.sessions.Size();
                       ReplyJson(res, body.dump());
                     }));
  server.Get("/api/session", ForUser(context, Access::kRead,
                                     [&context](const httplib::Request&, httplib::Response& res,
                                                const Caller& caller) {
                                       nlohmann::json body;
                                       body["csrf"] = caller.session ? caller.session->csrf : "";
                                       body["signed_in_with_token"] = !caller.token.empty();
                                       body["daemon"] = context.link.address();
                                       ReplyJson(res, body.dump());
                                     }));
}

}  // namespace dlmfd::web
