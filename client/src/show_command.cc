// dlmfd show JOB [--json]
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_text.h"
#include "rpc_status.h"

namespace dlmfd::cli {

int RunShow(int argc, char** argv) {
  CLI::App app{"Show one job."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string job_id;
  bool json = false;
  app.add_option("job", job_id, "job id")->required();
  app.add_flag("--json", json, "the job as one JSON line");
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("show", [&] {
    Connection connection(connection_flags);
    auto context = connection.UnaryContext();
    v1::GetRequest request;
    request.set_job_id(job_id);
    v1::Job job;
    const grpc::Status status = connection.jobs().Get(context.get(), request, &job);
    if (!status.ok()) return ReportRpcError("show", status);
    std::cout << (json ? ToJsonLine(job) + "\n" : JobDetails(job));
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
