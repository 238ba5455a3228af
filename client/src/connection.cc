// Endpoint resolution and the gRPC channel.
#include "connection.h"

#include <cstdlib>
#include <filesystem>

#include <toml++/toml.h>

namespace dlmfd::cli {

inline constexpr const char* kDefaultServer = "127.0.0.1:7443";

void AddConnectionFlags(CLI::App& app, ConnectionFlags& flags) {
  app.add_option("--server", flags.server, "daemon address host:port (env DLMFD_SERVER)");
  app.add_option("--token", flags.token, "bearer token (env DLMFD_TOKEN)");
  app.add_option("--timeout", flags.timeout_seconds, "seconds allowed for each request")
      ->check(CLI::PositiveNumber);
}

std::string ConfigFilePath(const EnvLookup& env) {
  const char* xdg = env("XDG_CONFIG_HOME");
  if (xdg != nullptr && *xdg != '\0') return std::string(xdg) + "/dlmfd/config.toml";
  const char* home = env("HOME");
  if (home != nullptr && *home != '\0') return std::string(home) + "/.config/dlmfd/config.toml";
  return {};
}

Endpoint ResolveEndpoint(const ConnectionFlags& flags, const EnvLookup& env) {
  Endpoint e{kDefaultServer, "", "default", "none"};
  const std::string path = ConfigFilePath(env);
  std::error_code ec;
  if (!path.empty() && std::filesystem::exists(path, ec)) {
    toml::table table;
    try {
      table = toml::parse_file(path);
    } catch (const toml::parse_error& err) {
      throw UsageError("config file " + path + ": " + std::string(err.description()));
    }
    for (const auto& [key, value] : table) {
      const std::string name(key.str());
      if (name != "server" && name != "token") {
        throw UsageError("config file " + path + ": unknown key '" + name +
                         "' (allowed: server, token)");
      }
      if (!value.is_string())
        throw UsageError("config file " + path + ": " + name + " must be a string");
    }
    if (auto server = table["server"].value<std::string>()) {
      e.server = *server;
      e.server_from = "config file " + path;
    }
    if (auto token = table["token"].value<std::string>()) {
      e.token = *token;
      e.token_from = "config file " + path;
    }
  }
  if (const char* server = env("DLMFD_SERVER"); server != nullptr && *server != '\0') {
    e.server = server;
    e.server_from = "environment";
  }
  if (const char* token = env("DLMFD_TOKEN"); token != nullptr && *token != '\0') {
    e.token = token;
    e.token_from = "environment";
  }
  if (!flags.server.empty()) {
    e.server = flags.server;
    e.server_from = "flag";
  }
  if (!flags.token.empty()) {
    e.token = flags.token;
    e.token_from = "flag";
  }
  return e;
}

Connection::Connection(const ConnectionFlags& flags)
    : endpoint_(ResolveEndpoint(flags, [](const char* name) { return std::getenv(name); })),
      timeout_(std::chrono::milliseconds(static_cast<long long>(flags.timeout_seconds * 1000.0))) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(64 << 20);  // snapshots of large grids
  channel_ = grpc::CreateCustomChannel(endpoint_.server, grpc::InsecureChannelCredentials(), args);
  jobs_ = v1::Jobs::NewStub(channel_);
}

std::unique_ptr<grpc::ClientContext> Connection::StreamContext() const {
  auto context = std::make_unique<grpc::ClientContext>();
  if (!endpoint_.token.empty()) context->AddMetadata("authorization", "Bearer " + endpoint_.token);
  return context;
}

std::unique_ptr<grpc::ClientContext> Connection::UnaryContext() const {
  auto context = StreamContext();
  context->set_deadline(std::chrono::system_clock::now() + timeout_);
  return context;
}

}  // namespace dlmfd::cli
