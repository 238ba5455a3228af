// dlmfdd: the dlmfd job daemon. Configuration: docs/api.md (flag > DLMFD_* environment > TOML file
// > defaults). SIGTERM or SIGINT stop it cleanly: running solvers checkpoint and resume at the next
// start.
#include <signal.h>

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <iostream>

#include "config.h"
#include "daemon.h"

int main(int argc, char** argv) {
  using dlmfd::server::Config;
  // Block the stop signals in every thread; the main thread waits for them with sigwait.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  signal(SIGPIPE, SIG_IGN);

  Config config;
  try {
    if (!dlmfd::server::LoadConfig(
            argc, argv, [](const char* name) { return std::getenv(name); }, config)) {
      return 0;
    }
  } catch (const std::exception& e) {
    std::cerr << "dlmfdd: " << e.what() << "\n";
    return 2;
  }
  spdlog::set_level(spdlog::level::from_str(config.log_level));
  spdlog::set_pattern("%Y-%m-%dT%H:%M:%S.%e %^%l%$ %v");
  try {
    dlmfd::server::Daemon daemon(config);
    daemon.Start();
    int received = 0;
    sigwait(&stop_signals, &received);
    spdlog::info("signal {} received", received);
    daemon.Shutdown();
  } catch (const std::exception& e) {
    spdlog::error("dlmfdd: {}", e.what());
    return 1;
  }
  return 0;
}
