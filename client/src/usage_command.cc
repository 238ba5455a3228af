// dlmfd usage [--json]
// What the caller uses of the daemon (GetUsage): the bytes of their jobs against their disk quota
// (max_user_disk_mb), their jobs per state, and the queue's room (max_queued, shared by every
// user). As Slurm's sshare/sreport and a quota command would: the numbers before a study.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_text.h"
#include "rpc_status.h"

namespace dlmfd::cli {
namespace {

std::string Mebibytes(int64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return text;
}

}  // namespace

int RunUsage(int argc, char** argv) {
  CLI::App app{"Show your disk use against your quota and your jobs per state."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  bool json = false;
  app.add_flag("--json", json, "print the usage as one JSON line");
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("usage", [&] {
    Connection connection(connection_flags);
    auto context = connection.UnaryContext();
    v1::Usage usage;
    const grpc::Status status =
        connection.jobs().GetUsage(context.get(), v1::GetUsageRequest(), &usage);
    if (!status.ok()) return ReportRpcError("usage", status);
    if (json) {
      std::cout << ToJsonLine(usage) << "\n";
      return kExitOk;
    }
    std::cout << "user:        " << usage.user() << "\n"
              << "disk:        " << Mebibytes(usage.disk_bytes());
    if (usage.disk_quota_bytes() > 0) {
      char share[32];
      std::snprintf(share, sizeof share, "%.0f %%",
                    100.0 * static_cast<double>(usage.disk_bytes()) /
                        static_cast<double>(usage.disk_quota_bytes()));
      std::cout << " of " << Mebibytes(usage.disk_quota_bytes()) << " (" << share
                << "; max_user_disk_mb)";
    } else {
      std::cout << " (no quota)";
    }
    std::cout << "\n"
              << "jobs:        " << usage.jobs() << " (queued " << usage.queued() << ", running "
              << usage.running() << ", completed " << usage.completed() << ", failed "
              << usage.failed() << ", cancelled " << usage.cancelled() << ")\n"
              << "queue:       " << usage.queue_unfinished() << " unfinished of "
              << usage.queue_limit() << " (max_queued, every user)\n";
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
