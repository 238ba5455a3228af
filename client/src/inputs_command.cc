// dlmfd inputs JOB [--as-run]
// Prints the scene a job was submitted with, headed by its overrides as TOML comments (so the
// output is a scene file again: `dlmfd inputs JOB > scene.toml`); --as-run prints the scene as the
// solver ran it (results/scene.toml: every default filled in, the overrides applied).
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "rpc_status.h"

namespace dlmfd::cli {

int RunInputs(int argc, char** argv) {
  CLI::App app{"Print a job's scene and overrides as submitted, or the scene as run."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string job_id;
  bool as_run = false;
  app.add_option("job", job_id, "job id")->required();
  app.add_flag("--as-run", as_run, "the scene as the solver ran it (defaults and overrides in)");
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("inputs", [&] {
    Connection connection(connection_flags);
    v1::GetInputsRequest request;
    request.set_job_id(job_id);
    v1::JobInputs inputs;
    auto context = connection.UnaryContext();
    const grpc::Status status = connection.jobs().GetInputs(context.get(), request, &inputs);
    if (!status.ok()) return ReportRpcError("inputs", status);
    if (as_run) {
      if (inputs.scene_as_run().empty()) {
        return ReportError(
            "inputs", "job " + job_id + " has no scene as run yet (the solver has not started)",
            kExitNotFound);
      }
      std::cout << inputs.scene_as_run();
      return kExitOk;
    }
    std::cout << "# job " << job_id << ": the scene as submitted";
    if (inputs.overrides().empty()) {
      std::cout << ", without overrides\n";
    } else {
      std::cout << ", run with these overrides (dlmfd-solve --set):\n";
      for (const std::string& o : inputs.overrides()) std::cout << "#   " << o << "\n";
    }
    std::cout << inputs.scene();
    if (!inputs.scene().empty() && inputs.scene().back() != '\n') std::cout << "\n";
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
