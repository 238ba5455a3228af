// libFuzzer target: every rpc of dlmfd.v1.Jobs with any request body (issue 38 point 1).
//
// The real daemon (server/src/daemon.h: store on a SQLite file, scheduler, gRPC server with its
// interceptors) runs in this process on a free loopback port, in a temporary data directory; the
// fuzzer's first byte picks the rpc, the rest is the request body as it goes on the wire. Every
// call must end within its deadline with a code jobs.proto promises (not UNKNOWN, INTERNAL,
// UNIMPLEMENTED or UNAVAILABLE); the daemon must stay up. Accepted jobs run the real solver
// ($DLMFD_SOLVER_BINARY, a release dlmfd-solve) under small limits so that they end quickly.
// Watch is read to its first message (a live job's stream lasts as long as the job), Fetch to its
// end. Run: scripts/fuzz.sh (bounded; CI).
#include <grpcpp/create_channel.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/security/credentials.h>
#include <spdlog/spdlog.h>
#include <stdlib.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "../support/promised_codes.h"
#include "../support/raw_grpc_call.h"
#include "config.h"
#include "daemon.h"
#include "dlmfd/v1/jobs.grpc.pb.h"

namespace {

namespace fs = std::filesystem;
using dlmfd::server::Config;
using dlmfd::server::Daemon;

struct Harness {
  std::string data_dir;
  std::unique_ptr<Daemon> daemon;
  std::shared_ptr<grpc::Channel> channel;
  std::unique_ptr<grpc::GenericStub> generic;
  std::unique_ptr<dlmfd::v1::Jobs::Stub> stub;
  const google::protobuf::ServiceDescriptor* service = nullptr;
};

Harness* harness = nullptr;

[[noreturn]] void Finding(const std::string& what) {
  std::fprintf(stderr, "rpc_request_fuzz: %s\n", what.c_str());
  std::abort();
}

void StartDaemon() {
  const char* solver = std::getenv("DLMFD_SOLVER_BINARY");
  if (solver == nullptr || *solver == '\0') {
    std::fprintf(stderr, "rpc_request_fuzz: set DLMFD_SOLVER_BINARY to a dlmfd-solve\n");
    std::exit(2);
  }
  char pattern[] = "/tmp/dlmfd-rpc-fuzz-XXXXXX";
  if (mkdtemp(pattern) == nullptr) Finding("mkdtemp failed");
  harness = new Harness;
  harness->data_dir = pattern;
  Config config;
  config.listen = "127.0.0.1:0";
  config.data_dir = harness->data_dir + "/data";
  config.solver = solver;
  config.max_concurrent = 1;
  config.max_queued = 32;  // a full queue is RESOURCE_EXHAUSTED, which is fine
  config.max_steps = 20;   // accepted jobs end in a moment
  config.max_grid_nodes = 20'000;
  config.max_user_disk_mb = 64;
  config.solver_threads = 1;
  config.log_level = "off";
  dlmfd::server::ValidateConfig(config);
  spdlog::set_level(spdlog::level::off);
  harness->daemon = std::make_unique<Daemon>(config);
  harness->daemon->Start();
  harness->channel = grpc::CreateChannel("127.0.0.1:" + std::to_string(harness->daemon->port()),
                                         grpc::InsecureChannelCredentials());
  harness->generic = std::make_unique<grpc::GenericStub>(harness->channel);
  harness->stub = dlmfd::v1::Jobs::NewStub(harness->channel);
  harness->service = dlmfd::v1::SubmitRequest::descriptor()->file()->FindServiceByName("Jobs");
}

void RemoveDataDir() {
  if (harness == nullptr) return;
  harness->daemon->Shutdown();
  std::error_code ignored;
  fs::remove_all(harness->data_dir, ignored);
}

grpc::Status Unary(const std::string& method, const std::string& body) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
  return dlmfd::testing::RawUnaryCall(*harness->generic, context, method, body);
}

template <class Reply, class Request, class Open>
grpc::Status Stream(const Request& request, bool first_only, Open open) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
  auto reader = open(&context, request);
  return dlmfd::testing::ReadStream<Reply>(context, *reader, first_only);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  StartDaemon();
  std::atexit(RemoveDataDir);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const auto* method = harness->service->method(data[0] % harness->service->method_count());
  const std::string body(reinterpret_cast<const char*>(data + 1), size - 1);
  grpc::Status status;
  dlmfd::v1::WatchRequest watch;
  dlmfd::v1::FetchRequest fetch;
  if (method->name() == "Watch" && watch.ParseFromString(body)) {
    status = Stream<dlmfd::v1::WatchEvent>(
        watch, true, [](grpc::ClientContext* c, const dlmfd::v1::WatchRequest& r) {
          return harness->stub->Watch(c, r);
        });
  } else if (method->name() == "Fetch" && fetch.ParseFromString(body)) {
    status = Stream<dlmfd::v1::FileChunk>(
        fetch, false, [](grpc::ClientContext* c, const dlmfd::v1::FetchRequest& r) {
          return harness->stub->Fetch(c, r);
        });
  } else {
    // Unary, or a body that does not parse (the daemon names the request it cannot read).
    status = Unary("/dlmfd.v1.Jobs/" + method->name(), body);
  }
  if (dlmfd::testing::kPromisedCodes.count(status.error_code()) == 0) {
    Finding(method->name() + " answered code " + std::to_string(status.error_code()) + ": " +
            status.error_message().substr(0, 500));
  }
  return 0;
}
