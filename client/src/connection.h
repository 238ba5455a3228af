// Where the daemon is and who we are: the server address and bearer token, resolved with the
// precedence flag (--server, --token) > environment (DLMFD_SERVER, DLMFD_TOKEN) > config file
// ($XDG_CONFIG_HOME/dlmfd/config.toml, else ~/.config/dlmfd/config.toml; keys `server`, `token`)
// > default (127.0.0.1:7443, no token). Plaintext gRPC: tokens travel unencrypted, so a daemon
// beyond loopback belongs behind an SSH tunnel or a TLS proxy (TLS is not supported here).
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include "CLI/CLI.hpp"
#include "dlmfd/v1/jobs.grpc.pb.h"

namespace dlmfd::cli {

// A configuration problem the user must fix (exit code 2).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Endpoint {
  std::string server;
  std::string token;
  std::string server_from;  // "flag", "environment", "config file <path>", "default"
  std::string token_from;
};

struct ConnectionFlags {
  std::string server;
  std::string token;
  double timeout_seconds = 30.0;  // deadline of each unary call
};

// Adds --server, --token and --timeout to a subcommand.
void AddConnectionFlags(CLI::App& app, ConnectionFlags& flags);

using EnvLookup = std::function<const char*(const char*)>;
// Throws UsageError when the config file exists but is not valid TOML or has unknown keys.
Endpoint ResolveEndpoint(const ConnectionFlags& flags, const EnvLookup& env);
// The config file that ResolveEndpoint reads (it may not exist).
std::string ConfigFilePath(const EnvLookup& env);

class Connection {
 public:
  explicit Connection(const ConnectionFlags& flags);
  const Endpoint& endpoint() const { return endpoint_; }
  v1::Jobs::Stub& jobs() { return *jobs_; }
  const std::shared_ptr<grpc::Channel>& channel() const { return channel_; }
  // A context with the bearer token and, for unary calls, the deadline.
  std::unique_ptr<grpc::ClientContext> UnaryContext() const;
  std::unique_ptr<grpc::ClientContext> StreamContext() const;

 private:
  Endpoint endpoint_;
  std::chrono::milliseconds timeout_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::Jobs::Stub> jobs_;
};

}  // namespace dlmfd::cli
