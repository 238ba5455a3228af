#include "solver_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "dlmfd/solver/event_file.h"

namespace dlmfd::server {
namespace {

constexpr int kEventsFd = 3;
constexpr int kLockFd = 4;

std::runtime_error SystemError(const std::string& what) {
  return std::runtime_error(what + ": " + std::strerror(errno));
}

}  // namespace

SolverProcess::~SolverProcess() {
  if (events_fd_ >= 0) close(events_fd_);
  if (pid_ > 0) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
}

void SolverProcess::Start(const LaunchSpec& spec) {
  std::vector<std::string> args = {spec.solver, spec.scene_path, "--out", spec.results_dir};
  for (const auto& o : spec.overrides) {
    args.push_back("--set");
    args.push_back(o);
  }
  args.push_back("--events");
  args.push_back(std::to_string(kEventsFd));
  if (spec.resume) args.push_back("--resume");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // The child's environment, built before fork (setenv is not async-signal-safe).
  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e) {
    const std::string entry(*e);
    bool replaced = false;
    for (const auto& extra : spec.environment) {
      const auto name = extra.substr(0, extra.find('=') + 1);
      replaced = replaced || entry.compare(0, name.size(), name) == 0;
    }
    if (!replaced) env_text.push_back(entry);
  }
  env_text.insert(env_text.end(), spec.environment.begin(), spec.environment.end());
  std::vector<char*> envp;
  for (auto& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);

  int log_fd = open(spec.log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (log_fd < 0) throw SystemError("cannot open " + spec.log_path);
  int pipe_fds[2];
  if (pipe2(pipe_fds, O_CLOEXEC) != 0) {
    close(log_fd);
    throw SystemError("pipe");
  }
  const pid_t parent = getpid();
  const pid_t child = fork();
  if (child < 0) {
    close(log_fd);
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    throw SystemError("fork");
  }
  if (child == 0) {
    // Async-signal-safe calls only from here to exec.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    setpgid(0, 0);
    int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0) dup2(devnull, 0);
    // Move the pipe and the lock above the targets first so that dup2 never clobbers them.
    int events = fcntl(pipe_fds[1], F_DUPFD, 10);
    int lock = spec.lock_fd >= 0 ? fcntl(spec.lock_fd, F_DUPFD, 10) : -1;
    int log = fcntl(log_fd, F_DUPFD, 10);
    if (events < 0 || log < 0) _exit(127);
    dup2(log, 1);
    dup2(log, 2);
    dup2(events, kEventsFd);
    if (lock >= 0) dup2(lock, kLockFd);
    close_range(lock >= 0 ? kLockFd + 1 : kEventsFd + 1, ~0U, 0);
    signal(SIGPIPE, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    execve(argv[0], argv.data(), envp.data());
    static const char kMessage[] = "dlmfdd: cannot execute the solver\n";
    ssize_t ignored = write(2, kMessage, sizeof(kMessage) - 1);
    (void)ignored;
    _exit(127);
  }
  close(log_fd);
  close(pipe_fds[1]);
  events_fd_ = pipe_fds[0];
  std::lock_guard lock(mutex_);
  pid_ = child;
}

void SolverProcess::ReadEvents(const std::function<void(const v1::SolverEvent&)>& on_event) {
  {
    solver::EventFileReader input(events_fd_);
    v1::SolverEvent event;
    while (input.Next(&event)) on_event(event);
  }
  close(events_fd_);
  events_fd_ = -1;
}

SolverExit SolverProcess::Wait() {
  // Wait without reaping so that the pid stays reserved while Signal may still use it.
  siginfo_t info{};
  while (waitid(P_PID, static_cast<id_t>(pid_), &info, WEXITED | WNOWAIT) != 0 && errno == EINTR) {}
  std::lock_guard lock(mutex_);
  int status = 0;
  rusage usage{};
  pid_t reaped = -1;
  while ((reaped = wait4(pid_, &status, 0, &usage)) < 0 && errno == EINTR) {}
  pid_ = -1;
  SolverExit exit;
  if (reaped > 0) {
    exit.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                       1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    exit.peak_memory_bytes = static_cast<int64_t>(usage.ru_maxrss) * 1024;  // KiB
  }
  if (WIFSIGNALED(status)) {
    exit.signalled = true;
    exit.code = WTERMSIG(status);
  } else {
    exit.code = WEXITSTATUS(status);
  }
  return exit;
}

void SolverProcess::Signal(int signal_number) {
  std::lock_guard lock(mutex_);
  if (pid_ > 0) kill(pid_, signal_number);
}

int LockDirectory(const std::string& path, const std::function<bool()>& should_stop) {
  int fd = open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw SystemError("cannot open " + path);
  while (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno != EWOULDBLOCK && errno != EINTR) {
      close(fd);
      throw SystemError("cannot lock " + path);
    }
    if (should_stop()) {
      close(fd);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return fd;
}

}  // namespace dlmfd::server
