// dlmfd retry JOB...  |  dlmfd retry --study S [--state failed,cancelled]  |  --tag T...
//             [--set key=value]... [--json]
// Reruns finished jobs from their stored scene and overrides (plus --set, which replaces an
// override of the same key): each keeps its id and its study, its attempt number goes up and the
// attempt before is recorded (`dlmfd show`). A job that did not complete and runs the same scene
// resumes from its last checkpoint; any other starts afresh.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_selection.h"
#include "job_text.h"
#include "rpc_status.h"

namespace dlmfd::cli {

int RunRetry(int argc, char** argv) {
  CLI::App app{"Rerun finished jobs, in their study."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::vector<std::string> job_ids, states, overrides;
  JobSelection selection;
  bool json = false;
  auto* jobs_option = app.add_option("job", job_ids, "job ids (each must have finished)");
  AddSelectionFlags(app, selection, jobs_option);
  app.add_option("--state", states,
                 "with --study or --tag: the states to rerun, completed|failed|cancelled "
                 "(repeatable or comma list; default failed,cancelled)")
      ->delimiter(',');
  app.add_option("--set", overrides, "change a scene key for the rerun: key=value (repeatable)");
  app.add_flag("--json", json, "one JSON line per requeued job");
  if (auto code = ParseArgs(app, argc, argv)) return *code;
  if (job_ids.empty() && selection.empty())
    return ReportError("retry", "name a job id, --study ID or --tag T", kExitUsage);
  if (!job_ids.empty() && !states.empty())
    return ReportError("retry", "--state goes with --study or --tag", kExitUsage);

  return Guarded("retry", [&] {
    v1::RetryRequest request;
    for (const std::string& o : overrides) {
      SplitKeyValue("--set", o);
      request.add_overrides(o);
    }
    std::vector<v1::JobState> wanted;
    for (const std::string& s : states) wanted.push_back(ParseState(s));
    Connection connection(connection_flags);
    if (!selection.tags.empty()) {
      // A tag is not a study: its jobs in the wanted states are named one by one.
      std::vector<v1::Job> jobs;
      const grpc::Status status = SelectJobs(connection, selection, jobs);
      if (!status.ok()) return ReportRpcError("retry", status);
      if (wanted.empty()) wanted = {v1::FAILED, v1::CANCELLED};
      for (const v1::Job& job : jobs) {
        for (v1::JobState s : wanted) {
          if (job.state() == s) request.add_job_ids(job.id());
        }
      }
      if (request.job_ids_size() == 0) {
        return ReportError("retry", "no job of " + SelectionName(selection) + " to rerun",
                           kExitConflict);
      }
    } else if (!selection.study.empty()) {
      request.set_study_id(selection.study);
      for (v1::JobState s : wanted) request.add_states(s);
    } else {
      for (const std::string& id : job_ids) request.add_job_ids(id);
    }
    auto context = connection.UnaryContext();
    v1::RetryResponse response;
    const grpc::Status status = connection.jobs().Retry(context.get(), request, &response);
    if (!status.ok()) return ReportRpcError("retry", status);
    for (const v1::Job& job : response.jobs()) {
      if (json) {
        std::cout << ToJsonLine(job) << "\n";
      } else {
        std::cout << job.id() << " " << StateName(job.state()) << " (attempt " << job.attempt()
                  << ")\n";
      }
    }
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
