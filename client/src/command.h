// The subcommand table of dlmfd (as in ninja's src/ninja.cc): each subcommand is one function in
// its own file, parses its own flags with CLI11, and returns a documented exit code (exit_codes.h).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <google/protobuf/map.h>

#include "CLI/CLI.hpp"

namespace dlmfd::cli {

struct Command {
  const char* name;
  const char* summary;
  int (*run)(int argc, char** argv);  // argv[0] is "dlmfd <name>"
};

int RunSubmit(int argc, char** argv);
int RunStudy(int argc, char** argv);
int RunList(int argc, char** argv);
int RunShow(int argc, char** argv);
int RunWatch(int argc, char** argv);
int RunCancel(int argc, char** argv);
int RunFetch(int argc, char** argv);
int RunLogs(int argc, char** argv);
int RunPlot(int argc, char** argv);
int RunChart(int argc, char** argv);
int RunMovie(int argc, char** argv);
int RunFigure(int argc, char** argv);
int RunHealth(int argc, char** argv);
int RunUsage(int argc, char** argv);
int RunTable(int argc, char** argv);
int RunInputs(int argc, char** argv);
int RunDelete(int argc, char** argv);
int RunPriority(int argc, char** argv);
int RunHold(int argc, char** argv);
int RunRelease(int argc, char** argv);
// `dlmfd chart --study ...`: a quantity of a study against a parameter (chart_study.cc).
bool IsStudyChart(int argc, char** argv);
int RunStudyChart(int argc, char** argv);
int RunStudies(int argc, char** argv);
int RunRetry(int argc, char** argv);

// Parses argv into `app`; returns an exit code when the command must stop (help: 0, error: 2).
std::optional<int> ParseArgs(CLI::App& app, int argc, char** argv);
// Runs `body`, turning UsageError into exit 2 and any other exception into exit 8, each reported
// as one line naming the command.
int Guarded(const std::string& command, const std::function<int()>& body);

}  // namespace dlmfd::cli

namespace dlmfd::cli {

// The whole file; throws UsageError naming the path when it cannot be read.
std::string ReadInputFile(const std::string& path);
// "key=value" split at the first '='; throws UsageError naming the flag when there is none.
std::pair<std::string, std::string> SplitKeyValue(const std::string& flag, const std::string& text);
// Adds each "key=value" of --label to `labels`.
void AddLabels(const std::vector<std::string>& texts,
               google::protobuf::Map<std::string, std::string>* labels);
// --time's duration in seconds (time_limit_text.h); throws UsageError saying what is expected.
int64_t TimeLimitFlag(const std::string& text);
// A random 128-bit hex id that makes a retried Submit or SubmitStudy idempotent.
std::string NewRequestId();
// How `watch` prints on the descriptor it writes to (stdout by default): live line on a terminal,
// plain otherwise, or JSON.
enum class PrintMode;
PrintMode ChoosePrintMode(bool json, int fd = 1);

}  // namespace dlmfd::cli
