// dlmfd watch JOB [--json] [--snapshots] [--from-seq N] [--reconnect-seconds S]
// dlmfd watch --study S | --tag T... [--json] [--interval SECONDS]
// Exit status: 0 when the job (every job of the study) completed, 1 when one failed or was
// cancelled, 130 on Ctrl-C (the jobs go on), or the code of the rpc error.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_selection.h"
#include "progress_printer.h"
#include "rpc_status.h"
#include "study_watch.h"
#include "watch_session.h"

namespace dlmfd::cli {

int RunWatch(int argc, char** argv) {
  CLI::App app{"Follow a job, or a study, to its end."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  WatchOptions options;
  JobSelection selection;
  bool json = false;
  double interval = 1.0;
  auto* job_option = app.add_option("job", options.job_id, "job id");
  AddSelectionFlags(app, selection, job_option);
  app.add_flag("--json", json, "print every event (a study: every change) as one JSON line");
  app.add_flag("--snapshots", options.include_snapshots, "with --json: include trA snapshots");
  app.add_option("--snapshot-width", options.snapshot_max_width,
                 "downsample snapshots to this many nodes in x");
  app.add_option("--snapshot-height", options.snapshot_max_height, "... and in y");
  app.add_option("--from-seq", options.from_seq, "start after this event sequence number")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--reconnect-seconds", options.reconnect_seconds,
                 "give up after this long without the daemon")
      ->check(CLI::PositiveNumber);
  app.add_option("--interval", interval, "a study: seconds between looks (default 1)")
      ->check(CLI::Range(0.1, 3600.0));
  if (auto code = ParseArgs(app, argc, argv)) return *code;
  if (options.job_id.empty() && selection.empty())
    return ReportError("watch", "name a job id, --study ID or --tag T", kExitUsage);
  if (!json) options.include_snapshots = false;

  return Guarded("watch", [&] {
    Connection connection(connection_flags);
    if (!selection.empty()) {
      return WatchStudy(connection, selection, ChoosePrintMode(json), std::cout, interval);
    }
    ProgressPrinter printer(options.job_id, ChoosePrintMode(json), std::cout);
    const WatchOutcome outcome = WatchJob(
        connection, options, [&](const v1::WatchEvent& e) { return printer.OnEvent(e); },
        [&](const grpc::Status& s, double delay) { printer.OnReconnect(s, delay); });
    return printer.Finish(outcome, "watch");
  });
}

}  // namespace dlmfd::cli
