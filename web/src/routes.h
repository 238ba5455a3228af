// The two halves of the route table (web_server.h lists the routes): pages and the session
// (page_routes.cc), and the data, actions, pictures, files and live events (api_routes.cc).
#pragma once

#include <httplib.h>

#include "web_context.h"

namespace dlmfd::web {

// A job or study id as the daemon makes them: letters, digits, '-', '_' and '.', 1-128 bytes.
inline constexpr const char* kIdPattern = "([A-Za-z0-9._-]{1,128})";

void InstallPageRoutes(httplib::Server& server, WebContext& context);
void InstallApiRoutes(httplib::Server& server, WebContext& context);

}  // namespace dlmfd::web
