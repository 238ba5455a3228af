// diagnostics.csv of the results directory (design.md 3.2): one row per step. The header is
// `step,time,wall_seconds` and then the column names of the first StepReport; every later report of
// the run must have the same columns. Rows are flushed as they come. On resume the file is cut back
// to the rows with step <= the checkpoint step.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "dlmfd/core/state.h"

namespace dlmfd {

class DiagnosticsWriter {
 public:
  // Creates (truncates) `path`; the header is written with the first row.
  explicit DiagnosticsWriter(const std::string& path);
  // Reopens `path`, keeping the header and the rows with step <= last_step.
  DiagnosticsWriter(const std::string& path, long last_step);
  ~DiagnosticsWriter();
  DiagnosticsWriter(const DiagnosticsWriter&) = delete;
  DiagnosticsWriter& operator=(const DiagnosticsWriter&) = delete;

  void Append(const StepReport& report);

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  bool header_written_ = false;
  std::vector<std::string> columns_;
};

struct DiagnosticsTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  // The index of a column in header, or -1.
  int Column(const std::string& name) const;
};

DiagnosticsTable ReadDiagnostics(const std::string& path);

}  // namespace dlmfd
