// dlmfd study SCENE [--grid key=v1,v2,...]... [--zip key=v1,v2,...]... [--range key=A:B:N]...
//                   [--log-range key=A:B:N]... [--set k=v]... [--tag T]... [--label k=v]...
//                   [--max-running N] [--priority P] [--name NAME] [--time DURATION]
//                   [--after ID[,ID]...]
// A study: one job per point. --grid and the ranges are axes of a full grid (the Cartesian
// product); the --zip axes step together (equal lengths) and are one axis of that grid. A key may
// hold * for every index (`particles.*.density`). Values are split at commas outside brackets and
// quotes, so a vector value stays whole: --grid 'particles.0.center=[1,7],[1,6]'.
#include <filesystem>
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_text.h"
#include "rpc_status.h"

namespace dlmfd::cli {
namespace {

v1::StudyAxis ParseAxis(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    throw UsageError("--grid/--zip " + text + ": expected key=value1,value2,...");
  }
  v1::StudyAxis axis;
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
      if (current.empty()) throw UsageError("--grid/--zip " + text + ": an empty value");
      axis.add_values(current);
      current.clear();
    } else {
      current += c;
    }
  }
  return axis;
}

// key=START:STOP:COUNT as a range axis.
v1::StudyAxis ParseRange(const std::string& flag, const std::string& text, bool logarithmic) {
  const auto eq = text.find('=');
  const std::string usage = flag + " " + text + ": expected key=START:STOP:COUNT";
  if (eq == std::string::npos || eq == 0) throw UsageError(usage);
  v1::StudyAxis axis;
  axis.set_key(text.substr(0, eq));
  const std::string spec = text.substr(eq + 1);
  const auto c1 = spec.find(':');
  const auto c2 = c1 == std::string::npos ? c1 : spec.find(':', c1 + 1);
  if (c2 == std::string::npos) throw UsageError(usage);
  try {
    std::size_t used = 0;
    const std::string a = spec.substr(0, c1), b = spec.substr(c1 + 1, c2 - c1 - 1),
                      n = spec.substr(c2 + 1);
    axis.mutable_range()->set_start(std::stod(a, &used));
    if (used != a.size()) throw UsageError(usage);
    axis.mutable_range()->set_stop(std::stod(b, &used));
    if (used != b.size()) throw UsageError(usage);
    axis.mutable_range()->set_count(std::stoi(n, &used));
    if (used != n.size()) throw UsageError(usage);
  } catch (const std::logic_error&) {
    throw UsageError(usage);
  }
  axis.mutable_range()->set_logarithmic(logarithmic);
  return axis;
}

}  // namespace

int RunStudy(int argc, char** argv) {
  CLI::App app{"Queue one job per point of a parameter grid."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string scene_path, name, request_id, time_limit;
  std::vector<std::string> grids, zips, ranges, log_ranges, overrides, tags, labels, after;
  int priority = 0, max_running = 0;
  bool json = false, quiet = false;
  app.add_option("scene", scene_path, "base scene file (TOML)")->required();
  app.add_option("--grid", grids, "an axis: key=v1,v2,... (repeatable; the grid is their product)");
  app.add_option("--zip", zips, "an axis stepping with the other --zip axes: key=v1,v2,...");
  app.add_option("--range", ranges, "an axis of COUNT evenly spaced values: key=START:STOP:COUNT");
  app.add_option("--log-range", log_ranges,
                 "an axis of COUNT values in geometric progression: key=START:STOP:COUNT");
  app.add_option("--set", overrides, "override for every point: key=value (repeatable)");
  app.add_option("--tag", tags, "tag the study and every job (repeatable)");
  app.add_option("--label", labels, "a key=value label of the study and every job (repeatable)");
  app.add_option("--max-running", max_running,
                 "at most N jobs of the study run at once (0: no limit)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--priority", priority, "higher runs first, -1000..1000")
      ->check(CLI::Range(-1000, 1000));
  app.add_option("--name", name, "study name (default: the scene file's stem)");
  app.add_option("--time", time_limit,
                 "each job's wall-time limit of one run: 90m, 2h, 1:30:00 (default: the daemon's)");
  app.add_option("--after", after,
                 "every job starts only once these jobs have COMPLETED: ID[,ID] (repeatable)")
      ->delimiter(',');
  app.add_option("--request-id", request_id, "idempotency key (default: a fresh random id)");
  app.add_flag("--json", json, "print the response as one JSON line");
  app.add_flag("-q,--quiet", quiet, "print only the study id");
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("study", [&] {
    v1::SubmitStudyRequest request;
    request.set_scene(ReadInputFile(scene_path));
    for (const std::string& g : grids) *request.add_axes() = ParseAxis(g);
    for (const std::string& r : ranges) *request.add_axes() = ParseRange("--range", r, false);
    for (const std::string& r : log_ranges) {
      *request.add_axes() = ParseRange("--log-range", r, true);
    }
    for (const std::string& z : zips) {
      v1::StudyAxis axis = ParseAxis(z);
      axis.set_zip("zip");
      *request.add_axes() = axis;
    }
    if (request.axes_size() == 0) throw UsageError("give at least one --grid, --zip or --range");
    AddLabels(labels, request.mutable_labels());
    request.set_max_running(max_running);
    if (!time_limit.empty()) request.set_time_limit_seconds(TimeLimitFlag(time_limit));
    for (const std::string& o : overrides) {
      if (o.find('=') == std::string::npos) throw UsageError("--set " + o + ": expected key=value");
      request.add_overrides(o);
    }
    for (const std::string& t : tags) request.add_tags(t);
    for (const std::string& id : after) request.add_after(id);
    request.set_priority(priority);
    request.set_name(name.empty() ? std::filesystem::path(scene_path).stem().string() : name);
    request.set_client_request_id(request_id.empty() ? NewRequestId() : request_id);
    Connection connection(connection_flags);
    auto context = connection.UnaryContext();
    v1::SubmitStudyResponse response;
    const grpc::Status status = connection.jobs().SubmitStudy(context.get(), request, &response);
    if (!status.ok()) return ReportRpcError("study", status);
    if (json || quiet) {
      std::cout << (json ? ToJsonLine(response) : response.study_id()) << "\n";
      return kExitOk;
    }
    std::cout << "study " << response.study_id() << ": " << response.jobs_size() << " jobs\n"
              << JobTable({response.jobs().begin(), response.jobs().end()});
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
