// Test support for the tests labelled slurm: the dev Slurm of scripts/slurm-dev.sh (its
// configuration and jobcomp file), the skip when no Slurm answers, the daemon's slurm flags, tiny
// scenes, and shell commands whose output the tests read (squeue, scontrol, pgrep). Header only:
// the slurm tests link the server tests' support (daemon_process.h).
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../server/support/daemon_process.h"

namespace dlmfd::testing {

inline constexpr char kDevSlurmDir[] = "/tmp/dlmfd-slurm";  // scripts/slurm-dev.sh's default

inline std::string DevSlurmDir() {
  const char* dir = std::getenv("DLMFD_SLURM_DIR");
  return dir && *dir ? dir : kDevSlurmDir;
}

// The dev Slurm's configuration, unless SLURM_CONF already names one.
inline void UseDevSlurm() {
  const std::string conf = DevSlurmDir() + "/slurm.conf";
  if (!std::getenv("SLURM_CONF") && std::filesystem::exists(conf)) {
    setenv("SLURM_CONF", conf.c_str(), 1);
  }
}

// Asked once: sinfo takes about 9 s to give up when no slurmctld answers.
inline bool SlurmRunning() {
  static const bool running = [] {
    UseDevSlurm();
    return std::system("sinfo -h > /dev/null 2>&1") == 0;
  }();
  return running;
}

inline std::string JobCompFile() { return DevSlurmDir() + "/log/jobcomp.txt"; }

// A fixed disk in an Oldroyd-B lid-driven cavity, 16 x 16 cells, dt = 0.01: particle states and
// trA snapshots to stream.
inline std::string DiskInCavity(double end_time, double checkpoint_every = 0) {
  std::ostringstream scene;
  scene << "title = \"disk in an Oldroyd-B cavity\"\n"
           "[domain]\nsize = [1.0, 1.0]\nh = 0.0625\n"
           "[domain.boundary]\n"
           "left = { type = \"wall\" }\nright = { type = \"wall\" }\nbottom = { type = \"wall\" }\n"
           "top = { type = \"velocity\", profile = \"uniform\", value = [1.0, 0.0] }\n"
           "[fluid]\nviscosity = 0.1\nrelaxation_time = 0.1\nsolvent_ratio = 0.5\n"
           "[time]\ndt = 0.01\nend = "
        << end_time
        << "\n"
           "[[particles]]\ncenter = [0.5, 0.5]\ndiameter = 0.25\ndensity = 1.0\n"
           "motion = \"fixed\"\n"
           "[output]\nfields_every = 0.05\nparticles_every = 0.02\n";
  if (checkpoint_every > 0) scene << "checkpoint_every = " << checkpoint_every << "\n";
  return scene.str();
}

// The daemon's flags for the dev Slurm: job directories under dir/shared, squeue every second.
inline std::vector<std::string> SlurmFlags(const std::string& dir) {
  return {"--executor",           "slurm", "--slurm-shared-dir",   dir + "/shared",
          "--slurm-poll-seconds", "1",     "--slurm-jobcomp-file", JobCompFile()};
}

inline v1::Job Submit(v1::Jobs::Stub& stub, const std::string& scene) {
  v1::SubmitRequest request;
  request.set_scene(scene);
  request.set_name("slurm-test");
  v1::Job job;
  auto status = stub.Submit(Context().get(), request, &job);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return job;
}

// Runs a shell command; returns its standard output.
inline std::string Shell(const std::string& command) {
  std::string out;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[4096];
    for (size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
    pclose(pipe);
  }
  return out;
}

// Polls until done() or the timeout (generous: a slow, shared machine); returns done().
inline bool WaitUntil(const std::function<bool()>& done,
                      std::chrono::seconds timeout = std::chrono::seconds(120)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  return true;
}

// Cancels the job (Cancel, as `dlmfd cancel`) and waits for its end; returns the job then.
inline v1::Job CancelAndWait(v1::Jobs::Stub& stub, const std::string& id) {
  v1::CancelRequest cancel;
  cancel.set_job_id(id);
  v1::Job cancelled;
  const grpc::Status status = stub.Cancel(Context().get(), cancel, &cancelled);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return WaitFinished(stub, id);
}

// Cancels the Slurm jobs whose working directory starts with prefix.
inline void CancelSlurmJobsUnder(const std::string& prefix) {
  std::istringstream lines(Shell("squeue -h -o '%i %Z' 2>/dev/null"));
  for (std::string id, work_dir; lines >> id >> work_dir;) {
    if (work_dir.rfind(prefix, 0) == 0) std::system(("scancel " + id + " 2>/dev/null").c_str());
  }
}

// The Slurm jobs of an earlier slurm test that ctest killed (its timeout: no destructor ran) would
// hold the node's CPUs for ever; the slurm tests run one at a time (RESOURCE_LOCK in
// tests/CMakeLists.txt), so every job under a test directory is such a leftover when one starts.
inline void CancelLeftoverTestJobs() {
  CancelSlurmJobsUnder((std::filesystem::temp_directory_path() / "dlmfdd-test-").string());
}

// At the end of a test, cancels the Slurm jobs whose working directory lies under dir (a daemon
// that shuts down leaves its Slurm jobs running, to adopt them at its next start).
class SlurmCleanup {
 public:
  explicit SlurmCleanup(std::string dir)
      : dir_(std::move(dir)) {}
  ~SlurmCleanup() { CancelSlurmJobsUnder(dir_); }
  SlurmCleanup(const SlurmCleanup&) = delete;
  SlurmCleanup& operator=(const SlurmCleanup&) = delete;

 private:
  std::string dir_;
};

// A test against the dev Slurm: skipped, naming scripts/slurm-dev.sh, when no Slurm answers (or
// the solver is not built); a temporary directory whose Slurm jobs are cancelled at the end;
// StartDaemon starts a dlmfdd with the slurm executor there (again after a kill: the same data).
class SlurmTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!SolverAvailable()) GTEST_SKIP() << "dlmfd-solve is not built: " << kSolverPath;
    if (!SlurmRunning()) {
      GTEST_SKIP() << "no Slurm answers sinfo: start one with scripts/slurm-dev.sh start (as "
                      "root), or set SLURM_CONF";
    }
    CancelLeftoverTestJobs();
  }
  // SlurmFlags and more; false when the daemon did not start (its log says why). listen: a free
  // loopback port, or the address of a daemon before (its clients reconnect there).
  bool StartDaemon(const std::vector<std::string>& more = {},
                   const std::string& listen = "127.0.0.1:0") {
    std::vector<std::string> flags = SlurmFlags(dir_.path());
    flags.insert(flags.end(), more.begin(), more.end());
    stub_.reset();
    daemon_ = std::make_unique<DaemonProcess>(dir_.path() + "/data", flags, listen);
    if (!daemon_->Start()) return false;
    stub_ = daemon_->Stub();
    return true;
  }
  DaemonProcess& daemon() { return *daemon_; }
  v1::Jobs::Stub* stub() { return stub_.get(); }
  const std::string& dir() const { return dir_.path(); }

 private:
  TempDir dir_;
  SlurmCleanup cleanup_{dir_.path()};
  std::unique_ptr<DaemonProcess> daemon_;
  std::unique_ptr<v1::Jobs::Stub> stub_;
};

// How many times Slurm ran a job of this name to its end (the jobcomp file's lines).
inline int SlurmEndsOfName(const std::string& name) {
  std::ifstream jobcomp(JobCompFile());
  int ends = 0;
  for (std::string line; std::getline(jobcomp, line);) {
    if (line.find(" Name=" + name + " ") != std::string::npos) ++ends;
  }
  return ends;
}

}  // namespace dlmfd::testing
