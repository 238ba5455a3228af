#include "slurm_commands.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "dlmfd/io/results_writer.h"
#include "job_time_limit.h"

namespace dlmfd::server {

namespace fs = std::filesystem;

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
    << "rm -f " << kSlurmExitFile << " " << kSlurmWarnedFile
    << "\n"
    // Slurm ran the job again (scontrol requeue, a node failure): resume from the checkpoint the
    // attempt before wrote.
    << "resume=" << (job.resume ? "--resume" : "") << "\n"
    << "if [ \"${SLURM_RESTART_COUNT:-0}\" -gt 0 ] && [ -f "
    << ShellQuote(job.results_dir + "/" + ResultsWriter::kCheckpoint)
    << " ]; then resume=--resume; fi\n"
    << "exec 3>>" << kSlurmEventsFile << "\n"
    << ShellQuote(job.solver) << " " << ShellQuote(job.scene_path) << " --out "
    << ShellQuote(job.results_dir);
  for (const auto& o : job.overrides) s << " --set " << ShellQuote(o);
  s << " --events 3 $resume &\n"
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
    // A trap interrupts wait with 128 + its signal; the solver may have ended right after: its
    // own status (127: wait had already returned it).
    << "if [ $status -gt 128 ]; then wait $solver 2>/dev/null; s=$?; [ $s -ne 127 ] && "
       "status=$s; fi\n"
    // The status and the Slurm restart that wrote it: a requeued job's old status is not its end.
    << "echo \"$status ${SLURM_RESTART_COUNT:-0}\" > " << kSlurmExitFile << ".tmp && mv "
    << kSlurmExitFile << ".tmp " << kSlurmExitFile << "\n"
    << "exit $status\n";
  return s.str();
}

std::string ArrayScript(const std::string& name,
                        const std::vector<std::pair<int, std::string>>& task_dirs) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# Written by dlmfdd (server/src/slurm_commands.cc): the job array " << name << ".\n"
    << "# Task I runs the batch script of its job's directory (" << kSlurmScript << ").\n"
    << "case \"$SLURM_ARRAY_TASK_ID\" in\n";
  for (const auto& [index, dir] : task_dirs) {
    s << "  " << index << ") dir=" << ShellQuote(dir) << " ;;\n";
  }
  s << "  *) echo \"dlmfdd: no job for array task $SLURM_ARRAY_TASK_ID\" >&2; exit 2 ;;\n"
    << "esac\n"
    << "exec /bin/bash \"$dir/" << kSlurmScript << "\"\n";
  return s.str();
}

std::string ArraySpec(const std::vector<int>& indices, int throttle) {
  std::string spec;
  for (size_t i = 0; i < indices.size();) {
    size_t j = i;
    while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
    if (!spec.empty()) spec += ",";
    spec += std::to_string(indices[i]);
    if (j > i) spec += "-" + std::to_string(indices[j]);
    i = j + 1;
  }
  if (throttle > 0) spec += "%" + std::to_string(throttle);
  return spec;
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
  if (!job.array.empty()) args.push_back("--array=" + job.array);
  if (job.time_limit_seconds > 0) {
    const int64_t minutes = SlurmTimeMinutes(job.time_limit_seconds);
    args.push_back("--time=" + std::to_string(minutes));
    args.push_back("--signal=B:USR1@" +
                   std::to_string(SlurmSignalLead(minutes, settings.signal_seconds)));
  }
  if (!settings.partition.empty()) args.push_back("--partition=" + settings.partition);
  if (!settings.account.empty()) args.push_back("--account=" + settings.account);
  if (!settings.qos.empty()) args.push_back("--qos=" + settings.qos);
  std::istringstream extra(settings.sbatch_options);
  for (std::string word; extra >> word;) args.push_back(word);
  args.push_back(script_path);
  return args;
}

std::vector<std::string> SqueueOfNameArguments(const std::string& name) {
  return {"--noheader", "--name=" + name, "--states=PENDING,RUNNING,SUSPENDED,CONFIGURING,REQUEUED",
          "--format=%i %Z"};
}

std::string ParseLiveJobIn(const std::string& output, const std::string& job_dir) {
  const auto normal = [](const std::string& dir) {
    fs::path path = fs::path(dir).lexically_normal();
    return (path.has_filename() ? path : path.parent_path()).string();  // no trailing '/'
  };
  const std::string wanted = normal(job_dir);
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    const size_t space = line.find(' ');
    if (space == std::string::npos) continue;
    const std::string id = line.substr(0, space);
    if (normal(line.substr(space + 1)) == wanted) return id;
  }
  return {};
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

namespace {

// The indices of an array task string: "2-5%2", "1,3,7-9", "[2-5%2]".
std::vector<int> TaskIndices(std::string text) {
  text = text.substr(0, text.find('%'));
  std::vector<int> out;
  std::istringstream parts(text);
  for (std::string part; std::getline(parts, part, ',');) {
    part.erase(
        std::remove_if(part.begin(), part.end(), [](char c) { return c == '[' || c == ']'; }),
        part.end());
    if (part.empty() || !std::isdigit(static_cast<unsigned char>(part[0]))) continue;
    const size_t dash = part.find('-');
    const int first = std::atoi(part.c_str());
    const int last = dash == std::string::npos ? first : std::atoi(part.c_str() + dash + 1);
    for (int k = first; k <= last; ++k) out.push_back(k);
  }
  return out;
}

std::optional<SlurmJobStatus> Lookup(const std::map<std::string, SlurmJobStatus>& jobs,
                                     const std::string& id) {
  const auto it = jobs.find(id);
  if (it == jobs.end()) return std::nullopt;
  return it->second;
}

int64_t IntegerOr(const nlohmann::json& job, const char* key, int64_t otherwise) {
  return job.contains(key) && job[key].is_number_integer() ? job[key].get<int64_t>() : otherwise;
}

}  // namespace

std::string ArrayTaskId(const std::string& array_id, int index) {
  return array_id + "_" + std::to_string(index);
}

std::map<std::string, SlurmJobStatus> ParseSqueueJson(const std::string& json) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(json);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("squeue --json printed no JSON: ") + e.what());
  }
  if (!doc.is_object() || !doc.contains("jobs") || !doc["jobs"].is_array()) {
    throw std::runtime_error("squeue --json printed no \"jobs\" array");
  }
  // slurmctld not answering: squeue --json exits 0 with an empty jobs array and the error here.
  if (doc.contains("errors") && doc["errors"].is_array() && !doc["errors"].empty()) {
    const auto& error = doc["errors"][0];
    std::string text = error.is_object() ? error.value("description", std::string()) : "";
    if (error.is_object() && error.contains("source") && error["source"].is_string()) {
      text += " (" + error["source"].get<std::string>() + ")";
    }
    throw std::runtime_error("squeue --json reported an error: " + text);
  }
  std::map<std::string, SlurmJobStatus> out;
  for (const auto& job : doc["jobs"]) {
    if (!job.is_object() || !job.contains("job_id")) continue;
    SlurmJobStatus status;
    const auto& state = job.value("job_state", nlohmann::json());
    if (state.is_string()) {
      status.state = state.get<std::string>();
    } else if (state.is_array() && !state.empty() && state[0].is_string()) {
      status.state = state[0].get<std::string>();
    }
    if (job.contains("state_reason") && job["state_reason"].is_string()) {
      status.reason = job["state_reason"].get<std::string>();
    }
    status.restarts = static_cast<int>(IntegerOr(job, "restart_cnt", 0));
    const int64_t array_id = IntegerOr(job, "array_job_id", 0);
    if (array_id == 0) {
      status.id = std::to_string(IntegerOr(job, "job_id", 0));
      out[status.id] = status;
      continue;
    }
    // An array task of its own, or the array's record of the tasks not started yet.
    const int64_t task = IntegerOr(job, "array_task_id", -1);
    std::vector<int> tasks;
    if (task >= 0) {
      tasks.push_back(static_cast<int>(task));
    } else if (job.contains("array_task_string") && job["array_task_string"].is_string()) {
      tasks = TaskIndices(job["array_task_string"].get<std::string>());
    }
    for (int k : tasks) {
      status.id = ArrayTaskId(std::to_string(array_id), k);
      out[status.id] = status;
    }
  }
  return out;
}

std::optional<SlurmJobStatus> FindInSqueueJson(const std::string& json, const std::string& id) {
  return Lookup(ParseSqueueJson(json), id);
}

std::map<std::string, SlurmJobStatus> ParseJobComp(const std::string& text) {
  std::map<std::string, SlurmJobStatus> out;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    SlurmJobStatus status;
    std::string array_id, task;
    std::istringstream fields(line);
    for (std::string field; fields >> field;) {
      if (field.rfind("JobId=", 0) == 0) status.id = field.substr(6);
      if (field.rfind("JobState=", 0) == 0) status.state = field.substr(9);
      if (field.rfind("ExitCode=", 0) == 0) status.exit_code = field.substr(9);
      if (field.rfind("ArrayJobId=", 0) == 0) array_id = field.substr(11);
      if (field.rfind("ArrayTaskId=", 0) == 0) task = field.substr(12);
    }
    if (status.id.empty()) continue;
    if (!array_id.empty() && !task.empty()) status.id = array_id + "_" + task;
    out[status.id] = status;  // a requeued job has one line per end: the last one counts
  }
  return out;
}

std::optional<SlurmJobStatus> FindInJobComp(const std::string& text, const std::string& id) {
  return Lookup(ParseJobComp(text), id);
}

bool TransientSlurmError(const std::string& err) {
  // slurm 22.05's messages (src/common/slurm_errno.c) for a controller that is down, restarting
  // or overloaded.
  for (const char* text :
       {"Unable to contact slurm controller", "Socket timed out", "Slurm temporarily unable",
        "Zero Bytes were transmitted", "Connection refused", "slurmctld is not responding",
        "Transport endpoint is not connected"}) {
    if (err.find(text) != std::string::npos) return true;
  }
  return false;
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
