#include "slurm_commands.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace dlmfd::server {

std::string ShellQuote(const std::string& word) {
  std::string out = "'";
  for (char c : word) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

std::string BatchScript(const BatchJob& job) {
  const std::string dir = ShellQuote(job.job_dir);
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# Written by dlmfdd (server/src/slurm_commands.cc): one attempt of job " << job.name
    << ".\n"
    << "# The solver's events go to " << kSlurmEventsFile << " (fd 3), its exit status to "
    << kSlurmExitFile << ".\n"
    << "cd " << dir << " || exit 1\n"
    << "export OMP_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-" << job.threads << "}\"\n"
    << "rm -f " << kSlurmExitFile << " " << kSlurmWarnedFile << "\n"
    << "exec 3>>" << kSlurmEventsFile << "\n"
    << ShellQuote(job.solver) << " " << ShellQuote(job.scene_path) << " --out "
    << ShellQuote(job.results_dir);
  for (const auto& o : job.overrides) s << " --set " << ShellQuote(o);
  s << " --events 3" << (job.resume ? " --resume" : "") << " &\n"
    << "solver=$!\n"
    << "exec 3>&-\n"
    // Slurm's warning before the time limit and scancel's SIGTERM: the solver checkpoints.
    << "trap 'touch " << kSlurmWarnedFile << "; kill -TERM $solver 2>/dev/null' USR1\n"
    << "trap 'kill -TERM $solver 2>/dev/null' TERM\n"
    << "status=0\n"
    << "while :; do\n"
    << "  wait $solver; status=$?\n"
    << "  kill -0 $solver 2>/dev/null || break\n"
    << "done\n"
    << "echo $status > " << kSlurmExitFile << ".tmp && mv " << kSlurmExitFile << ".tmp "
    << kSlurmExitFile << "\n"
    << "exit $status\n";
  return s.str();
}

std::vector<std::string> SbatchArguments(const BatchJob& job, const SlurmSettings& settings,
                                         const std::string& script_path) {
  std::vector<std::string> args = {
      "--parsable",
      "--job-name=" + job.name,
      "--cpus-per-task=" + std::to_string(job.threads),
      "--ntasks=1",
      "--mem=" + std::to_string(std::max<int64_t>(1, job.memory_mb)) + "M",
      "--output=" + job.log_path,
      "--open-mode=append",
      "--chdir=" + job.job_dir};
  if (settings.time_limit_minutes > 0) {
    args.push_back("--time=" + std::to_string(settings.time_limit_minutes));
    args.push_back("--signal=B:USR1@" + std::to_string(settings.signal_seconds));
  }
  if (!settings.partition.empty()) args.push_back("--partition=" + settings.partition);
  if (!settings.account.empty()) args.push_back("--account=" + settings.account);
  if (!settings.qos.empty()) args.push_back("--qos=" + settings.qos);
  std::istringstream extra(settings.sbatch_options);
  for (std::string word; extra >> word;) args.push_back(word);
  args.push_back(script_path);
  return args;
}

std::string ParseSbatchId(const std::string& output) {
  std::string line = output.substr(0, output.find('\n'));
  line = line.substr(0, line.find(';'));
  const bool digits = !line.empty() && line.find_first_not_of("0123456789") == std::string::npos;
  if (!digits) {
    throw std::runtime_error("sbatch --parsable printed no job id: \"" + output.substr(0, 200) +
                             "\"");
  }
  return line;
}

std::optional<SlurmJobStatus> FindInSqueueJson(const std::string& json, const std::string& id) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(json);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("squeue --json printed no JSON: ") + e.what());
  }
  if (!doc.is_object() || !doc.contains("jobs") || !doc["jobs"].is_array()) {
    throw std::runtime_error("squeue --json printed no \"jobs\" array");
  }
  for (const auto& job : doc["jobs"]) {
    if (!job.contains("job_id") || std::to_string(job["job_id"].get<int64_t>()) != id) continue;
    SlurmJobStatus status;
    status.id = id;
    const auto& state = job.value("job_state", nlohmann::json());
    if (state.is_string()) {
      status.state = state.get<std::string>();
    } else if (state.is_array() && !state.empty() && state[0].is_string()) {
      status.state = state[0].get<std::string>();
    }
    if (job.contains("state_reason") && job["state_reason"].is_string()) {
      status.reason = job["state_reason"].get<std::string>();
    }
    if (job.contains("restart_cnt") && job["restart_cnt"].is_number_integer()) {
      status.restarts = job["restart_cnt"].get<int>();
    }
    return status;
  }
  return std::nullopt;
}

std::optional<SlurmJobStatus> FindInJobComp(const std::string& text, const std::string& id) {
  std::optional<SlurmJobStatus> found;
  std::istringstream lines(text);
  const std::string key = "JobId=" + id + " ";
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(key, 0) != 0) continue;
    SlurmJobStatus status;
    status.id = id;
    std::istringstream fields(line);
    for (std::string field; fields >> field;) {
      if (field.rfind("JobState=", 0) == 0) status.state = field.substr(9);
      if (field.rfind("ExitCode=", 0) == 0) status.exit_code = field.substr(9);
    }
    found = status;
  }
  return found;
}

namespace {

// Reads both pipes to their ends without letting either fill up.
void Drain(int out_fd, int err_fd, CommandResult& result) {
  pollfd fds[2] = {{out_fd, POLLIN, 0}, {err_fd, POLLIN, 0}};
  std::string* sinks[2] = {&result.out, &result.err};
  int open = 2;
  char buffer[4096];
  while (open > 0) {
    if (poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t n = read(fds[i].fd, buffer, sizeof buffer);
      if (n > 0) {
        sinks[i]->append(buffer, static_cast<size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        close(fds[i].fd);
        fds[i].fd = -1;
        --open;
      }
    }
  }
}

}  // namespace

CommandResult RunCommand(const std::vector<std::string>& argv) {
  CommandResult result;
  if (argv.empty()) return result;
  int out[2], err[2];
  if (pipe2(out, O_CLOEXEC) != 0) return result;
  if (pipe2(err, O_CLOEXEC) != 0) {
    close(out[0]);
    close(out[1]);
    return result;
  }
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(out[1], STDOUT_FILENO);
    dup2(err[1], STDERR_FILENO);
    const int null_fd = open("/dev/null", O_RDONLY);
    if (null_fd >= 0) dup2(null_fd, STDIN_FILENO);
    execvp(args[0], args.data());
    _exit(127);
  }
  close(out[1]);
  close(err[1]);
  if (pid < 0) {
    close(out[0]);
    close(err[0]);
    result.err = "cannot fork to run " + argv[0];
    return result;
  }
  Drain(out[0], err[0], result);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (result.status == 127 && result.err.empty()) result.err = argv[0] + ": command not found";
  return result;
}

}  // namespace dlmfd::server
