// What dlmfd-web is told at start: where it listens, which daemon it serves, TLS, and the bounds
// on what browsers may hold open. Flag > environment > default, as for the CLI; the daemon's
// address is resolved as the CLI resolves it (--server, DLMFD_SERVER, the config file), but never
// a token: each browser user signs in with their own (docs/dashboard.md).
//
// Rules checked at start (exit status 2 with a message naming the flag): a listen address
// HOST:PORT with a port 0-65535 (0: a free one); TLS certificate and key given together, both
// readable; a host that is not loopback (127.0.0.0/8, ::1, localhost) only with TLS, and only
// for a daemon that refuses calls without a token (checked at start with one call), so that
// tokens and session cookies never cross a network in clear and no browser acts as the daemon's
// tokenless local user.
#pragma once

#include <string>

#include "CLI/CLI.hpp"
#include "connection.h"

namespace dlmfd::web {

struct WebOptions {
  std::string listen = "127.0.0.1:7480";  // --listen, DLMFD_WEB_LISTEN
  std::string port_file;                  // --port-file: the bound port, once serving
  std::string tls_cert;                   // --tls-cert: PEM certificate (chain) for HTTPS
  std::string tls_key;                    // --tls-key: its PEM private key
  cli::ConnectionFlags daemon;            // --server, --timeout (the daemon's address, deadlines)
  int max_sessions = 1000;                // signed-in browsers kept; the least recently used go
  double session_idle_hours = 12.0;       // a session unused this long is forgotten
  int max_live_pages = 64;                // event streams (open pages) at once, all users
  int max_watched_jobs = 256;             // Watch streams one page may hold; beyond it, polling

  // Parsed from listen by Validate.
  std::string host;
  int port = 0;
  bool loopback = true;
  bool tls() const { return !tls_cert.empty(); }
};

void AddWebFlags(CLI::App& app, WebOptions& options);
// Applies the environment (DLMFD_WEB_LISTEN) where no flag was given, parses and checks the
// options; throws cli::UsageError naming the flag.
void ValidateWebOptions(WebOptions& options, bool listen_from_flag);
// True for 127.0.0.0/8, ::1 and localhost.
bool IsLoopbackHost(const std::string& host);

}  // namespace dlmfd::web
