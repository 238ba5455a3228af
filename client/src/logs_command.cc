// dlmfd logs JOB [--follow] [--level L]
// Prints the job's solver log (DATA/jobs/ID/solver.log on the daemon, kept after the end: the
// solver's log lines and progress lines) as it is now and returns; with --follow it goes on
// printing what the solver adds until the job ends. --level hides log lines below a level (a line
// "[...] [dlmfd-solve] [info] ..." has the level info; lines without one are always shown).
#include <chrono>
#include <csignal>
#include <iostream>
#include <sstream>
#include <thread>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "rpc_status.h"

namespace dlmfd::cli {
namespace {

constexpr const char* kLevels[] = {"trace", "debug", "info", "warning", "error", "critical"};

// The rank of a level name (spdlog writes "warning", users may say "warn"); -1 if it is none.
int LevelRank(const std::string& level) {
  if (level == "warn") return 3;
  for (int k = 0; k < 6; ++k) {
    if (level == kLevels[k]) return k;
  }
  return -1;
}

// The level of a spdlog line "[time] [logger] [level] text"; -1 for any other line.
int LineLevel(const std::string& line) {
  size_t at = 0;
  for (int field = 0; field < 3; ++field) {
    const size_t open = line.find('[', at);
    const size_t close = open == std::string::npos ? open : line.find(']', open);
    if (close == std::string::npos) return -1;
    if (field == 2) return LevelRank(line.substr(open + 1, close - open - 1));
    at = close + 1;
  }
  return -1;
}

volatile std::sig_atomic_t g_interrupted = 0;

}  // namespace

int RunLogs(int argc, char** argv) {
  CLI::App app{"Print a job's solver log."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string job_id, level = "trace";
  bool follow = false;
  app.add_option("job", job_id, "job id")->required();
  app.add_flag("--follow,-f", follow, "keep printing until the job ends");
  app.add_option("--level", level, "lowest level shown")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error"}));
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("logs", [&] {
    Connection connection(connection_flags);
    const int lowest = LevelRank(level);
    std::signal(SIGINT, [](int) { g_interrupted = 1; });
    std::string partial;  // a line not yet ended
    int64_t offset = 0;
    auto print = [&](const std::string& text, bool flush_partial) {
      std::istringstream lines(partial + text);
      partial.clear();
      std::string line;
      while (std::getline(lines, line)) {
        if (lines.eof() && !flush_partial) {
          partial = line;  // the log's last line may still be growing
          break;
        }
        if (LineLevel(line) < 0 || LineLevel(line) >= lowest) std::cout << line << "\n";
      }
      std::cout.flush();
    };
    while (!g_interrupted) {
      v1::ReadLogRequest request;
      request.set_job_id(job_id);
      request.set_offset(offset);
      v1::LogChunk chunk;
      auto context = connection.UnaryContext();
      const grpc::Status status = connection.jobs().ReadLog(context.get(), request, &chunk);
      if (!status.ok()) return ReportRpcError("logs", status);
      offset += static_cast<int64_t>(chunk.data().size());
      const bool caught_up = offset >= chunk.size();
      const bool last = caught_up && (chunk.finished() || !follow);
      print(chunk.data(), last);
      if (last) return kExitOk;
      if (caught_up) std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
    print("", true);
    return kExitInterrupted;
  });
}

}  // namespace dlmfd::cli
