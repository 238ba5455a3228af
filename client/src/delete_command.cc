// dlmfd delete JOB... | --study ID  [--force]
// Removes the jobs' records and directories (results, log, inputs) on the daemon. A queued job is
// cancelled first; a running one only with --force (cancelled, then deleted once its solver has
// stopped). Nothing is deleted when one of the jobs cannot be.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "rpc_status.h"

namespace dlmfd::cli {

int RunDelete(int argc, char** argv) {
  CLI::App app{"Delete jobs or a study: their records and results."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::vector<std::string> job_ids;
  std::string study;
  bool force = false;
  auto* jobs_option = app.add_option("job", job_ids, "job ids");
  auto* study_option = app.add_option("--study", study, "every job of this study");
  jobs_option->excludes(study_option);
  app.add_flag("--force", force, "also running jobs (they are cancelled first)");
  if (auto code = ParseArgs(app, argc, argv)) return *code;
  if (job_ids.empty() && study.empty())
    return ReportError("delete", "name job ids or --study ID", kExitUsage);

  return Guarded("delete", [&] {
    Connection connection(connection_flags);
    v1::DeleteRequest request;
    for (const std::string& id : job_ids) request.add_job_ids(id);
    request.set_study_id(study);
    request.set_force(force);
    v1::DeleteResponse response;
    // A forced delete waits for running solvers to stop at a step boundary.
    auto context = connection.StreamContext();
    const grpc::Status status = connection.jobs().Delete(context.get(), request, &response);
    if (!status.ok()) return ReportRpcError("delete", status);
    for (const std::string& id : response.deleted()) std::cout << id << " deleted\n";
    std::cerr << response.deleted_size() << (response.deleted_size() == 1 ? " job" : " jobs")
              << " deleted, " << response.freed_bytes() << " bytes freed\n";
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
