// dlmfd submit SCENE [--set key=value]... [--tag T]... [--label k=v]... [--priority P] [--name N]
// [--time DURATION] [--after ID[,ID]...] [--wait [--json]] Prints the job id alone on stdout, so
// that JOB=$(dlmfd submit --wait ...) captures it; --wait's progress goes to stderr (with --json
// every event goes to stdout, one JSON line each, after the job). Submit is retried on UNAVAILABLE
// with the same client request id, so a retry never queues the job twice.
#include <filesystem>
#include <iostream>
#include <thread>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_text.h"
#include "progress_printer.h"
#include "rpc_status.h"
#include "watch_session.h"

namespace dlmfd::cli {

int RunSubmit(int argc, char** argv) {
  CLI::App app{"Queue a scene file as a job."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string scene_path, name, request_id, time_limit;
  std::vector<std::string> overrides, tags, labels, after;
  int priority = 0;
  bool wait = false, json = false;
  app.add_option("scene", scene_path, "scene file (TOML)")->required();
  app.add_option("--set", overrides,
                 "override a scene key: --set fluid.relaxation_time=2 (repeatable)");
  app.add_option("--tag", tags, "tag the job (repeatable)");
  app.add_option("--label", labels, "a key=value label (repeatable)");
  app.add_option("--priority", priority, "higher runs first, -1000..1000")
      ->check(CLI::Range(-1000, 1000));
  app.add_option("--name", name, "job name (default: the scene file's stem)");
  app.add_option("--time", time_limit,
                 "wall-time limit of one run: 90m, 2h, 1h30m, 1:30:00 (default: the daemon's)");
  app.add_option("--after", after,
                 "start only once these jobs have COMPLETED: ID[,ID] (repeatable; one that "
                 "fails or is cancelled cancels this job)")
      ->delimiter(',');
  app.add_option("--request-id", request_id, "idempotency key (default: a fresh random id)");
  app.add_flag("--wait", wait, "watch the job to the end; exit 0 if it completed, 1 if not");
  app.add_flag("--json", json, "print the job (and with --wait every event) as JSON lines");
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("submit", [&] {
    v1::SubmitRequest request;
    request.set_scene(ReadInputFile(scene_path));
    for (const std::string& o : overrides) {
      if (o.find('=') == std::string::npos) throw UsageError("--set " + o + ": expected key=value");
      request.add_overrides(o);
    }
    for (const std::string& t : tags) request.add_tags(t);
    for (const std::string& id : after) request.add_after(id);
    AddLabels(labels, request.mutable_labels());
    request.set_priority(priority);
    if (!time_limit.empty()) request.set_time_limit_seconds(TimeLimitFlag(time_limit));
    request.set_name(name.empty() ? std::filesystem::path(scene_path).stem().string() : name);
    request.set_client_request_id(request_id.empty() ? NewRequestId() : request_id);

    Connection connection(connection_flags);
    v1::Job job;
    grpc::Status status;
    for (int attempt = 0; attempt < 4; ++attempt) {
      auto context = connection.UnaryContext();
      status = connection.jobs().Submit(context.get(), request, &job);
      if (status.error_code() != grpc::StatusCode::UNAVAILABLE) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(250 << attempt));
    }
    if (!status.ok()) return ReportRpcError("submit", status);
    if (json) {
      std::cout << ToJsonLine(job) << "\n";
    } else {
      std::cout << job.id() << "\n";
      std::cerr << "submitted " << job.name() << " as job " << job.id() << " ("
                << StateName(job.state()) << ")\n";
    }
    std::cout.flush();
    if (!wait) return kExitOk;
    // The id is the output; what the job does meanwhile is for the person watching (issue 38).
    std::ostream& progress = json ? std::cout : std::cerr;
    ProgressPrinter printer(job.id(), ChoosePrintMode(json, json ? 1 : 2), progress);
    WatchOptions options;
    options.job_id = job.id();
    const WatchOutcome outcome = WatchJob(
        connection, options, [&](const v1::WatchEvent& e) { return printer.OnEvent(e); },
        [&](const grpc::Status& s, double delay) { printer.OnReconnect(s, delay); });
    return printer.Finish(outcome, "submit");
  });
}

}  // namespace dlmfd::cli
