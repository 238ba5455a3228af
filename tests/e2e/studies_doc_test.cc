// docs/studies.md stays runnable (issue 14 point 9): every ```sh block of the page, in order, is
// one bash script (set -euo pipefail) run against the real dlmfdd, dlmfd-solve and dlmfd, in a
// fresh directory where `cases/` is the repository's. The script must exit 0, and the steps the
// page explains must have happened: a failed point, its retry in the study, one folder per point,
// the table and the chart; a second stage after a first job, and a dependant of a cancelled job.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/cli_harness.h"

namespace dlmfd::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// The ```sh blocks of a Markdown text, joined.
std::string ShellBlocks(const std::string& markdown) {
  std::istringstream lines(markdown);
  std::string line, script;
  bool inside = false;
  while (std::getline(lines, line)) {
    if (!inside && line == "```sh") {
      inside = true;
    } else if (inside && line == "```") {
      inside = false;
      script += "\n";
    } else if (inside) {
      script += line + "\n";
    }
  }
  return script;
}

TEST(StudiesDoc, TheWorkedStudyRunsAsWritten) {
  for (const std::string* binary : {&kClient, &kDaemon, &kSolver})
    ASSERT_TRUE(fs::exists(*binary)) << *binary << " is not built";
  const fs::path root =
      fs::path(::testing::TempDir()) / ("dlmfd_studies_doc_" + std::to_string(getpid()));
  fs::remove_all(root);
  CliDaemon daemon(root / "daemon");
  std::string error;
  ASSERT_TRUE(daemon.Start("127.0.0.1:0", error)) << error;
  const fs::path work = root / "work";
  fs::create_directories(work);
  fs::create_directory_symlink(fs::path(DLMFD_SOURCE_DIR) / "cases", work / "cases");

  const std::string blocks = ShellBlocks(Slurp(fs::path(DLMFD_SOURCE_DIR) / "docs/studies.md"));
  ASSERT_THAT(blocks, HasSubstr("dlmfd study"));
  std::ofstream(work / "study.sh") << "set -euo pipefail\n" << blocks;
  auto env = daemon.Env();
  env["PATH"] = fs::path(kClient).parent_path().string() + ":/usr/bin:/bin";
  const CliRun run =
      Execute({"/bin/bash", (work / "study.sh").string()}, env, nullptr, work.string());
  ASSERT_EQ(run.code, 0) << "stdout:\n" << run.out << "\nstderr:\n" << run.err;

  // Both points at dt = 0.04 fail (docs/studies.md says why) and are retried at 0.01.
  EXPECT_THAT(run.out, HasSubstr("4 jobs  0 queued  0 running  2 done  2 failed"));
  EXPECT_THAT(run.out, HasSubstr("(attempt 2)"));
  EXPECT_THAT(run.out, HasSubstr("4 jobs  0 queued  0 running  4 done  0 failed"));
  EXPECT_THAT(run.out, HasSubstr("  attempt 1: failed ("));
  // Issue 38: a retried point is named after the time step it ran with.
  EXPECT_THAT(run.out, HasSubstr("name:        waters-king[fluid.relaxation_time=3,time.dt=0.01]"));
  for (const char* point :
       {"fluid.relaxation_time=1,time.dt=0.005", "fluid.relaxation_time=1,time.dt=0.01",
        "fluid.relaxation_time=3,time.dt=0.005", "fluid.relaxation_time=3,time.dt=0.01"}) {
    EXPECT_TRUE(fs::exists(work / "runs/waters-king" / point / "summary.json")) << point;
  }
  // The table: a row per point with its typed parameters, the retried points with their new dt.
  EXPECT_THAT(run.out, HasSubstr("fluid.relaxation_time,time.dt,status,steps,time,max_trA,"
                                 "min_eig_A\n1,0.005,completed,600,3,"));
  EXPECT_THAT(run.out, HasSubstr("\n1,0.01,completed,300,3,"));
  EXPECT_THAT(run.out, HasSubstr("\n3,0.01,completed,300,3,"));
  const std::string json = Slurp(work / "waters-king.json");
  EXPECT_THAT(json, HasSubstr("\"fluid.relaxation_time\": 3,\n    \"time.dt\": 0.01,\n"));
  // The chart: one line per relaxation time, under a legend naming it.
  EXPECT_THAT(run.err, HasSubstr("legend (fluid.relaxation_time): 1; 3"));
  EXPECT_EQ(Slurp(work / "waters-king-max-trA.png").substr(0, 8),
            std::string("\x89PNG\r\n\x1a\n", 8));
  // Issue 38: a second stage after the first (afterok), and a dependant of a cancelled job.
  EXPECT_THAT(run.out, HasSubstr("2 jobs  0 queued  0 running  2 done  0 failed"));
  EXPECT_THAT(run.out, HasSubstr("state:       completed\nafter:       j-"));
  EXPECT_THAT(run.out, HasSubstr("state:       cancelled\nreason:      dependency j-"));
  EXPECT_THAT(run.out, HasSubstr(" failed (CANCELLED)\nafter:       j-"));
  // Issue 38: the accounting columns of a study's jobs and the user's disk use.
  EXPECT_THAT(run.out, HasSubstr("ELAPSED  EXIT  CPU   MAXRSS"));
  EXPECT_THAT(run.out, HasSubstr("\ndisk:        "));
  EXPECT_THAT(run.out, HasSubstr("\njobs:        9 (queued 0, running 0, completed 7, failed 0, "
                                 "cancelled 2)"));
  fs::remove_all(root);
}

}  // namespace
}  // namespace dlmfd::testing
