#include "web_options.h"

#include <cstdlib>
#include <fstream>
#include <regex>

namespace dlmfd::web {

void AddWebFlags(CLI::App& app, WebOptions& options) {
  app.add_option("--listen", options.listen,
                 "HOST:PORT to serve on (env DLMFD_WEB_LISTEN; default 127.0.0.1:7480; port 0: a "
                 "free one)");
  app.add_option("--port-file", options.port_file, "write the bound port here once serving");
  app.add_option("--tls-cert", options.tls_cert, "PEM certificate: serve HTTPS (needs --tls-key)");
  app.add_option("--tls-key", options.tls_key, "PEM private key of --tls-cert");
  app.add_option("--server", options.daemon.server,
                 "the daemon's address host:port (env DLMFD_SERVER, else the CLI's config file)");
  app.add_option("--timeout", options.daemon.timeout_seconds,
                 "seconds allowed for each request to the daemon")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-sessions", options.max_sessions, "signed-in browsers kept (1 to 100000)")
      ->check(CLI::Range(1, 100000));
  app.add_option("--session-idle-hours", options.session_idle_hours,
                 "hours after which an unused session is forgotten")
      ->check(CLI::Range(0.01, 8760.0));
  app.add_option("--max-live-pages", options.max_live_pages,
                 "pages with live updates at once, all users (1 to 1000)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--max-watched-jobs", options.max_watched_jobs,
                 "jobs one page follows by Watch streams; beyond them it polls (1 to 10000)")
      ->check(CLI::Range(1, 10000));
}

bool IsLoopbackHost(const std::string& host) {
  if (host == "localhost" || host == "::1") return true;
  static const std::regex kLoopbackV4(R"(127\.\d{1,3}\.\d{1,3}\.\d{1,3})");
  return std::regex_match(host, kLoopbackV4);
}

namespace {

bool Readable(const std::string& path) { return std::ifstream(path).good(); }

}  // namespace

void ValidateWebOptions(WebOptions& options, bool listen_from_flag) {
  if (!listen_from_flag) {
    if (const char* env = std::getenv("DLMFD_WEB_LISTEN"); env != nullptr && *env != '\0') {
      options.listen = env;
    }
  }
  static const std::regex kListen(R"(^(\[([0-9A-Fa-f:.]+)\]|([A-Za-z0-9.-]+)):([0-9]{1,5})$)");
  std::smatch m;
  if (!std::regex_match(options.listen, m, kListen) || std::stoi(m[4].str()) > 65535) {
    throw cli::UsageError("--listen " + options.listen +
                          ": expected HOST:PORT with a port 0 to 65535 (an IPv6 host in "
                          "brackets), e.g. 127.0.0.1:7480");
  }
  options.host = m[2].matched ? m[2].str() : m[3].str();
  options.port = std::stoi(m[4].str());
  options.loopback = IsLoopbackHost(options.host);
  if (options.tls_cert.empty() != options.tls_key.empty()) {
    throw cli::UsageError("--tls-cert and --tls-key go together: give both or neither");
  }
  if (!options.tls_cert.empty() && !Readable(options.tls_cert)) {
    throw cli::UsageError("--tls-cert " + options.tls_cert + ": cannot be read");
  }
  if (!options.tls_key.empty() && !Readable(options.tls_key)) {
    throw cli::UsageError("--tls-key " + options.tls_key + ": cannot be read");
  }
  if (!options.loopback && !options.tls()) {
    throw cli::UsageError("refusing to listen on " + options.listen +
                          ": it is not a loopback address and no TLS is configured (give "
                          "--tls-cert and --tls-key, or listen on 127.0.0.1)");
  }
}

}  // namespace dlmfd::web
