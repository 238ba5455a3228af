#include "config.h"

#include <sys/stat.h>
#include <toml++/toml.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <regex>
#include <sstream>
#include <utility>

#include "executor.h"
#include "service_error.h"

namespace dlmfd::server {
namespace fs = std::filesystem;
namespace {

constexpr int kMaxConcurrentLimit = 1024;  // solver processes at once
constexpr int kMinEventBuffer = 8;         // events a watcher queue or a job's ring holds at least
constexpr size_t kMinTokenLength = 16;     // characters of a bearer token

int64_t ParseInteger(const std::string& key, const std::string& text) {
  try {
    size_t used = 0;
    long long value = std::stoll(text, &used);
    if (used != text.size()) throw std::invalid_argument(text);
    return value;
  } catch (const std::exception&) {
    throw ConfigError(key + " = \"" + text + "\" is not an integer");
  }
}

// One setting: its TOML key, flag name, environment variable and where it goes.
struct Setting {
  const char* key;
  std::function<void(Config&, const std::string&)> set;
};

std::vector<Setting> Settings() {
  auto text = [](std::string Config::*member) {
    return [member](Config& c, const std::string& v) { c.*member = v; };
  };
  auto integer = [](const char* key, int64_t Config::*member) {
    return [key, member](Config& c, const std::string& v) { c.*member = ParseInteger(key, v); };
  };
  auto small = [](const char* key, int Config::*member) {
    return [key, member](Config& c, const std::string& v) {
      c.*member = static_cast<int>(ParseInteger(key, v));
    };
  };
  auto slurm_text = [](std::string SlurmSettings::*member) {
    return [member](Config& c, const std::string& v) { c.slurm.*member = v; };
  };
  auto slurm_small = [](const char* key, int SlurmSettings::*member) {
    return [key, member](Config& c, const std::string& v) {
      c.slurm.*member = static_cast<int>(ParseInteger(key, v));
    };
  };
  return {
      {"listen", text(&Config::listen)},
      {"data_dir", text(&Config::data_dir)},
      {"max_concurrent", small("max_concurrent", &Config::max_concurrent)},
      {"solver", text(&Config::solver)},
      {"tokens_file", text(&Config::tokens_file)},
      {"max_scene_bytes", integer("max_scene_bytes", &Config::max_scene_bytes)},
      {"max_grid_nodes", integer("max_grid_nodes", &Config::max_grid_nodes)},
      {"max_memory_mb", integer("max_memory_mb", &Config::max_memory_mb)},
      {"max_queued", integer("max_queued", &Config::max_queued)},
      {"max_user_disk_mb", integer("max_user_disk_mb", &Config::max_user_disk_mb)},
      {"max_steps", integer("max_steps", &Config::max_steps)},
      {"max_snapshots", integer("max_snapshots", &Config::max_snapshots)},
      {"max_wall_seconds", integer("max_wall_seconds", &Config::max_wall_seconds)},
      {"watcher_buffer", small("watcher_buffer", &Config::watcher_buffer)},
      {"event_ring", small("event_ring", &Config::event_ring)},
      {"solver_threads", small("solver_threads", &Config::solver_threads)},
      {"log_level", text(&Config::log_level)},
      {"port_file", text(&Config::port_file)},
      {"executor", text(&Config::executor)},
      {"slurm_partition", slurm_text(&SlurmSettings::partition)},
      {"slurm_account", slurm_text(&SlurmSettings::account)},
      {"slurm_qos", slurm_text(&SlurmSettings::qos)},
      {"slurm_sbatch_options", slurm_text(&SlurmSettings::sbatch_options)},
      {"slurm_shared_dir", slurm_text(&SlurmSettings::shared_dir)},
      {"slurm_solver", slurm_text(&SlurmSettings::solver)},
      {"slurm_jobcomp_file", slurm_text(&SlurmSettings::jobcomp_file)},
      {"slurm_poll_seconds", slurm_small("slurm_poll_seconds", &SlurmSettings::poll_seconds)},
      {"slurm_max_submitted", slurm_small("slurm_max_submitted", &SlurmSettings::max_submitted)},
      {"slurm_time_limit_minutes",
       slurm_small("slurm_time_limit_minutes", &SlurmSettings::time_limit_minutes)},
      {"slurm_signal_seconds", slurm_small("slurm_signal_seconds", &SlurmSettings::signal_seconds)},
      {"slurm_max_attempts", slurm_small("slurm_max_attempts", &SlurmSettings::max_attempts)},
  };
}

std::string FlagName(const std::string& key) {
  std::string flag = "--" + key;
  for (auto& c : flag) c = c == '_' ? '-' : c;
  return flag;
}

std::string EnvName(const std::string& key) {
  std::string name = "DLMFD_" + key;
  for (auto& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return name;
}

std::string TomlValueText(const toml::node& node, const std::string& key) {
  if (auto s = node.value<std::string>()) return *s;
  if (node.is_integer()) return std::to_string(*node.value<int64_t>());
  throw ConfigError("config file: " + key + " must be a string or an integer");
}

void ApplyFile(const std::string& path, const std::vector<Setting>& settings, Config& config) {
  toml::table table;
  try {
    table = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    std::ostringstream message;
    message << "config file " << path << ": " << e.description() << " at line "
            << e.source().begin.line;
    throw ConfigError(message.str());
  }
  for (const auto& [key, node] : table) {
    std::string name(key.str());
    bool known = false;
    for (const auto& setting : settings) {
      if (name == setting.key) {
        setting.set(config, TomlValueText(node, name));
        known = true;
      }
    }
    if (!known) throw ConfigError("config file " + path + ": unknown key " + name);
  }
}

std::string DefaultDataDir(const EnvLookup& env) {
  if (const char* xdg = env("XDG_DATA_HOME"); xdg && *xdg) return std::string(xdg) + "/dlmfd";
  if (const char* home = env("HOME"); home && *home)
    return std::string(home) + "/.local/share/dlmfd";
  return "dlmfd-data";
}

std::string DefaultSolver(const char* argv0) {
  std::error_code error;
  fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (error) self = fs::absolute(argv0 ? argv0 : "dlmfdd");
  fs::path sibling = self.parent_path() / "dlmfd-solve";
  if (fs::exists(sibling)) return sibling.string();
  // A build tree keeps the solver in solver/ next to server/.
  fs::path build_tree = self.parent_path().parent_path() / "solver" / "dlmfd-solve";
  if (fs::exists(build_tree)) return build_tree.string();
  return sibling.string();
}

// Throws unless listen is unix:PATH or HOST:PORT with a port from 0 (pick a free one) to 65535; an
// IPv6 host is written in brackets. gRPC would wrap a larger port silently (99999 -> 34463).
void ValidateListen(const std::string& listen) {
  if (listen.rfind("unix:", 0) == 0 || listen.rfind("unix-abstract:", 0) == 0) return;
  size_t colon = std::string::npos;
  if (!listen.empty() && listen.front() == '[') {
    const size_t close = listen.find(']');
    if (close != std::string::npos && close + 1 < listen.size() && listen[close + 1] == ':') {
      colon = close + 1;
    }
  } else if (listen.find(':') == listen.rfind(':')) {
    colon = listen.find(':');
  }
  const std::string port = colon == std::string::npos ? "" : listen.substr(colon + 1);
  const bool digits =
      !port.empty() && port.size() <= 5 &&
      std::all_of(port.begin(), port.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (colon == 0 || !digits || std::stoi(port) > 65535) {
    throw ConfigError("listen = \"" + CutForMessage(listen) +
                      "\" is not allowed: expected HOST:PORT (an IPv6 host in brackets) or "
                      "unix:PATH, with a port from 0 to 65535 (0: pick a free port)");
  }
}

// Throws unless the solver is an executable regular file: a job would otherwise fail only when it
// first runs, long after the daemon said it was ready.
void ValidateSolver(const std::string& solver) {
  std::error_code error;
  const fs::file_status status = fs::status(solver, error);
  const char* why = nullptr;
  if (!fs::exists(status)) {
    why = "it does not exist";
  } else if (fs::is_directory(status)) {
    why = "it is a directory";
  } else if (!fs::is_regular_file(status) || access(solver.c_str(), X_OK) != 0) {
    why = "it is not a regular file the daemon may execute";
  }
  if (why) {
    throw ConfigError("solver = \"" + CutForMessage(solver) +
                      "\" (--solver, DLMFD_SOLVER) is not an executable file: " + why +
                      " (expected the path of dlmfd-solve)");
  }
}

// Throws unless executor is local or slurm and the slurm_* values are in their ranges. The slurm
// solver is not checked here: it is a path on the nodes, which the daemon's machine may not have.
void ValidateExecutor(Config& config) {
  if (!IsExecutorName(config.executor)) {
    throw ConfigError("executor = \"" + CutForMessage(config.executor) +
                      "\" is not allowed: expected " + ExecutorNamesText());
  }
  auto range = [](const char* key, int value, int least, int most) {
    if (value < least || value > most) {
      throw ConfigError(std::string(key) + " = " + std::to_string(value) +
                        " is not allowed: expected " + std::to_string(least) + " to " +
                        std::to_string(most));
    }
  };
  range("slurm_poll_seconds", config.slurm.poll_seconds, 1, 3600);
  range("slurm_max_submitted", config.slurm.max_submitted, 1, 100000);
  range("slurm_time_limit_minutes", config.slurm.time_limit_minutes, 0, 525600);
  range("slurm_signal_seconds", config.slurm.signal_seconds, 1, 65535);
  range("slurm_max_attempts", config.slurm.max_attempts, 1, 100);
  if (config.slurm.solver.empty()) config.slurm.solver = config.solver;
}

}  // namespace

std::vector<std::string> ConfigWarnings(const Config& config) {
  std::vector<std::string> warnings;
  if (!config.tokens_file.empty()) {
    struct stat info {};
    if (stat(config.tokens_file.c_str(), &info) == 0 && (info.st_mode & (S_IRWXG | S_IRWXO))) {
      char mode[8];
      std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(info.st_mode & 07777));
      warnings.push_back("tokens_file = \"" + config.tokens_file +
                         "\" can be read by its group or other users (mode " + mode +
                         "): anyone who reads it can act as any user in it; chmod 600 it");
    }
  }
  return warnings;
}

bool IsLoopbackAddress(const std::string& listen) {
  if (listen.rfind("unix:", 0) == 0) return true;
  std::string host = listen;
  if (!host.empty() && host.front() == '[') {
    auto close = host.find(']');
    host = close == std::string::npos ? host : host.substr(1, close - 1);
  } else if (auto colon = host.rfind(':'); colon != std::string::npos && host.find(':') == colon) {
    host = host.substr(0, colon);
  }
  if (host == "localhost" || host == "::1") return true;
  static const std::regex kLoopbackV4(R"(127\.\d{1,3}\.\d{1,3}\.\d{1,3})");
  return std::regex_match(host, kLoopbackV4);
}

std::map<std::string, std::string> LoadTokens(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError("tokens file " + path + " cannot be read");
  std::map<std::string, std::string> tokens;
  static const std::regex kUser(R"([A-Za-z0-9_.@-]{1,64})");
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream fields(line);
    std::string token, user, extra;
    if (!(fields >> token) || token[0] == '#') continue;
    if (!(fields >> user) || (fields >> extra)) {
      throw ConfigError("tokens file " + path + " line " + std::to_string(number) +
                        ": expected \"token user\"");
    }
    if (token.size() < kMinTokenLength) {
      throw ConfigError("tokens file " + path + " line " + std::to_string(number) +
                        ": a token must have at least " + std::to_string(kMinTokenLength) +
                        " characters");
    }
    if (!std::regex_match(user, kUser)) {
      throw ConfigError("tokens file " + path + " line " + std::to_string(number) +
                        ": user names use letters, digits and _.@- only");
    }
    if (!tokens.emplace(token, user).second) {
      throw ConfigError("tokens file " + path + " line " + std::to_string(number) +
                        ": the token is listed twice");
    }
  }
  return tokens;
}

void ValidateConfig(Config& config) {
  if (config.listen.empty()) throw ConfigError("listen must not be empty");
  ValidateListen(config.listen);
  if (config.data_dir.empty()) throw ConfigError("data_dir must not be empty");
  // Paths are made absolute against the directory the daemon starts in: its jobs and a Slurm
  // job's batch script (which runs in the job directory) must not read them against another one.
  for (std::string* path : {&config.data_dir, &config.solver, &config.slurm.shared_dir,
                            &config.slurm.solver, &config.slurm.jobcomp_file}) {
    if (path->empty()) continue;
    fs::path absolute = fs::absolute(*path).lexically_normal();
    if (!absolute.has_filename() && absolute != absolute.root_path()) {
      absolute = absolute.parent_path();  // "dir/" -> "dir"
    }
    *path = absolute.string();
  }
  if (config.max_concurrent < 1 || config.max_concurrent > kMaxConcurrentLimit) {
    throw ConfigError("max_concurrent = " + std::to_string(config.max_concurrent) +
                      " is not allowed: expected 1 to " + std::to_string(kMaxConcurrentLimit));
  }
  auto positive = [](const char* key, int64_t value) {
    if (value < 1) throw ConfigError(std::string(key) + " must be >= 1");
  };
  positive("max_scene_bytes", config.max_scene_bytes);
  positive("max_grid_nodes", config.max_grid_nodes);
  positive("max_memory_mb", config.max_memory_mb);
  positive("max_queued", config.max_queued);
  for (const auto& [key, value] :
       {std::pair<const char*, int64_t>{"max_user_disk_mb", config.max_user_disk_mb},
        {"max_steps", config.max_steps},
        {"max_snapshots", config.max_snapshots},
        {"max_wall_seconds", config.max_wall_seconds}}) {
    if (value < 0) throw ConfigError(std::string(key) + " must be >= 0 (0: no limit)");
  }
  auto at_least = [](const char* key, int value, int least) {
    if (value < least) throw ConfigError(std::string(key) + " must be >= " + std::to_string(least));
  };
  at_least("watcher_buffer", config.watcher_buffer, kMinEventBuffer);
  at_least("event_ring", config.event_ring, kMinEventBuffer);
  if (config.solver_threads < 0) throw ConfigError("solver_threads must be >= 0");
  static const char* const kLevels[] = {"trace", "debug", "info", "warn", "error", "off"};
  if (std::find(std::begin(kLevels), std::end(kLevels), config.log_level) == std::end(kLevels)) {
    throw ConfigError("log_level = " + config.log_level +
                      " is not allowed: expected trace, debug, info, warn, error or off");
  }
  config.tokens.clear();
  if (!config.tokens_file.empty()) {
    config.tokens = LoadTokens(config.tokens_file);
    // An empty file must not mean "no authentication": whoever set tokens_file asked for it.
    if (config.tokens.empty()) {
      throw ConfigError("tokens_file = \"" + CutForMessage(config.tokens_file) +
                        "\" has no tokens: add lines \"token user\", or leave tokens_file unset "
                        "to run without authentication (loopback only)");
    }
  }
  if (!IsLoopbackAddress(config.listen) && config.tokens.empty()) {
    throw ConfigError(
        "refusing to listen on " + config.listen +
        ": it is not a loopback address and no tokens are configured "
        "(set tokens_file to a file of \"token user\" lines, or listen on 127.0.0.1)");
  }
  if (config.solver.empty()) throw ConfigError("solver must not be empty");
  ValidateSolver(config.solver);
  ValidateExecutor(config);
}

bool LoadConfig(int argc, const char* const* argv, const EnvLookup& env, Config& config) {
  const auto settings = Settings();
  CLI::App app{"dlmfdd: the dlmfd job daemon (gRPC API dlmfd.v1.Jobs)"};
  std::string config_file;
  app.add_option("--config", config_file, "TOML config file (also DLMFD_CONFIG)");
  std::map<std::string, std::string> flag_values;
  std::vector<CLI::Option*> options;
  for (const auto& setting : settings) {
    options.push_back(
        app.add_option(FlagName(setting.key), flag_values[setting.key],
                       std::string("see docs/api.md (") + EnvName(setting.key) + ")"));
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return false;
  } catch (const CLI::ParseError& e) {
    throw ConfigError(e.what());
  }

  config = Config{};
  config.data_dir = DefaultDataDir(env);
  config.solver = DefaultSolver(argc > 0 ? argv[0] : nullptr);
  if (config_file.empty()) {
    if (const char* from_env = env("DLMFD_CONFIG"); from_env && *from_env) config_file = from_env;
  }
  if (!config_file.empty()) ApplyFile(config_file, settings, config);
  for (const auto& setting : settings) {
    if (const char* value = env(EnvName(setting.key).c_str()); value && *value) {
      setting.set(config, value);
    }
  }
  for (size_t i = 0; i < settings.size(); ++i) {
    if (options[i]->count() > 0) settings[i].set(config, flag_values[settings[i].key]);
  }
  ValidateConfig(config);
  return true;
}

}  // namespace dlmfd::server
