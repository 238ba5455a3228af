// A set of jobs named on the command line: by id, by study (--study S) or by tag (--tag T,
// repeatable: every tag must be carried), as `show`, `watch`, `fetch`, `cancel` and `retry` take
// them (kubectl's -l, Slurm's job arrays). The jobs of a selection are read with List, every page.
#pragma once

#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "connection.h"

namespace dlmfd::cli {

struct JobSelection {
  std::string study;
  std::vector<std::string> tags;
  bool empty() const { return study.empty() && tags.empty(); }
};

// Adds --study and --tag, which exclude `ids` (the positional job ids) when given.
void AddSelectionFlags(CLI::App& app, JobSelection& selection, CLI::Option* ids);

// Every job of the selection, newest first. A study that does not exist is NOT_FOUND (exit 3).
grpc::Status SelectJobs(Connection& connection, const JobSelection& selection,
                        std::vector<v1::Job>& jobs);

// A description of the selection for messages: "study s-1234", "tag a,b".
std::string SelectionName(const JobSelection& selection);

}  // namespace dlmfd::cli
