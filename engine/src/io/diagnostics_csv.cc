#include "dlmfd/io/diagnostics_csv.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "dlmfd/core/errors.h"
#include "dlmfd/io/atomic_file.h"

namespace dlmfd {
namespace {

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) out.push_back(cell);
  return out;
}

std::FILE* OpenOrThrow(const std::string& path, const char* mode) {
  std::FILE* f = std::fopen(path.c_str(), mode);
  if (f == nullptr) throw Error("cannot open " + path + ": " + std::strerror(errno));
  return f;
}

}  // namespace

DiagnosticsWriter::DiagnosticsWriter(const std::string& path)
    : path_(path),
      file_(OpenOrThrow(path, "w")) {}

DiagnosticsWriter::DiagnosticsWriter(const std::string& path, long last_step)
    : path_(path) {
  std::stringstream in(ReadTextFile(path));
  std::string line, kept;
  if (std::getline(in, line) && !line.empty()) {
    kept = line + "\n";
    header_written_ = true;
    const std::vector<std::string> header = SplitCsv(line);
    columns_.assign(header.begin() + std::min<std::size_t>(3, header.size()), header.end());
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      if (std::strtol(line.c_str(), nullptr, 10) > last_step) break;
      kept += line + "\n";
    }
  }
  WriteTextAtomically(path, kept);
  file_ = OpenOrThrow(path, "a");
}

DiagnosticsWriter::~DiagnosticsWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void DiagnosticsWriter::Append(const StepReport& report) {
  if (!header_written_) {
    std::fputs("step,time,wall_seconds", file_);
    for (const auto& c : report.columns) {
      std::fprintf(file_, ",%s", c.first.c_str());
      columns_.push_back(c.first);
    }
    std::fputc('\n', file_);
    header_written_ = true;
  }
  std::fprintf(file_, "%ld,%.17g,%.6g", report.step, report.time, report.wall_seconds);
  for (const std::string& name : columns_) std::fprintf(file_, ",%.10g", report.Get(name, 0.0));
  std::fputc('\n', file_);
  if (std::fflush(file_) != 0) throw Error("cannot write " + path_);
}

int DiagnosticsTable::Column(const std::string& name) const {
  for (std::size_t k = 0; k < header.size(); ++k) {
    if (header[k] == name) return static_cast<int>(k);
  }
  return -1;
}

DiagnosticsTable ReadDiagnostics(const std::string& path) {
  std::stringstream in(ReadTextFile(path));
  DiagnosticsTable t;
  std::string line;
  if (std::getline(in, line)) t.header = SplitCsv(line);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<double> row;
    for (const std::string& cell : SplitCsv(line))
      row.push_back(std::strtod(cell.c_str(), nullptr));
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace dlmfd
