// dlmfd health [--service NAME] [--wait SECONDS]
// The standard gRPC health check (grpc.health.v1.Health/Check). Prints "SERVING" and exits 0, or
// prints the status and exits 5 when the daemon is not serving or cannot be reached. --wait keeps
// asking (every 0.2 s) until it serves or the time is up: what scripts use after starting dlmfdd.
#include <chrono>
#include <iostream>
#include <thread>

#include "command.h"
#include "connection.h"
#include "exit_codes.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "rpc_status.h"

namespace dlmfd::cli {

int RunHealth(int argc, char** argv) {
  CLI::App app{"Ask the daemon whether it is serving."};
  ConnectionFlags connection_flags;
  AddConnectionFlags(app, connection_flags);
  std::string service;
  double wait_seconds = 0.0;
  app.add_option("--service", service, "service name (default: the whole server)");
  app.add_option("--wait", wait_seconds, "retry until serving, for at most this many seconds")
      ->check(CLI::NonNegativeNumber);
  if (auto code = ParseArgs(app, argc, argv)) return *code;

  return Guarded("health", [&] {
    Connection connection(connection_flags);
    auto stub = grpc::health::v1::Health::NewStub(connection.channel());
    const auto give_up =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_seconds);
    for (;;) {
      auto context = connection.UnaryContext();
      grpc::health::v1::HealthCheckRequest request;
      request.set_service(service);
      grpc::health::v1::HealthCheckResponse response;
      const grpc::Status status = stub->Check(context.get(), request, &response);
      const bool serving =
          status.ok() && response.status() == grpc::health::v1::HealthCheckResponse::SERVING;
      if (serving) {
        std::cout << "SERVING " << connection.endpoint().server << "\n";
        return kExitOk;
      }
      if (std::chrono::steady_clock::now() >= give_up) {
        if (!status.ok()) return ReportRpcError("health", status);
        std::cout << grpc::health::v1::HealthCheckResponse::ServingStatus_Name(response.status())
                  << " " << connection.endpoint().server << "\n";
        return kExitUnavailable;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
  });
}

}  // namespace dlmfd::cli
