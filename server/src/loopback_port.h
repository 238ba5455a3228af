// One daemon per loopback port, on both loopback addresses.
//
// Clients of "localhost:PORT" reach 127.0.0.1 or [::1], whichever the resolver gives first. gRPC
// binds every address a listen name resolves to that it can and succeeds when one binds, so a
// second daemon could take [::1]:PORT beside a first one on 127.0.0.1:PORT, and clients of
// localhost then sent their token to either (issue 38). Before serving, RequireLoopbackPortFree
// refuses a loopback listen address whose port is bound on either loopback address; once serving,
// LoopbackPortGuard binds (without listening and without SO_REUSEADDR) the loopback address of the
// other family on the same port, so that no later process can listen there. A host without IPv6
// (or IPv4) loopback has nothing to guard on that side.
#pragma once

#include <string>
#include <vector>

namespace dlmfd::server {

// Throws ConfigError naming the address when `listen` is 127.0.0.1, [::1] or localhost with a port
// other than 0 and that port is in use on 127.0.0.1 or [::1].
void RequireLoopbackPortFree(const std::string& listen);

class LoopbackPortGuard {
 public:
  LoopbackPortGuard() = default;
  // Binds the loopback address(es) of `listen`'s port that the server does not listen on. Throws
  // ConfigError when one is taken and the port was chosen by the user; with port 0 (chosen by the
  // system) a taken one is only logged.
  LoopbackPortGuard(const std::string& listen, int bound_port);
  ~LoopbackPortGuard();
  LoopbackPortGuard(LoopbackPortGuard&& other) noexcept;
  LoopbackPortGuard& operator=(LoopbackPortGuard&& other) noexcept;

 private:
  std::vector<int> fds_;
};

}  // namespace dlmfd::server
