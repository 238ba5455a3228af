// Test support: a real dlmfdd process on a free loopback port with a temporary data directory, and
// helpers to talk to it through the generated dlmfd.v1.Jobs stub.
#pragma once

#include <grpcpp/grpcpp.h>
#include <sys/types.h>

#include <memory>
#include <string>
#include <vector>

#include "dlmfd/v1/jobs.grpc.pb.h"

namespace dlmfd::testing {

inline const char kDaemonPath[] = DLMFD_BINARY_DIR "/server/dlmfdd";

// The dlmfd-solve the daemon runs (its --solver flag): $DLMFD_SOLVER_BINARY when set and not empty,
// else the one of this build. The solver is a separate process, so a ThreadSanitizer run of the
// daemon may use a solver built without TSan (scripts/tsan.sh does: libgomp is not instrumented).
std::string SolverPathFromEnvironment();
inline const std::string kSolverPath = SolverPathFromEnvironment();

bool SolverAvailable();

// Skips the current test when dlmfd-solve is not built.
#define REQUIRE_SOLVER() \
  if (!SolverAvailable()) GTEST_SKIP() << "dlmfd-solve is not built: " << kSolverPath

// A fresh temporary directory, removed by the destructor.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

class DaemonProcess {
 public:
  // data_dir: reused across restarts; extra: more flags ("--max-concurrent", "3", ...); listen:
  // the --listen address (a free loopback port by default).
  DaemonProcess(std::string data_dir, std::vector<std::string> extra = {},
                std::string listen = "127.0.0.1:0");
  ~DaemonProcess();

  // Starts and waits until it serves (port file written); false if it exited first (its exit
  // status is then start_exit_status()).
  bool Start();
  int start_exit_status() const { return start_exit_status_; }
  void Kill(int signal_number);
  // Waits for the process to exit; returns its exit status (128 + signal when killed). A sanitizer
  // report the daemon wrote to its log since the last Wait fails the current test (the daemon's
  // exit status alone is not checked by every test).
  int Wait();
  int port() const { return port_; }
  std::string address() const { return "127.0.0.1:" + std::to_string(port_); }
  const std::string& log_path() const { return log_path_; }
  std::string Log() const;

  std::shared_ptr<grpc::Channel> Channel() const;
  std::unique_ptr<v1::Jobs::Stub> Stub() const;
  // True when the standard health service answers SERVING for `service` ("" is the server).
  bool Healthy(const std::string& service = "") const;

 private:
  std::string data_dir_;
  std::vector<std::string> extra_;
  std::string listen_;
  std::string log_path_;
  std::string port_file_;
  pid_t pid_ = -1;
  int port_ = 0;
  int start_exit_status_ = -1;
  std::size_t log_checked_ = 0;  // log bytes already searched for sanitizer reports
};

// A client context with an optional bearer token.
std::unique_ptr<grpc::ClientContext> Context(const std::string& token = "");

// A tiny lid-driven cavity: 16 x 16 cells, Newtonian.
std::string CavityScene(double end_time = 0.5);

// Submit of `scene` as the user of `token`; a refused submit is a test failure (the job is then
// empty).
v1::Job SubmitScene(v1::Jobs::Stub& stub, const std::string& scene, const std::string& token = "");
// Get of one job; a failed Get is a test failure (the job is then empty).
v1::Job GetJob(v1::Jobs::Stub& stub, const std::string& job_id, const std::string& token = "");

// Reads a Watch stream to its end; returns the events.
std::vector<v1::WatchEvent> WatchAll(v1::Jobs::Stub& stub, const std::string& job_id,
                                     const std::string& token = "", int64_t from_seq = 0);
// Polls Get until the job is finished; returns it. A job still unfinished after ten minutes is a
// test failure (a hung job or a deadlocked scheduler fails the test instead of hanging it).
v1::Job WaitFinished(v1::Jobs::Stub& stub, const std::string& job_id,
                     const std::string& token = "");
// Reads the job's Watch stream until a progress event past step 0 (the solver has started); a job
// with no progress within five minutes is a test failure. A short job can end before the stream
// is opened: then the stream has no progress event to show, and the job's record has the step it
// reached.
void WaitForProgress(v1::Jobs::Stub& stub, const std::string& job_id);

}  // namespace dlmfd::testing
