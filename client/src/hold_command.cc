// dlmfd hold JOB...  |  dlmfd release JOB...
// Hold keeps queued jobs from starting (they stay QUEUED, marked held); release lets them start.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_text.h"
#include "rpc_status.h"

namespace dlmfd::cli {
namespace {

int HoldOrRelease(int argc, char** argv, bool hold) {
  const char* name = hold ? "hold" : "release";
  CLI::App app{hold ? "Keep queued jobs from starting." : "Let held jobs start."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::vector<std::string> job_ids;
  app.add_option("job", job_ids, "job ids")->required();
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded(name, [&] {
    Connection connection(connection_flags);
    int worst = kExitOk;
    for (const std::string& id : job_ids) {
      v1::HoldRequest request;
      request.set_job_id(id);
      v1::Job job;
      auto context = connection.UnaryContext();
      const grpc::Status status = hold ? connection.jobs().Hold(context.get(), request, &job)
                                       : connection.jobs().Release(context.get(), request, &job);
      if (!status.ok()) {
        worst = std::max(worst, ReportRpcError(name, status));
        continue;
      }
      std::cout << job.id() << " " << StateName(job.state()) << (job.held() ? " (held)" : "")
                << "\n";
    }
    return worst;
  });
}

}  // namespace

int RunHold(int argc, char** argv) { return HoldOrRelease(argc, argv, true); }
int RunRelease(int argc, char** argv) { return HoldOrRelease(argc, argv, false); }

}  // namespace dlmfd::cli
