// dlmfd sweep SCENE --grid key=v1,v2,... [--grid ...] [--set k=v]... [--tag T]... [--priority P]
// One job per point of the Cartesian product of the axes. Values are split at commas outside
// brackets and quotes, so a vector value stays whole: --grid 'particles.0.center=[1,7],[1,6]'.
#include <filesystem>
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_text.h"
#include "rpc_status.h"

namespace dlmfd::cli {
namespace {

v1::SweepAxis ParseAxis(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    throw UsageError("--grid " + text + ": expected key=value1,value2,...");
  }
  v1::SweepAxis axis;
  axis.set_key(text.substr(0, eq));
  std::string current;
  int depth = 0;
  bool quoted = false;
  for (std::size_t k = eq + 1; k <= text.size(); ++k) {
    const char c = k < text.size() ? text[k] : ',';
    if (c == '"') quoted = !quoted;
    if (!quoted && (c == '[' || c == '{')) ++depth;
    if (!quoted && (c == ']' || c == '}')) --depth;
    if (c == ',' && depth == 0 && !quoted) {
      if (current.empty()) throw UsageError("--grid " + text + ": an empty value");
      axis.add_values(current);
      current.clear();
    } else {
      current += c;
    }
  }
  return axis;
}

}  // namespace

int RunSweep(int argc, char** argv) {
  CLI::App app{"Queue one job per point of a parameter grid."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string scene_path, name, request_id;
  std::vector<std::string> grids, overrides, tags;
  int priority = 0;
  bool json = false;
  app.add_option("scene", scene_path, "base scene file (TOML)")->required();
  app.add_option("--grid", grids, "an axis: key=v1,v2,... (repeatable; the grid is their product)")
      ->required();
  app.add_option("--set", overrides, "override for every point: key=value (repeatable)");
  app.add_option("--tag", tags, "label every job (repeatable)");
  app.add_option("--priority", priority, "higher runs first, -1000..1000")
      ->check(CLI::Range(-1000, 1000));
  app.add_option("--name", name, "sweep name (default: the scene file's stem)");
  app.add_option("--request-id", request_id, "idempotency key (default: a fresh random id)");
  app.add_flag("--json", json, "print the response as one JSON line");
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("sweep", [&] {
    v1::SubmitSweepRequest request;
    request.set_scene(ReadInputFile(scene_path));
    for (const std::string& g : grids) *request.add_axes() = ParseAxis(g);
    for (const std::string& o : overrides) {
      if (o.find('=') == std::string::npos) throw UsageError("--set " + o + ": expected key=value");
      request.add_overrides(o);
    }
    for (const std::string& t : tags) request.add_tags(t);
    request.set_priority(priority);
    request.set_name(name.empty() ? std::filesystem::path(scene_path).stem().string() : name);
    request.set_client_request_id(request_id.empty() ? NewRequestId() : request_id);
    Connection connection(connection_flags);
    auto context = connection.UnaryContext();
    v1::SubmitSweepResponse response;
    const grpc::Status status = connection.jobs().SubmitSweep(context.get(), request, &response);
    if (!status.ok()) return ReportRpcError("sweep", status);
    if (json) {
      std::cout << ToJsonLine(response) << "\n";
      return kExitOk;
    }
    std::cout << "sweep " << response.sweep_id() << ": " << response.jobs_size() << " jobs\n"
              << JobTable({response.jobs().begin(), response.jobs().end()});
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
