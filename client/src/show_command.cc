// dlmfd show JOB [--json]  |  dlmfd show --study S [--json]  |  dlmfd show --tag T... [--json]
// A study shows its axes, limit and counts, then its jobs; a tag its counts, then its jobs.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_selection.h"
#include "job_text.h"
#include "rpc_status.h"
#include "study_text.h"

namespace dlmfd::cli {

int RunShow(int argc, char** argv) {
  CLI::App app{"Show one job, or a study."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string job_id;
  JobSelection selection;
  bool json = false;
  auto* job_option = app.add_option("job", job_id, "job id");
  AddSelectionFlags(app, selection, job_option);
  app.add_flag("--json", json, "the job (or the study, then its jobs) as JSON lines");
  if (auto code = ParseArgs(app, argc, argv)) return *code;
  if (job_id.empty() && selection.empty())
    return ReportError("show", "name a job id, --study ID or --tag T", kExitUsage);

  return Guarded("show", [&] {
    Connection connection(connection_flags);
    if (!job_id.empty()) {
      auto context = connection.UnaryContext();
      v1::GetRequest request;
      request.set_job_id(job_id);
      v1::Job job;
      const grpc::Status status = connection.jobs().Get(context.get(), request, &job);
      if (!status.ok()) return ReportRpcError("show", status);
      std::cout << (json ? ToJsonLine(job) + "\n" : JobDetails(job));
      return kExitOk;
    }
    if (!selection.study.empty()) {
      auto context = connection.UnaryContext();
      v1::GetStudyRequest request;
      request.set_study_id(selection.study);
      v1::Study study;
      const grpc::Status status = connection.jobs().GetStudy(context.get(), request, &study);
      if (!status.ok()) return ReportRpcError("show", status);
      std::cout << (json ? ToJsonLine(study) + "\n" : StudyDetails(study));
    }
    std::vector<v1::Job> jobs;
    const grpc::Status status = SelectJobs(connection, selection, jobs);
    if (!status.ok()) return ReportRpcError("show", status);
    if (jobs.empty() && selection.study.empty()) {
      return ReportError("show", "no job carries " + SelectionName(selection), kExitNotFound);
    }
    if (json) {
      for (const v1::Job& job : jobs) std::cout << ToJsonLine(job) << "\n";
      return kExitOk;
    }
    if (selection.study.empty()) {
      const StudyCounts counts = CountJobs(jobs);
      std::cout << FitToWidth(StudyFields(SelectionName(selection), counts, -1), std::string::npos)
                << "\n";
    }
    std::cout << JobTable(jobs);
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
