// dlmfd cancel JOB...  |  dlmfd cancel --sweep ID
// A running job stops at a step boundary and keeps its partial results; the reply may still say
// "running (cancel requested)" until the solver has exited.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_text.h"
#include "rpc_status.h"

namespace dlmfd::cli {

int RunCancel(int argc, char** argv) {
  CLI::App app{"Cancel jobs or a sweep."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::vector<std::string> job_ids;
  std::string sweep;
  auto* jobs_option = app.add_option("job", job_ids, "job ids");
  auto* sweep_option =
      app.add_option("--sweep", sweep, "cancel every unfinished job of this sweep");
  jobs_option->excludes(sweep_option);
  if (auto code = ParseArgs(app, argc, argv)) return *code;
  if (job_ids.empty() && sweep.empty())
    return ReportError("cancel", "name a job id or --sweep ID", kExitUsage);

  return Guarded("cancel", [&] {
    Connection connection(connection_flags);
    if (!sweep.empty()) {
      auto context = connection.UnaryContext();
      v1::CancelSweepRequest request;
      request.set_sweep_id(sweep);
      v1::CancelSweepResponse response;
      const grpc::Status status = connection.jobs().CancelSweep(context.get(), request, &response);
      if (!status.ok()) return ReportRpcError("cancel", status);
      std::cout << JobTable({response.jobs().begin(), response.jobs().end()});
      return kExitOk;
    }
    int worst = kExitOk;
    for (const std::string& id : job_ids) {
      auto context = connection.UnaryContext();
      v1::CancelRequest request;
      request.set_job_id(id);
      v1::Job job;
      const grpc::Status status = connection.jobs().Cancel(context.get(), request, &job);
      if (!status.ok()) {
        worst = std::max(worst, ReportRpcError("cancel", status));
        continue;
      }
      std::cout << job.id() << " " << StateName(job.state())
                << (job.reason().empty() ? "" : " (" + job.reason() + ")") << "\n";
    }
    return worst;
  });
}

}  // namespace dlmfd::cli
