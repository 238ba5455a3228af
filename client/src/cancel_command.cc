// dlmfd cancel JOB...  |  dlmfd cancel --study ID  |  dlmfd cancel --tag T...
// A running job stops at a step boundary and keeps its partial results; the reply may still say
// "running (cancel requested)" until the solver has exited. For a study or a tag, the unfinished
// jobs are cancelled and the finished ones left as they are.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_selection.h"
#include "job_text.h"
#include "rpc_status.h"

namespace dlmfd::cli {
namespace {

// Cancels one job; prints its state or reports the error. Returns the exit code.
int CancelOne(Connection& connection, const std::string& id) {
  auto context = connection.UnaryContext();
  v1::CancelRequest request;
  request.set_job_id(id);
  v1::Job job;
  const grpc::Status status = connection.jobs().Cancel(context.get(), request, &job);
  if (!status.ok()) return ReportRpcError("cancel", status);
  std::cout << job.id() << " " << StateName(job.state())
            << (job.reason().empty() ? "" : " (" + job.reason() + ")") << "\n";
  return kExitOk;
}

}  // namespace

int RunCancel(int argc, char** argv) {
  CLI::App app{"Cancel jobs, a study, or the jobs of a tag."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::vector<std::string> job_ids;
  JobSelection selection;
  auto* jobs_option = app.add_option("job", job_ids, "job ids");
  AddSelectionFlags(app, selection, jobs_option);
  if (auto code = ParseArgs(app, argc, argv)) return *code;
  if (job_ids.empty() && selection.empty())
    return ReportError("cancel", "name a job id, --study ID or --tag T", kExitUsage);

  return Guarded("cancel", [&] {
    Connection connection(connection_flags);
    if (!selection.study.empty() && selection.tags.empty()) {
      auto context = connection.UnaryContext();
      v1::CancelStudyRequest request;
      request.set_study_id(selection.study);
      v1::CancelStudyResponse response;
      const grpc::Status status = connection.jobs().CancelStudy(context.get(), request, &response);
      if (!status.ok()) return ReportRpcError("cancel", status);
      std::cout << JobTable({response.jobs().begin(), response.jobs().end()});
      return kExitOk;
    }
    if (!selection.empty()) {
      std::vector<v1::Job> jobs;
      const grpc::Status status = SelectJobs(connection, selection, jobs);
      if (!status.ok()) return ReportRpcError("cancel", status);
      if (jobs.empty()) {
        return ReportError("cancel", "no job carries " + SelectionName(selection), kExitNotFound);
      }
      for (const v1::Job& job : jobs) {
        if (!IsFinal(job.state())) job_ids.push_back(job.id());
      }
      if (job_ids.empty())
        std::cerr << "every job of " << SelectionName(selection) << " has finished\n";
    }
    int worst = kExitOk;
    for (const std::string& id : job_ids) worst = std::max(worst, CancelOne(connection, id));
    return worst;
  });
}

}  // namespace dlmfd::cli
