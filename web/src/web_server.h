// The HTTP side of dlmfd-web: the routes, who may call them, and the rules every request meets.
//
//   pages       GET /  (studies)  /studies/ID  /jobs/ID  /login;  /static/NAME
//   session     POST /login (form field token)  POST /logout;  GET /api/session, /api/status
//   data        GET /api/overview  /api/studies/ID  /api/jobs/ID  /api/jobs/ID/files
//               /api/jobs/ID/log?offset=N  /api/jobs/ID/particles
//   actions     POST /api/jobs/ID/{cancel,retry,hold,release,delete}
//               POST /api/studies/ID/{cancel,retry,delete}
//   pictures    GET /pictures/jobs/ID/field.png?width=&height=&caption=0
//               GET /pictures/studies/ID/chart.png?x=&y=&group=&logx=1&logy=1&width=&height=
//   movie       GET /movies/jobs/ID/movie.mp4 (job_movie.h)
//   files       GET /files/jobs/ID/PATH (a download through the daemon's Fetch)
//   live        GET /events/overview  /events/studies/ID  /events/jobs/ID (live_events.h)
//
// Rules: on a loopback address the Host header must name this server (a page of another site
// that rebinds its name to 127.0.0.1 gets 421). Every route but the login page and the static
// files needs a user: a session cookie, or `Authorization: Bearer TOKEN` (checked with the daemon
// at each call). Without either, on a loopback address in front of a daemon that takes calls
// without a token, the first visit makes a session (the daemon's user "local"); otherwise pages
// redirect to /login and the API answers 401. POST requests with a session need the header
// X-CSRF-Token equal to the session's, and an Origin header, when sent, naming this server (403
// otherwise). Deletions need {"confirm": ID} in the body. Every reply carries a Content Security
// Policy allowing only this server's own scripts, styles and pictures, nosniff, no framing and a
// referrer only to this server (no-referrer would make the browser send `Origin: null`). A request
// that fails gets a JSON {"error": ...} with a 4xx/5xx status; a handler's exception becomes 500
// and the process keeps serving.
#pragma once

#include <httplib.h>

#include <memory>

#include "web_context.h"

namespace dlmfd::web {

// Registers every route on `server` (an httplib::Server or SSLServer).
void InstallRoutes(httplib::Server& server, WebContext& context);

}  // namespace dlmfd::web
