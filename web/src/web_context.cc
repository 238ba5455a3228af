#include "web_context.h"

namespace dlmfd::web {

WebContext::WebContext(const WebOptions& web_options, const cli::Endpoint& endpoint)
    : options(web_options),
      link(endpoint, web_options.daemon.timeout_seconds),
      sessions(
          static_cast<std::size_t>(web_options.max_sessions),
          std::chrono::seconds(static_cast<long long>(web_options.session_idle_hours * 3600))) {}

}  // namespace dlmfd::web
