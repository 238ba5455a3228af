// dlmfd logs JOB [--follow] [--level L]
// Prints the log lines the daemon still holds for the job ("time level text"); with --follow it
// goes on until the job ends. Without it, it stops at the job's latest event (Get's last_seq).
#include <cstdio>
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_text.h"
#include "rpc_status.h"
#include "watch_session.h"

namespace dlmfd::cli {
namespace {

int LevelRank(const std::string& level) {
  const char* order[] = {"trace", "debug", "info", "warn", "error"};
  for (int k = 0; k < 5; ++k) {
    if (level == order[k]) return k;
  }
  return 2;
}

}  // namespace

int RunLogs(int argc, char** argv) {
  CLI::App app{"Print a job's log lines."};
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
    v1::Job job;
    {
      auto context = connection.UnaryContext();
      v1::GetRequest request;
      request.set_job_id(job_id);
      const grpc::Status status = connection.jobs().Get(context.get(), request, &job);
      if (!status.ok()) return ReportRpcError("logs", status);
    }
    const std::int64_t stop_at = job.last_seq();
    int printed = 0;
    WatchOptions options;
    options.job_id = job_id;
    const WatchOutcome outcome = WatchJob(connection, options, [&](const v1::WatchEvent& e) {
      if (e.has_log() && LevelRank(e.log().level()) >= LevelRank(level)) {
        std::cout << FormatTimestamp(e.wall_time()) << " " << e.log().level() << " "
                  << e.log().text() << "\n";
        ++printed;
      } else if (e.has_gap()) {
        std::cout << "-- events " << e.gap().from_seq() << "-" << e.gap().to_seq() << " not held ("
                  << e.gap().reason() << ")\n";
      }
      return follow || e.seq() < stop_at;
    });
    std::cout.flush();
    if (outcome.interrupted) return kExitInterrupted;
    if (!outcome.status.ok()) return ReportRpcError("logs", outcome.status);
    if (printed == 0) std::cerr << "no log lines held for job " << job_id << "\n";
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
