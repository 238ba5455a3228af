#include "loopback_port.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "config.h"

namespace dlmfd::server {
namespace {

enum class Family { kV4, kV6 };

struct LoopbackListen {
  bool v4 = false, v6 = false;  // the families the server itself listens on
  int port = 0;
};

// 127.0.0.1:P, [::1]:P and localhost:P; nothing for any other address.
bool ParseLoopback(const std::string& listen, LoopbackListen& out) {
  const auto colon = listen.rfind(':');
  if (colon == std::string::npos) return false;
  const std::string host = listen.substr(0, colon);
  try {
    out.port = std::stoi(listen.substr(colon + 1));
  } catch (const std::exception&) {
    return false;
  }
  out.v4 = host == "127.0.0.1" || host == "localhost";
  out.v6 = host == "[::1]" || host == "localhost";
  return out.v4 || out.v6;
}

const char* Name(Family family) { return family == Family::kV4 ? "127.0.0.1" : "[::1]"; }

// A socket bound to the loopback address of `family` on `port`, not listening; -1 when the address
// is in use, -2 when the family has no loopback here. A probe sets SO_REUSEADDR, as gRPC does, so
// that connections of an earlier server in TIME_WAIT do not count as a use; a guard does not, so
// that nobody can bind, and so listen, beside it.
int BindLoopback(Family family, int port, bool probe) {
  const int fd = socket(family == Family::kV4 ? AF_INET : AF_INET6, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return -2;
  if (probe) {
    const int reuse = 1;
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &reuse, sizeof reuse);
  }
  int result = 0;
  if (family == Family::kV4) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    result = bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address);
  } else {
    const int only = 1;
    setsockopt(fd, IPPROTO_IPV6, IPV6_V6ONLY, &only, sizeof only);
    sockaddr_in6 address{};
    address.sin6_family = AF_INET6;
    address.sin6_port = htons(static_cast<uint16_t>(port));
    address.sin6_addr = in6addr_loopback;
    result = bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address);
  }
  if (result == 0) return fd;
  const int error = errno;
  close(fd);
  errno = error;
  return error == EADDRINUSE ? -1 : -2;
}

std::string InUse(const std::string& listen, Family family, int port) {
  return "cannot listen on " + listen + ": port " + std::to_string(port) + " is in use on " +
         Name(family) + " (by another dlmfdd?), and clients of localhost:" + std::to_string(port) +
         " could reach that one; stop it or choose another port";
}

}  // namespace

void RequireLoopbackPortFree(const std::string& listen) {
  LoopbackListen parsed;
  if (!ParseLoopback(listen, parsed) || parsed.port == 0) return;
  for (Family family : {Family::kV4, Family::kV6}) {
    const int fd = BindLoopback(family, parsed.port, true);
    if (fd == -1) throw ConfigError(InUse(listen, family, parsed.port));
    if (fd >= 0) close(fd);
  }
}

LoopbackPortGuard::LoopbackPortGuard(const std::string& listen, int bound_port) {
  LoopbackListen parsed;
  if (!ParseLoopback(listen, parsed) || bound_port <= 0) return;
  for (Family family : {Family::kV4, Family::kV6}) {
    if (family == Family::kV4 ? parsed.v4 : parsed.v6) continue;
    const int fd = BindLoopback(family, bound_port, false);
    if (fd >= 0) {
      fds_.push_back(fd);
    } else if (fd == -1) {
      if (parsed.port != 0) throw ConfigError(InUse(listen, family, bound_port));
      spdlog::warn(
          "port {} chosen by the system is in use on {} too: clients of localhost:{} "
          "may reach another server",
          bound_port, Name(family), bound_port);
    }
  }
}

LoopbackPortGuard::~LoopbackPortGuard() {
  for (int fd : fds_) close(fd);
}

LoopbackPortGuard::LoopbackPortGuard(LoopbackPortGuard&& other) noexcept
    : fds_(std::move(other.fds_)) {
  other.fds_.clear();
}

LoopbackPortGuard& LoopbackPortGuard::operator=(LoopbackPortGuard&& other) noexcept {
  if (this != &other) {
    for (int fd : fds_) close(fd);
    fds_ = std::move(other.fds_);
    other.fds_.clear();
  }
  return *this;
}

}  // namespace dlmfd::server
