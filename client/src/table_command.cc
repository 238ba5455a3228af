// dlmfd table --study S | JOB...  [--format csv|json] [--columns a,b,...]
// One row per job of the study (or per job named) with its parameters as typed values and the
// quantities of its summary.json (study_table.h lists the columns). CSV on stdout by default.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "rpc_status.h"
#include "study_table.h"

namespace dlmfd::cli {

int RunTable(int argc, char** argv) {
  CLI::App app{"Tabulate the summaries of a study's jobs (or of the jobs named)."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::vector<std::string> job_ids, columns;
  std::string study, format = "csv";
  auto* jobs_option = app.add_option("job", job_ids, "job ids");
  auto* study_option = app.add_option("--study", study, "every job of this study");
  jobs_option->excludes(study_option);
  app.add_option("--format", format, "csv (default) or json")
      ->check(CLI::IsMember({"csv", "json"}));
  app.add_option("--columns", columns, "only these columns, in this order (comma separated)")
      ->delimiter(',');
  if (auto code = ParseArgs(app, argc, argv)) return *code;
  if (job_ids.empty() && study.empty())
    return ReportError("table", "name job ids or --study ID", kExitUsage);

  return Guarded("table", [&] {
    Connection connection(connection_flags);
    v1::TableResponse response;
    const grpc::Status status = FetchTableRows(connection, study, job_ids, &response);
    if (!status.ok()) return ReportRpcError("table", status);
    StudyTable table = FlattenTable(response);
    if (!columns.empty()) table = table.Select(columns);
    std::cout << (format == "json" ? TableJson(table) : TableCsv(table));
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
