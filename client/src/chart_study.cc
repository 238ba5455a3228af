// dlmfd chart --study S --x KEY --y COLUMN [--group KEY] [--title T] [--logx] [--logy] [--out F]
//             [--width W] [--height H]
// A quantity of a study against one of its parameters: one point per job of the study that has the
// column, from the Table rpc (study_table.h names the columns); --group draws one line per value of
// a second parameter, named by its values under a legend titled by its key (printed on stderr too),
// in increasing value. Points are joined in increasing x.
#include <iostream>

#include "command.h"
#include "connection.h"
#include "dlmfd/core/errors.h"
#include "exit_codes.h"
#include "rpc_status.h"
#include "study_chart.h"
#include "study_table.h"

namespace dlmfd::cli {

bool IsStudyChart(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--study" || arg.rfind("--study=", 0) == 0) return true;
  }
  return false;
}

int RunStudyChart(int argc, char** argv) {
  CLI::App app{"Draw a quantity of a study's jobs against one of its parameters as a PNG."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string study, x_key, y_column, group_key, out;
  LineChartOptions options;
  options.width = 1000;
  options.height = 700;
  bool log_x = false, log_y = false;
  app.add_option("--study", study, "the study id")->required();
  app.add_option("--x", x_key, "a parameter of the study (a column of dlmfd table)")->required();
  app.add_option("--y", y_column, "a column of dlmfd table (fall_speed, min_gap, p0.y, ...)")
      ->required();
  app.add_option("--group", group_key, "one line per value of this parameter");
  app.add_option("--title", options.title, "title above the chart");
  app.add_flag("--logx", log_x, "log10 x axis");
  app.add_flag("--logy", log_y, "log10 y axis");
  app.add_option("--out,-o", out, "PNG file to write (default chart_<study>.png here)");
  app.add_option("--width", options.width, "image width in pixels")->check(CLI::Range(200, 8192));
  app.add_option("--height", options.height, "image height in pixels")
      ->check(CLI::Range(150, 8192));
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("chart", [&] {
    Connection connection(connection_flags);
    v1::TableResponse response;
    const grpc::Status status = FetchTableRows(connection, study, {}, &response);
    if (!status.ok()) return ReportRpcError("chart", status);
    StudyChartSpec spec;
    spec.study_id = study;
    spec.x = x_key;
    spec.y = y_column;
    spec.group = group_key;
    spec.log_x = log_x;
    spec.log_y = log_y;
    spec.options = options;
    StudyChart chart;
    try {
      chart = DrawStudyChart(FlattenTable(response), spec);
    } catch (const InvalidParameter& e) {
      throw UsageError(e.what());
    }
    if (!group_key.empty()) {
      std::string names;
      for (const std::string& name : chart.legend) names += (names.empty() ? "" : "; ") + name;
      std::cerr << "legend (" << group_key << "): " << names << "\n";
    }
    ChartPicture& picture = chart.picture;
    // A study id is the daemon's ("s-" and hex digits): a safe file name.
    const std::string path = out.empty() ? "chart_" + study + ".png" : out;
    try {
      picture.image.Write(path);
    } catch (const Error& e) {
      return ReportError("chart", e.what(), kExitLocalIo);
    }
    std::cout << path << "\n";
    return kExitOk;
  });
}

}  // namespace dlmfd::cli
