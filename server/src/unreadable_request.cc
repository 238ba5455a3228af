#include "unreadable_request.h"

#include <google/protobuf/descriptor.h>

#include <atomic>
#include <string>

namespace dlmfd::server {
namespace {

using grpc::experimental::InterceptionHookPoints;

// "/dlmfd.v1.Jobs/Submit" -> the input type's full name, or "" when the method is not in the
// generated descriptor pool (health, reflection: their names are said as the method only).
std::string RequestType(const std::string& method) {
  const auto slash = method.rfind('/');
  if (method.empty() || slash == std::string::npos || slash == 0) return "";
  const std::string service = method.substr(1, slash - 1);
  const auto* descriptor =
      google::protobuf::DescriptorPool::generated_pool()->FindServiceByName(service);
  const auto* rpc = descriptor ? descriptor->FindMethodByName(method.substr(slash + 1)) : nullptr;
  return rpc ? rpc->input_type()->full_name() : "";
}

class UnreadableRequest final : public grpc::experimental::Interceptor {
 public:
  explicit UnreadableRequest(std::string method)
      : method_(std::move(method)) {}
  // gRPC runs a call's hook points, then destroys its interceptors, one after the other but
  // possibly on different threads, handing the call over inside its (uninstrumented) library:
  // the acquire here and at each Intercept's start, paired with the release at each Intercept's
  // end, state that order where ThreadSanitizer can see it (scripts/tsan.sh).
  ~UnreadableRequest() override { (void)handoff_.load(std::memory_order_acquire); }

  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    handoff_.fetch_add(1, std::memory_order_acq_rel);
    Hook(methods);
    // Proceed may hand the call to another thread, which may run the next hook or destroy this.
    handoff_.fetch_add(1, std::memory_order_acq_rel);
    methods->Proceed();
  }

 private:
  void Hook(grpc::experimental::InterceptorBatchMethods* methods) {
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::POST_RECV_MESSAGE) &&
        methods->GetRecvMessage() == nullptr) {
      unreadable_ = true;
    }
    if (unreadable_ &&
        methods->QueryInterceptionHookPoint(InterceptionHookPoints::PRE_SEND_STATUS) &&
        methods->GetSendStatus().error_code() == grpc::StatusCode::UNIMPLEMENTED) {
      const std::string type = RequestType(method_);
      methods->ModifySendStatus(
          grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                       "request: the body of " + method_ + " cannot be read as " +
                           (type.empty() ? std::string("its request message") : type) +
                           " (malformed protobuf, or a string field that is not UTF-8)"));
    }
  }

  const std::string method_;
  bool unreadable_ = false;
  std::atomic<unsigned> handoff_{0};
};

}  // namespace

grpc::experimental::Interceptor* UnreadableRequestFactory::CreateServerInterceptor(
    grpc::experimental::ServerRpcInfo* info) {
  return new UnreadableRequest(info->method() ? info->method() : "");
}

}  // namespace dlmfd::server
