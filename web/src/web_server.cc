#include "web_server.h"

#include <nlohmann/json.hpp>

#include "http_reply.h"
#include "request_guard.h"
#include "routes.h"

namespace dlmfd::web {

void InstallRoutes(httplib::Server& server, WebContext& context) {
  server.set_pre_routing_handler([&context](const httplib::Request& req, httplib::Response& res) {
    return HostAllowed(context, req, res) ? httplib::Server::HandlerResponse::Unhandled
                                          : httplib::Server::HandlerResponse::Handled;
  });
  server.set_post_routing_handler([](const httplib::Request&, httplib::Response& res) {
    res.set_header("Content-Security-Policy",
                   "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self'; "
                   "connect-src 'self'; media-src 'self'; form-action 'self'; base-uri 'none'; "
                   "frame-ancestors 'none'");
    res.set_header("X-Content-Type-Options", "nosniff");
    res.set_header("X-Frame-Options", "DENY");
    res.set_header("Referrer-Policy", "same-origin");
  });
  server.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
        std::string what = "unknown error";
        try {
          std::rethrow_exception(error);
        } catch (const std::exception& e) {
          what = e.what();
        } catch (...) {}
        ReplyError(res, 500, "internal error: " + what);
      });
  // Routes that match nothing, and bodies httplib refused, get a JSON error naming the status.
  server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (res.body.empty()) {
      const std::string message = res.status == 404   ? "no such page: " + req.path
                                  : res.status == 413 ? "the request body is over 1 MiB"
                                  : res.status == 400 ? "the request cannot be read as HTTP"
                                                      : "HTTP status " + std::to_string(res.status);
      ReplyError(res, res.status, message);
    }
  });
  server.set_payload_max_length(1 << 20);
  InstallPageRoutes(server, context);
  InstallApiRoutes(server, context);
}

}  // namespace dlmfd::web
