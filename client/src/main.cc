// dlmfd: the command-line client of the dlmfdd job daemon (docs/cli.md).
//
//   dlmfd [--server ADDR] [--token TOKEN] COMMAND [ARGS...]
//
// Options given before the command are handed to it, so `dlmfd --server h:1 list` and
// `dlmfd list --server h:1` mean the same.
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "command.h"
#include "exit_codes.h"

namespace dlmfd::cli {
namespace {

const Command kCommands[] = {
    {"submit", "queue a scene file as a job (--wait: watch it to the end)", RunSubmit},
    {"study", "queue a study: one job per point of its axes", RunStudy},
    {"studies", "list your studies with their counts per state", RunStudies},
    {"list", "list your jobs (by state, tag, label, study, scene value)", RunList},
    {"show", "show one job, or a study (--study, --tag)", RunShow},
    {"watch", "follow a job (or a study): live line, or NDJSON with --json", RunWatch},
    {"cancel", "cancel jobs, a study or the jobs of a tag", RunCancel},
    {"retry", "rerun finished jobs of a study, resuming where possible", RunRetry},
    {"fetch", "download result files of a job or a study", RunFetch},
    {"logs", "print a job's solver log (--follow: until it ends)", RunLogs},
    {"inputs", "print the scene a job was submitted with (--as-run: as it ran)", RunInputs},
    {"table", "one row per job of a study: parameters and summary quantities", RunTable},
    {"delete", "delete jobs or a study: records and results", RunDelete},
    {"priority", "change the priority of a queued job", RunPriority},
    {"hold", "keep a queued job from starting", RunHold},
    {"release", "let a held job start", RunRelease},
    {"plot", "draw a field (trA, speed, vorticity, ...) with the particles (PNG/SVG/PDF)", RunPlot},
    {"chart", "line chart of particle quantities of runs, of CSV columns, or of a study (--study)",
     RunChart},
    {"movie", "movie (ffmpeg) of a run's snapshots with the particles and the time", RunMovie},
    {"figure", "a multi-panel figure, (a)-(d), of plot and chart command lines", RunFigure},
    {"health", "ask the daemon whether it is serving", RunHealth},
    {"usage", "your disk use against your quota, your jobs per state", RunUsage},
};

void Usage(std::ostream& out) {
  out << "usage: dlmfd [--server ADDR] [--token TOKEN] COMMAND [ARGS...]\n\ncommands:\n";
  for (const Command& c : kCommands) {
    out << "  " << c.name << std::string(10 - std::strlen(c.name), ' ') << c.summary << "\n";
  }
  out << "\n`dlmfd COMMAND --help` describes a command; docs/cli.md has examples and exit codes.\n"
      << "Server and token: flag > DLMFD_SERVER / DLMFD_TOKEN > ~/.config/dlmfd/config.toml > "
         "127.0.0.1:7443\n";
}

bool TakesValue(const std::string& arg) {
  return arg == "--server" || arg == "--token" || arg == "--timeout";
}

bool IsGlobalOption(const std::string& arg) {
  return TakesValue(arg) || arg.rfind("--server=", 0) == 0 || arg.rfind("--token=", 0) == 0 ||
         arg.rfind("--timeout=", 0) == 0;
}

int Main(int argc, char** argv) {
  std::vector<std::string> leading;
  int i = 1;
  while (i < argc && IsGlobalOption(argv[i])) {
    leading.emplace_back(argv[i]);
    if (TakesValue(argv[i]) && i + 1 < argc) leading.emplace_back(argv[++i]);
    ++i;
  }
  if (i >= argc) {
    Usage(std::cerr);
    return kExitUsage;
  }
  const std::string name = argv[i];
  if (name == "help" || name == "--help" || name == "-h") {
    Usage(std::cout);
    return kExitOk;
  }
  if (name == "version" || name == "--version") {
    std::cout << "dlmfd " << DLMFD_VERSION << "\n";
    return kExitOk;
  }
  for (const Command& c : kCommands) {
    if (name != c.name) continue;
    std::vector<std::string> storage = {"dlmfd " + name};
    storage.insert(storage.end(), leading.begin(), leading.end());
    for (int k = i + 1; k < argc; ++k) storage.emplace_back(argv[k]);
    std::vector<char*> args;
    for (std::string& s : storage) args.push_back(s.data());
    args.push_back(nullptr);
    return c.run(int(storage.size()), args.data());
  }
  std::cerr << "dlmfd: unknown command '" << name << "'\n\n";
  Usage(std::cerr);
  return kExitUsage;
}

}  // namespace
}  // namespace dlmfd::cli

int main(int argc, char** argv) { return dlmfd::cli::Main(argc, argv); }
