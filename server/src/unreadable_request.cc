#include "unreadable_request.h"

#include <google/protobuf/descriptor.h>

#include <atomic>
#include <string>
#include <utility>

namespace dlmfd::server {
namespace {

using grpc::experimental::InterceptionHookPoints;

// The services gRPC adds to the daemon (EnableDefaultHealthCheckService, the reflection plugin):
// served, but their request types are not in the generated pool (named by the method only).
bool ServedByGrpc(const std::string& method) {
  for (const char* service :
       {"/grpc.health.v1.Health/", "/grpc.reflection.v1alpha.ServerReflection/"}) {
    if (method.rfind(service, 0) == 0) return true;
  }
  return false;
}

class UnreadableRequest final : public grpc::experimental::Interceptor {
 public:
  UnreadableRequest(std::string method, std::string type)
      : method_(std::move(method)),
        type_(std::move(type)) {}
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
      methods->ModifySendStatus(
          grpc::Status(grpc::StatusCode::INVALID_ARGUMENT,
                       "request: the body of " + method_ + " cannot be read as " +
                           (type_.empty() ? std::string("its request message") : type_) +
                           " (malformed protobuf, or a string field that is not UTF-8)"));
    }
  }

  const std::string method_;
  const std::string type_;  // the request message's full name; empty: not in the generated pool
  bool unreadable_ = false;
  std::atomic<unsigned> handoff_{0};
};

}  // namespace

UnreadableRequestFactory::UnreadableRequestFactory(const std::vector<std::string>& services) {
  const auto* pool = google::protobuf::DescriptorPool::generated_pool();
  for (const std::string& name : services) {
    const auto* service = pool->FindServiceByName(name);
    for (int m = 0; service != nullptr && m < service->method_count(); ++m) {
      const auto* rpc = service->method(m);
      request_types_["/" + name + "/" + rpc->name()] = rpc->input_type()->full_name();
    }
  }
}

// A method this daemon does not serve is answered UNIMPLEMENTED by gRPC's handler of unknown
// methods, which is right and leaves nothing to name: such a call gets no interceptor (gRPC skips a
// null one), so no code of the daemon touches that handler's call object. scripts/tsan.supp's one
// `race:` line, on gRPC's own race in that object, relies on this.
grpc::experimental::Interceptor* UnreadableRequestFactory::CreateServerInterceptor(
    grpc::experimental::ServerRpcInfo* info) {
  const std::string method = info->method() ? info->method() : "";
  const auto found = request_types_.find(method);
  if (found != request_types_.end()) return new UnreadableRequest(method, found->second);
  return ServedByGrpc(method) ? new UnreadableRequest(method, "") : nullptr;
}

}  // namespace dlmfd::server
