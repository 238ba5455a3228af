#include "daemon_process.h"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <grpcpp/generic/generic_stub.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "../../support/raw_grpc_call.h"

namespace dlmfd::testing {
namespace fs = std::filesystem;

std::string SolverPathFromEnvironment() {
  const char* from_environment = std::getenv("DLMFD_SOLVER_BINARY");
  if (from_environment && *from_environment) return from_environment;
  return DLMFD_BINARY_DIR "/solver/dlmfd-solve";
}

bool SolverAvailable() { return access(kSolverPath.c_str(), X_OK) == 0; }

TempDir::TempDir() {
  std::string pattern = (fs::temp_directory_path() / "dlmfdd-test-XXXXXX").string();
  path_ = mkdtemp(pattern.data());
}

TempDir::~TempDir() {
  std::error_code error;
  fs::remove_all(path_, error);
}

DaemonProcess::DaemonProcess(std::string data_dir, std::vector<std::string> extra,
                             std::string listen)
    : data_dir_(std::move(data_dir)),
      extra_(std::move(extra)),
      listen_(std::move(listen)) {
  log_path_ = data_dir_ + ".daemon.log";
  port_file_ = data_dir_ + ".port";
}

DaemonProcess::~DaemonProcess() {
  if (pid_ > 0) {
    Kill(SIGTERM);
    Wait();
  }
}

bool DaemonProcess::Start() {
  std::error_code error;
  fs::remove(port_file_, error);
  std::vector<std::string> args = {kDaemonPath, "--listen",    listen_,   "--data-dir",
                                   data_dir_,   "--port-file", port_file_};
  // A test that names its own solver replaces this build's.
  if (std::find(extra_.begin(), extra_.end(), "--solver") == extra_.end()) {
    args.insert(args.end(), {"--solver", kSolverPath});
  }
  args.insert(args.end(), extra_.begin(), extra_.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_ = fork();
  if (pid_ == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);  // a crashed test leaves no daemon behind
    FILE* log = std::freopen(log_path_.c_str(), "a", stderr);
    if (log) dup2(fileno(stderr), 1);
    execv(argv[0], argv.data());
    _exit(127);
  }
  // Wait until it serves or exits; no limit on the time it may take.
  while (true) {
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      start_exit_status_ = WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status);
      return false;
    }
    std::ifstream in(port_file_);
    if (in >> port_ && port_ > 0) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

void DaemonProcess::Kill(int signal_number) {
  if (pid_ > 0) kill(pid_, signal_number);
}

int DaemonProcess::Wait() {
  if (pid_ <= 0) return -1;
  int status = 0;
  waitpid(pid_, &status, 0);
  pid_ = -1;
  const std::string log = Log();
  if (log.size() > log_checked_) {
    const std::string fresh = log.substr(log_checked_);
    log_checked_ = log.size();
    static const char* const kSanitizerMarkers[] = {"WARNING: ThreadSanitizer",
                                                    "ERROR: AddressSanitizer", "runtime error:"};
    for (const char* marker : kSanitizerMarkers) {
      if (fresh.find(marker) != std::string::npos) {
        ADD_FAILURE() << "the daemon reported \"" << marker << "\":\n" << fresh;
        break;
      }
    }
  }
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status);
}

std::string DaemonProcess::Log() const {
  std::ifstream in(log_path_);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::shared_ptr<grpc::Channel> DaemonProcess::Channel() const {
  return grpc::CreateChannel(address(), grpc::InsecureChannelCredentials());
}

std::unique_ptr<v1::Jobs::Stub> DaemonProcess::Stub() const { return v1::Jobs::NewStub(Channel()); }

bool DaemonProcess::Healthy(const std::string& service) const {
  auto channel = Channel();
  grpc::ClientContext context;
  // grpc.health.v1.HealthCheckRequest { service = 1 (string) }: tag 0x0a, length, bytes; an empty
  // service name is an empty message. Names here are shorter than 128 bytes (one-byte length).
  std::string request_bytes;
  if (!service.empty()) {
    request_bytes = std::string("\x0a", 1) + static_cast<char>(service.size()) + service;
  }
  grpc::GenericStub generic(channel);
  std::string bytes;
  if (!RawUnaryCall(generic, context, "/grpc.health.v1.Health/Check", request_bytes, &bytes).ok()) {
    return false;
  }
  // HealthCheckResponse { status = 1 (SERVING) }: field 1, varint 1 -> bytes 0x08 0x01.
  return bytes == std::string("\x08\x01", 2);
}

std::unique_ptr<grpc::ClientContext> Context(const std::string& token) {
  auto context = std::make_unique<grpc::ClientContext>();
  if (!token.empty()) context->AddMetadata("authorization", "Bearer " + token);
  return context;
}

std::string CavityScene(double end_time) {
  std::ostringstream scene;
  scene << "title = \"lid-driven cavity 16x16\"\n"
           "[domain]\nsize = [1.0, 1.0]\nh = 0.0625\n"
           "[domain.boundary]\n"
           "left = { type = \"wall\" }\nright = { type = \"wall\" }\nbottom = { type = \"wall\" }\n"
           "top = { type = \"velocity\", profile = \"uniform\", value = [1.0, 0.0] }\n"
           "[fluid]\nviscosity = 0.01\n"
           "[time]\ndt = 0.01\nend = "
        << end_time << "\n";
  return scene.str();
}

v1::Job SubmitScene(v1::Jobs::Stub& stub, const std::string& scene, const std::string& token) {
  v1::SubmitRequest request;
  request.set_scene(scene);
  auto context = Context(token);
  v1::Job job;
  const grpc::Status status = stub.Submit(context.get(), request, &job);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return job;
}

v1::Job GetJob(v1::Jobs::Stub& stub, const std::string& job_id, const std::string& token) {
  v1::GetRequest request;
  request.set_job_id(job_id);
  v1::Job job;
  auto context = Context(token);
  const grpc::Status status = stub.Get(context.get(), request, &job);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return job;
}

std::vector<v1::WatchEvent> WatchAll(v1::Jobs::Stub& stub, const std::string& job_id,
                                     const std::string& token, int64_t from_seq) {
  auto context = Context(token);
  v1::WatchRequest request;
  request.set_job_id(job_id);
  request.set_from_seq(from_seq);
  auto reader = stub.Watch(context.get(), request);
  std::vector<v1::WatchEvent> events;
  v1::WatchEvent event;
  while (reader->Read(&event)) events.push_back(event);
  reader->Finish();
  return events;
}

v1::Job WaitFinished(v1::Jobs::Stub& stub, const std::string& job_id, const std::string& token) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
  while (true) {
    auto context = Context(token);
    v1::GetRequest request;
    request.set_job_id(job_id);
    v1::Job job;
    auto status = stub.Get(context.get(), request, &job);
    if (!status.ok()) return job;
    if (job.state() >= v1::COMPLETED) return job;
    if (std::chrono::steady_clock::now() > deadline) {
      ADD_FAILURE() << "job " << job_id << " did not finish within 10 minutes (state "
                    << v1::JobState_Name(job.state()) << ")";
      return job;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

void WaitForProgress(v1::Jobs::Stub& stub, const std::string& job_id) {
  auto context = Context();
  context->set_deadline(std::chrono::system_clock::now() + std::chrono::minutes(5));
  v1::WatchRequest watch;
  watch.set_job_id(job_id);
  auto reader = stub.Watch(context.get(), watch);
  v1::WatchEvent event;
  bool progressed = false;
  while (!progressed && reader->Read(&event)) {
    progressed = event.has_progress() && event.progress().step() > 0;
  }
  context->TryCancel();
  reader->Finish();
  if (!progressed) progressed = GetJob(stub, job_id).step() > 0;
  EXPECT_TRUE(progressed) << "job " << job_id << " made no progress within five minutes";
}

}  // namespace dlmfd::testing
