// What every handler of dlmfd-web shares: the options, the channel to the daemon, the sessions,
// the picture cache and the count of live pages; and who made a request (Caller).
#pragma once

#include <atomic>
#include <memory>
#include <string>

#include "daemon_link.h"
#include "field_pictures.h"
#include "job_movie.h"
#include "session_store.h"
#include "web_options.h"

namespace dlmfd::web {

struct WebContext {
  WebContext(const WebOptions& web_options, const cli::Endpoint& endpoint);
  WebOptions options;
  DaemonLink link;
  SessionStore sessions;
  PictureCache pictures;
  MovieCache movies;
  std::atomic<int> live_pages{0};
  std::atomic<bool> stopping{false};
};

// The user of a request: a session (cookie) or a bearer token given in the request's own
// Authorization header (scripts; no session, no CSRF token needed: another site cannot set it).
struct Caller {
  std::shared_ptr<const Session> session;  // null for a header token
  std::string token;                       // sent to the daemon with each call ("" for none)
};

}  // namespace dlmfd::web
