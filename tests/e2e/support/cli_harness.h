// Test support for the CLI end to end: run a program with exactly a given environment and capture
// its output (through pipes, or with stdout on a pseudo-terminal, as a user's shell gives it), and
// a real dlmfdd with a tokens file and its SQLite store in a temporary directory.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "../../support/build_paths.h"

namespace dlmfd::testing {

// A small lid-driven cavity (10 steps, snapshots and checkpoints) the e2e tests submit.
inline constexpr char kCavity[] = R"toml(title = "lid-driven cavity (e2e)"
[domain]
size = [1.0, 1.0]
h = 0.0625
[domain.boundary]
left = { type = "wall" }
right = { type = "wall" }
bottom = { type = "wall" }
top = { type = "velocity", profile = "uniform", value = [1.0, 0.0] }
[fluid]
density = 1.0
viscosity = 0.01
relaxation_time = 0.0
[time]
dt = 0.01
end = 0.1
[output]
fields_every = 0.05
particles_every = 0.05
checkpoint_every = 0.05
)toml";

struct CliRun {
  int code = -1;
  std::string out;
  std::string err;
};

// Runs `argv` with exactly the environment `env`, capturing stdout and stderr; sets `printed` (when
// given) once the child has written its first bytes to stdout. `cwd`: the child's directory.
CliRun Execute(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env,
               std::atomic<bool>* printed = nullptr, const std::string& cwd = "");
// As Execute, with stdout (and stderr) on a pseudo-terminal of `columns` x 24: `out` holds what
// the terminal received, escape sequences included.
CliRun ExecuteOnTerminal(const std::vector<std::string>& argv,
                         const std::map<std::string, std::string>& env, int columns);

std::string Slurp(const std::filesystem::path& path);
std::string FirstLine(const std::string& text);

// dlmfdd on a free loopback port with `root`/data, a tokens file (alice, bob) and the real solver.
class CliDaemon {
 public:
  static constexpr const char* kAliceToken = "alice-token-0123456789";
  explicit CliDaemon(std::filesystem::path root);
  ~CliDaemon();
  // Starts it on `listen`; false (with the log in `error`) when it exited first.
  bool Start(const std::string& listen, std::string& error);
  void Kill(int signal_number);
  const std::string& server() const { return server_; }
  // A user's environment with no config file: HOME, PATH, DLMFD_SERVER, DLMFD_TOKEN (and the
  // sanitizer options of the test's own environment, when set).
  std::map<std::string, std::string> Env(bool with_server = true, bool with_token = true) const;

 private:
  std::filesystem::path root_;
  pid_t pid_ = -1;
  std::string server_;
};

}  // namespace dlmfd::testing
