#include "daemon_link.h"

namespace dlmfd::web {

DaemonLink::DaemonLink(const cli::Endpoint& endpoint, double timeout_seconds)
    : address_(endpoint.server),
      timeout_(std::chrono::milliseconds(static_cast<long long>(timeout_seconds * 1000.0))) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(64 << 20);
  // A restarted daemon is found again within a second or two (gRPC's default back-off reaches
  // two minutes, which would leave a page waiting long after the daemon is back).
  args.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, 200);
  args.SetInt(GRPC_ARG_MIN_RECONNECT_BACKOFF_MS, 200);
  args.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 1000);
  channel_ = grpc::CreateCustomChannel(address_, grpc::InsecureChannelCredentials(), args);
  jobs_ = v1::Jobs::NewStub(channel_);
}

std::unique_ptr<grpc::ClientContext> DaemonLink::Stream(const std::string& token) const {
  auto context = std::make_unique<grpc::ClientContext>();
  if (!token.empty()) context->AddMetadata("authorization", "Bearer " + token);
  return context;
}

std::unique_ptr<grpc::ClientContext> DaemonLink::Unary(const std::string& token) const {
  auto context = Stream(token);
  context->set_deadline(std::chrono::system_clock::now() + timeout_);
  return context;
}

grpc::Status DaemonLink::ProbeWithoutToken() {
  auto context = Unary("");
  v1::ListStudiesRequest request;
  request.set_page_size(1);
  v1::ListStudiesResponse response;
  return jobs_->ListStudies(context.get(), request, &response);
}

}  // namespace dlmfd::web
