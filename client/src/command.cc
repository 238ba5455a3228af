// Shared plumbing of the subcommands: flag parsing and the last-resort error report.
#include "command.h"

#include <unistd.h>

#include <cstdio>
#include <exception>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "connection.h"
#include "exit_codes.h"
#include "progress_printer.h"
#include "rpc_status.h"
#include "time_limit_text.h"

namespace dlmfd::cli {

std::optional<int> ParseArgs(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }
  return std::nullopt;
}

int Guarded(const std::string& command, const std::function<int()>& body) {
  try {
    return body();
  } catch (const UsageError& e) {
    return ReportError(command, e.what(), kExitUsage);
  } catch (const std::exception& e) {
    return ReportError(command, e.what(), kExitServerError);
  }
}

std::string ReadInputFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw UsageError("cannot read " + path);
  return text.str();
}

std::pair<std::string, std::string> SplitKeyValue(const std::string& flag,
                                                  const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw UsageError(flag + " " + text + ": expected key=value");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

void AddLabels(const std::vector<std::string>& texts,
               google::protobuf::Map<std::string, std::string>* labels) {
  for (const std::string& text : texts) {
    const auto [key, value] = SplitKeyValue("--label", text);
    (*labels)[key] = value;
  }
}

int64_t TimeLimitFlag(const std::string& text) {
  try {
    return ParseTimeLimit(text);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

std::string NewRequestId() {
  std::random_device device;
  char text[33];
  for (int k = 0; k < 4; ++k) std::snprintf(text + 8 * k, 9, "%08x", unsigned(device()));
  return text;
}

PrintMode ChoosePrintMode(bool json, int fd) {
  if (json) return PrintMode::kJson;
  return ::isatty(fd) ? PrintMode::kLive : PrintMode::kPlain;
}

}  // namespace dlmfd::cli
