// dlmfd priority JOB N
// Sets the priority of a queued or running job (-1000 to 1000; higher runs first).
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "rpc_status.h"

namespace dlmfd::cli {

int RunPriority(int argc, char** argv) {
  CLI::App app{"Change the priority of a queued job."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string job_id;
  int priority = 0;
  app.add_option("job", job_id, "job id")->required();
  app.add_option("priority", priority, "-1000 to 1000; higher runs first")->required();
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("priority", [&] {
    Connection connection(connection_flags);
    v1::SetPriorityRequest request;
    request.set_job_id(job_id);
    request.set_priority(priority);
    v1::Job job;
    auto context = connection.UnaryContext();
    const grpc::Status status = connection.jobs().SetPriority(context.get(), request, &job);
    if (!status.ok()) return ReportRpcError("priority", status);
    std::cout << job.id() << " priority " << job.priority() << "\n";
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
