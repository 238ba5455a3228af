// dlmfd studies [--tag T] [--page-size N] [--all] [--json]
// The caller's studies, newest first: counts per state, progress, age.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "job_text.h"
#include "rpc_status.h"
#include "study_text.h"

namespace dlmfd::cli {

int RunStudies(int argc, char** argv) {
  CLI::App app{"List your studies, newest first."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string tag, page_token;
  int page_size = 50;
  bool all = false, json = false;
  app.add_option("--tag", tag, "only studies with this tag");
  app.add_option("--page-size", page_size, "studies per page, 1..1000")->check(CLI::Range(1, 1000));
  app.add_option("--page-token", page_token, "continue from a previous page");
  app.add_flag("--all", all, "fetch every page");
  app.add_flag("--json", json, "one JSON line per study");
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("studies", [&] {
    v1::ListStudiesRequest request;
    request.set_tag(tag);
    request.set_page_size(page_size);
    request.set_page_token(page_token);
    Connection connection(connection_flags);
    std::vector<v1::Study> studies;
    std::string next;
    for (;;) {
      auto context = connection.UnaryContext();
      v1::ListStudiesResponse response;
      const grpc::Status status = connection.jobs().ListStudies(context.get(), request, &response);
      if (!status.ok()) return ReportRpcError("studies", status);
      studies.insert(studies.end(), response.studies().begin(), response.studies().end());
      next = response.next_page_token();
      if (!all || next.empty()) break;
      request.set_page_token(next);
    }
    if (json) {
      for (const v1::Study& study : studies) std::cout << ToJsonLine(study) << "\n";
    } else {
      std::cout << StudyListText(studies, NowEpochSeconds());
    }
    if (!next.empty())
      std::cerr << "more studies: dlmfd studies --page-token " << next << " (or --all)\n";
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
