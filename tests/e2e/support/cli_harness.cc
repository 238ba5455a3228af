#include "cli_harness.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

namespace dlmfd::testing {
namespace fs = std::filesystem;
namespace {

struct ChildArgs {
  std::vector<std::string> env_text;
  std::vector<char*> args, envp;
  ChildArgs(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env) {
    for (const auto& [k, v] : env) env_text.push_back(k + "=" + v);
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    for (auto& e : env_text) envp.push_back(e.data());
    args.push_back(nullptr);
    envp.push_back(nullptr);
  }
};

int ExitCode(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

CliRun Execute(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env,
               std::atomic<bool>* printed, const std::string& cwd) {
  // Everything the child needs is built before fork: a test may run this from a second thread.
  ChildArgs child(argv, env);
  int out_pipe[2], err_pipe[2];
  if (pipe(out_pipe) != 0 || pipe(err_pipe) != 0) return {};
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(out_pipe[1], STDOUT_FILENO);
    dup2(err_pipe[1], STDERR_FILENO);
    close(out_pipe[0]);
    close(err_pipe[0]);
    if (!cwd.empty() && chdir(cwd.c_str()) != 0) _exit(126);
    execve(child.args[0], child.args.data(), child.envp.data());
    _exit(127);
  }
  close(out_pipe[1]);
  close(err_pipe[1]);
  CliRun run;
  pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
  int open_fds = 2;
  char buffer[4096];
  while (open_fds > 0) {
    if (poll(fds, 2, -1) < 0) break;
    for (int k = 0; k < 2; ++k) {
      if (fds[k].fd < 0 || fds[k].revents == 0) continue;
      const ssize_t n = read(fds[k].fd, buffer, sizeof(buffer));
      if (n <= 0) {
        close(fds[k].fd);
        fds[k].fd = -1;
        --open_fds;
      } else {
        (k == 0 ? run.out : run.err).append(buffer, std::size_t(n));
        if (k == 0 && printed) printed->store(true);
      }
    }
  }
  run.code = ExitCode(pid);
  return run;
}

CliRun ExecuteOnTerminal(const std::vector<std::string>& argv,
                         const std::map<std::string, std::string>& env, int columns) {
  ChildArgs child(argv, env);
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0) return {};
  const std::string slave_name = ptsname(master);
  winsize size{};
  size.ws_col = static_cast<unsigned short>(columns);
  size.ws_row = 24;
  const pid_t pid = fork();
  if (pid == 0) {
    setsid();
    const int slave = open(slave_name.c_str(), O_RDWR);
    if (slave < 0) _exit(126);
    ioctl(slave, TIOCSWINSZ, &size);
    termios mode{};
    tcgetattr(slave, &mode);
    mode.c_oflag &= ~static_cast<tcflag_t>(ONLCR);  // what the program wrote, byte for byte
    tcsetattr(slave, TCSANOW, &mode);
    dup2(slave, STDOUT_FILENO);
    dup2(slave, STDERR_FILENO);
    close(slave);
    close(master);
    execve(child.args[0], child.args.data(), child.envp.data());
    _exit(127);
  }
  CliRun run;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(master, buffer, sizeof(buffer));
    if (n > 0) {
      run.out.append(buffer, std::size_t(n));
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;  // EIO once the child has closed the terminal
    }
  }
  close(master);
  run.code = ExitCode(pid);
  return run;
}

std::string Slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string FirstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

CliDaemon::CliDaemon(fs::path root)
    : root_(std::move(root)) {
  fs::create_directories(root_ / "data");
  fs::create_directories(root_ / "home");
  std::ofstream(root_ / "tokens") << kAliceToken << " alice\nbob-token-0123456789 bob\n";
  fs::permissions(root_ / "tokens", fs::perms::owner_read | fs::perms::owner_write);
}

CliDaemon::~CliDaemon() {
  if (pid_ > 0) {
    kill(pid_, SIGTERM);
    ExitCode(pid_);
  }
}

bool CliDaemon::Start(const std::string& listen, std::string& error) {
  const fs::path port_file = root_ / "port";
  fs::remove(port_file);
  const std::string log_path = (root_ / "dlmfdd.log").string();
  const std::string data = (root_ / "data").string();
  const std::string tokens = (root_ / "tokens").string();
  pid_ = fork();
  if (pid_ == 0) {
    const int log = open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    dup2(log, STDOUT_FILENO);
    dup2(log, STDERR_FILENO);
    execl(kDaemon.c_str(), kDaemon.c_str(), "--listen", listen.c_str(), "--port-file",
          port_file.c_str(), "--data-dir", data.c_str(), "--solver", kSolver.c_str(),
          "--tokens-file", tokens.c_str(), "--max-concurrent", "2", static_cast<char*>(nullptr));
    _exit(127);
  }
  while (!fs::exists(port_file) || fs::file_size(port_file) == 0) {
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) != 0) {
      pid_ = -1;
      error = "dlmfdd exited: " + Slurp(log_path);
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::string port = Slurp(port_file);
  port.erase(port.find_last_not_of(" \n\r\t") + 1);
  server_ = "127.0.0.1:" + port;
  return true;
}

void CliDaemon::Kill(int signal_number) {
  if (pid_ <= 0) return;
  kill(pid_, signal_number);
  ExitCode(pid_);
  pid_ = -1;
}

std::map<std::string, std::string> CliDaemon::Env(bool with_server, bool with_token) const {
  std::map<std::string, std::string> env = {{"HOME", (root_ / "home").string()},
                                            {"PATH", "/usr/bin:/bin"}};
  if (with_server) env["DLMFD_SERVER"] = server_;
  if (with_token) env["DLMFD_TOKEN"] = kAliceToken;
  // A sanitizer build's options (scripts/test.sh: the leak suppressions among them) reach the CLI.
  for (const char* name : {"ASAN_OPTIONS", "LSAN_OPTIONS", "UBSAN_OPTIONS"}) {
    if (const char* value = std::getenv(name)) env[name] = value;
  }
  return env;
}

}  // namespace dlmfd::testing
