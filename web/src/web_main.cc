// dlmfd-web: the web dashboard of dlmfdd's studies and jobs (docs/dashboard.md).
//
//   dlmfd-web [--listen 127.0.0.1:7480] [--server HOST:PORT] [--port-file F]
//             [--tls-cert CERT --tls-key KEY] [--max-sessions N] [--session-idle-hours H]
//             [--max-live-pages N] [--max-watched-jobs N]
//
// Prints one line, "dlmfd-web: serving http://HOST:PORT/ for the daemon at ADDR", once it
// listens; SIGINT or SIGTERM stop it (live pages end, their Watch streams are cancelled). Exit
// status: 0 stopped, 1 cannot listen, 2 bad options (the message names the flag).
#include <grpcpp/grpcpp.h>
#include <httplib.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <thread>

#include "connection.h"
#include "web_context.h"
#include "web_options.h"
#include "web_server.h"

namespace {

httplib::Server* g_server = nullptr;
std::atomic<bool>* g_stopping = nullptr;

extern "C" void Stop(int) {
  // Live pages see the flag and end; httplib's stop only shuts the listening socket and sets a
  // flag: both safe in a signal handler.
  if (g_stopping != nullptr) g_stopping->store(true);
  if (g_server != nullptr) g_server->stop();
}

int Main(int argc, char** argv) {
  using namespace dlmfd;
  CLI::App app{"dlmfd-web: the web dashboard of dlmfdd's studies and jobs (docs/dashboard.md)"};
  web::WebOptions options;
  web::AddWebFlags(app, options);
  app.set_version_flag("--version", std::string("dlmfd-web ") + DLMFD_VERSION);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  cli::Endpoint endpoint;
  try {
    web::ValidateWebOptions(options, app.count("--listen") > 0);
    endpoint =
        cli::ResolveEndpoint(options.daemon, [](const char* name) { return std::getenv(name); });
  } catch (const cli::UsageError& e) {
    std::cerr << "dlmfd-web: " << e.what() << "\n";
    return 2;
  }
  auto context = std::make_unique<web::WebContext>(options, endpoint);
  if (!options.loopback) {
    const grpc::Status probe = context->link.ProbeWithoutToken();
    if (probe.error_code() != grpc::StatusCode::UNAUTHENTICATED) {
      std::cerr << "dlmfd-web: refusing to listen on " << options.listen << ": the daemon at "
                << endpoint.server
                << (probe.ok() ? " takes calls without a token (give it a tokens_file)"
                               : " could not be asked whether it needs tokens (" +
                                     probe.error_message() + ")")
                << "; beyond loopback every browser user must sign in with a token\n";
      return 2;
    }
  }

  std::unique_ptr<httplib::Server> server;
  if (options.tls()) {
    auto tls =
        std::make_unique<httplib::SSLServer>(options.tls_cert.c_str(), options.tls_key.c_str());
    if (!tls->is_valid()) {
      std::cerr << "dlmfd-web: --tls-cert " << options.tls_cert << " and --tls-key "
                << options.tls_key << " do not make a usable certificate and key\n";
      return 2;
    }
    server = std::move(tls);
  } else {
    server = std::make_unique<httplib::Server>();
  }
  // Each live page holds a thread while it is open: room for them all and the other requests.
  const int threads = options.max_live_pages + 16;
  server->new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  web::InstallRoutes(*server, *context);
  // One dashboard per port: httplib's default also sets SO_REUSEPORT, which would let a second
  // process bind the same port and take half the connections.
  server->set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });

  int port = options.port;
  if (port == 0) {
    port = server->bind_to_any_port(options.host.c_str());
  } else if (!server->bind_to_port(options.host.c_str(), port)) {
    port = -1;
  }
  if (port <= 0) {
    std::cerr << "dlmfd-web: cannot listen on " << options.listen
              << " (in use, or not an address of this machine)\n";
    return 1;
  }
  context->options.port = port;
  if (!options.port_file.empty()) {
    const std::string tmp = options.port_file + ".tmp";
    std::ofstream(tmp) << port << "\n";
    std::rename(tmp.c_str(), options.port_file.c_str());
  }
  const std::string host =
      options.host.find(':') != std::string::npos ? "[" + options.host + "]" : options.host;
  std::cout << "dlmfd-web: serving " << (options.tls() ? "https" : "http") << "://" << host << ":"
            << port << "/ for the daemon at " << endpoint.server << std::endl;

  static_assert(std::atomic<bool>::is_always_lock_free);
  g_stopping = &context->stopping;
  g_server = server.get();
  std::signal(SIGINT, Stop);
  std::signal(SIGTERM, Stop);
  std::signal(SIGPIPE, SIG_IGN);
  const bool ok = server->listen_after_bind();
  context->stopping = true;
  g_server = nullptr;
  g_stopping = nullptr;
  server.reset();  // joins the threads: live pages end and cancel their streams
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) { return Main(argc, argv); }
