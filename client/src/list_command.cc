// dlmfd list [--state S]... [--tag T]... [--label k=v]... [--where KEY=VALUE]... [--study ID]
//            [--page-size N] [--page-token T | --all] [--json | -q]
// Every filter given must hold. --where matches the effective scene (the scene file, the overrides
// and the defaults, as the solver runs it): `--where particles.*.density=1.5`.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_text.h"
#include "rpc_status.h"

namespace dlmfd::cli {

int RunList(int argc, char** argv) {
  CLI::App app{"List your jobs, newest first."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::vector<std::string> states, tags, labels, where;
  std::string study, page_token;
  int page_size = 50;
  bool all = false, json = false, quiet = false;
  app.add_option("--state", states,
                 "queued|running|completed|failed|cancelled (repeatable or comma list)")
      ->delimiter(',');
  app.add_option("--tag", tags, "only jobs with this tag (repeatable: every one)");
  app.add_option("--label", labels, "only jobs with this key=value label (repeatable)");
  app.add_option("--where", where,
                 "only jobs whose effective scene has KEY=VALUE, KEY!=VALUE or KEY<NUMBER "
                 "(also <=, >, >=) (repeatable; * for any index)");
  app.add_option("--study", study, "only jobs of this study");
  app.add_option("--page-size", page_size, "jobs per page, 1..1000")->check(CLI::Range(1, 1000));
  app.add_option("--page-token", page_token, "continue from a previous page");
  app.add_flag("--all", all, "fetch every page");
  app.add_flag("--json", json, "one JSON line per job");
  app.add_flag("-q,--quiet", quiet, "only the job ids, one per line");
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("list", [&] {
    v1::ListRequest request;
    for (const std::string& s : states) request.add_states(ParseState(s));
    for (const std::string& t : tags) request.add_tags(t);
    AddLabels(labels, request.mutable_labels());
    // The daemon checks each (scene_values.h): one validation path.
    for (const std::string& w : where) request.add_where(w);
    request.set_study_id(study);
    request.set_page_size(page_size);
    request.set_page_token(page_token);
    Connection connection(connection_flags);
    std::vector<v1::Job> jobs;
    std::string next;
    for (;;) {
      auto context = connection.UnaryContext();
      v1::ListResponse response;
      const grpc::Status status = connection.jobs().List(context.get(), request, &response);
      if (!status.ok()) return ReportRpcError("list", status);
      jobs.insert(jobs.end(), response.jobs().begin(), response.jobs().end());
      next = response.next_page_token();
      if (!all || next.empty()) break;
      request.set_page_token(next);
    }
    if (json || quiet) {
      for (const v1::Job& job : jobs) std::cout << (json ? ToJsonLine(job) : job.id()) << "\n";
    } else {
      std::cout << JobTable(jobs);
    }
    if (!next.empty())
      std::cerr << "more jobs: dlmfd list --page-token " << next << " (or --all)\n";
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
