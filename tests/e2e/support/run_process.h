// Runs a program of the build (dlmfd, dlmfd-solve) as a child process in a folder, capturing its
// stdout and stderr through files there: the e2e tests drive the real binaries this way.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace dlmfd::test {

struct Outcome {
  int code = -1;  // exit status, or 128 + signal
  std::string out;
  std::string err;
};

// Runs `argv` (argv[0] a path) in `cwd`.
Outcome Execute(const std::vector<std::string>& argv, const std::filesystem::path& cwd);

}  // namespace dlmfd::test
