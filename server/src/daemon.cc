#include "daemon.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>
#include <grpcpp/server_builder.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "clock.h"
#include "dlmfd/io/atomic_file.h"
#include "job_proto.h"
#include "loopback_port.h"
#include "unreadable_request.h"

namespace dlmfd::server {
namespace fs = std::filesystem;

Daemon::Daemon(Config config)
    : config_(std::move(config)) {}

Daemon::~Daemon() {
  Shutdown();
  if (lock_fd_ >= 0) close(lock_fd_);
}

void Daemon::Start() {
  std::error_code error;
  fs::create_directories(fs::path(config_.data_dir) / "jobs", error);
  if (error) {
    throw ConfigError("data_dir " + config_.data_dir + " cannot be created: " + error.message());
  }
  const std::string lock_path = (fs::path(config_.data_dir) / "daemon.lock").string();
  lock_fd_ = open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (lock_fd_ < 0 || flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    throw ConfigError("data_dir " + config_.data_dir + " is in use by another dlmfdd (" +
                      lock_path + " is locked)");
  }
  store_ = std::make_unique<JobStore>((fs::path(config_.data_dir) / "jobs.db").string());
  for (const auto& id : store_->RequeueRunning(SystemClock().Now())) {
    spdlog::info("job {}: was RUNNING when the daemon stopped; QUEUED to resume", id);
  }
  executor_ = MakeExecutor(config_);
  hub_ = std::make_unique<EventHub>(
      *store_, [this](const std::string& id) { return executor_->JobDirectory(id); });
  hub_->Recover((fs::path(config_.data_dir) / "watch_seq").string());
  scheduler_ = std::make_unique<Scheduler>(config_, *executor_, *store_, *hub_);
  service_ = std::make_unique<JobsService>(config_, *store_, *hub_, *scheduler_);

  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  for (const auto& warning : ConfigWarnings(config_)) spdlog::warn("{}", warning);
  RequireLoopbackPortFree(config_.listen);
  grpc::ServerBuilder builder;
  // One daemon per port: gRPC sets SO_REUSEPORT by default, and then a second daemon would bind
  // the same port and the kernel would split the clients between the two.
  builder.AddChannelArgument(GRPC_ARG_ALLOW_REUSEPORT, 0);
  builder.AddListeningPort(config_.listen, grpc::InsecureServerCredentials(), &port_);
  builder.RegisterService(service_.get());
  std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> interceptors;
  interceptors.push_back(std::make_unique<UnreadableRequestFactory>(
      std::vector<std::string>{v1::Jobs::service_full_name()}));
  builder.experimental().SetInterceptorCreators(std::move(interceptors));
  builder.SetMaxReceiveMessageSize(
      static_cast<int>(std::min<int64_t>(config_.max_scene_bytes * 2 + (1 << 20), INT32_MAX)));
  server_ = builder.BuildAndStart();
  if (!server_ || port_ == 0) {
    throw ConfigError("cannot listen on " + config_.listen +
                      ": the address is in use (by another dlmfdd?) or not available here "
                      "(change listen, --listen or DLMFD_LISTEN)");
  }
  port_guard_ = LoopbackPortGuard(config_.listen, port_);
  // The health service answers for the server ("") and for the one service it serves.
  server_->GetHealthCheckService()->SetServingStatus(v1::Jobs::service_full_name(), true);
  scheduler_->Start();
  spdlog::info("dlmfdd listening on {} (port {}), data in {}, {} concurrent jobs, solver {}",
               config_.listen, port_, config_.data_dir, config_.max_concurrent, config_.solver);
  if (config_.tokens.empty()) {
    spdlog::info("no tokens configured: every caller is the user \"local\" (loopback only)");
  }
  if (!config_.port_file.empty()) {
    // Written whole or not at all: whoever polls for it never reads a half-written number.
    WriteTextAtomically(config_.port_file, std::to_string(port_) + "\n");
  }
}

void Daemon::Shutdown() {
  if (stopped_) return;
  stopped_ = true;
  if (server_) {
    spdlog::info("dlmfdd shutting down");
    server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  }
  if (scheduler_) scheduler_->Stop();
  // The solvers have stopped: no more events; the store learns the numbers actually issued.
  if (hub_) hub_->RecordIssued();
  if (server_) server_->Wait();
}

}  // namespace dlmfd::server
