// A path in the tests' temporary folder (::testing::TempDir(), or TEST_TMPDIR) that no other
// process shares: two suites run at once from different checkouts otherwise write the same files
// (seen: SolveApp.Resume* failing when two engineers' suites ran side by side). ctest runs each
// test in its own process, so each test's files are its own.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

namespace dlmfd::testing {

// TempDir()/stem_PID + extension.
inline std::string ScratchPath(const std::string& stem, const std::string& extension = "") {
  return ::testing::TempDir() + "/" + stem + "_" + std::to_string(::getpid()) + extension;
}

}  // namespace dlmfd::testing
