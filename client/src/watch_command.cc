// dlmfd watch JOB [--json] [--snapshots] [--from-seq N] [--reconnect-seconds S]
// Exit status: 0 when the job completed, 1 when it failed or was cancelled, 130 on Ctrl-C (the
// job goes on), or the code of the rpc error.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "progress_printer.h"
#include "watch_session.h"

namespace dlmfd::cli {

int RunWatch(int argc, char** argv) {
  CLI::App app{"Follow a job to its end."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  WatchOptions options;
  bool json = false;
  app.add_option("job", options.job_id, "job id")->required();
  app.add_flag("--json", json, "print every event as one JSON line (NDJSON)");
  app.add_flag("--snapshots", options.include_snapshots, "with --json: include trA snapshots");
  app.add_option("--snapshot-width", options.snapshot_max_width,
                 "downsample snapshots to this many nodes in x");
  app.add_option("--snapshot-height", options.snapshot_max_height, "... and in y");
  app.add_option("--from-seq", options.from_seq, "start after this event sequence number")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--reconnect-seconds", options.reconnect_seconds,
                 "give up after this long without the daemon")
      ->check(CLI::PositiveNumber);
  if (auto code = ParseArgs(app, argc, argv)) return *code;
  if (!json) options.include_snapshots = false;

  return Guarded("watch", [&] {
    Connection connection(connection_flags);
    ProgressPrinter printer(options.job_id, ChoosePrintMode(json), std::cout);
    const WatchOutcome outcome = WatchJob(
        connection, options, [&](const v1::WatchEvent& e) { return printer.OnEvent(e); },
        [&](const grpc::Status& s, double delay) { printer.OnReconnect(s, delay); });
    return printer.Finish(outcome, "watch");
  });
}

}  // namespace dlmfd::cli
