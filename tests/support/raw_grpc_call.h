// Calls through a generic stub with the request as it goes on the wire: a unary call with a raw
// body, and the read of a server stream to its end or to its first message. The hostile-input
// test, the request checks, the daemon's health probe and the rpc fuzz target make them.
#pragma once

#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>

#include <string>
#include <vector>

namespace dlmfd::testing {

// Sends `body` as the request of `method` ("/dlmfd.v1.Jobs/Submit") and waits for the status; the
// reply's bytes go to `reply` when given and the call succeeded. On a completion queue this thread
// drains, not the callback API: there gRPC's completing thread writes the status text that its
// callback thread reads, a hand-off inside the uninstrumented library that ThreadSanitizer
// reported as a race (scripts/tsan.sh).
inline grpc::Status RawUnaryCall(grpc::GenericStub& stub, grpc::ClientContext& context,
                                 const std::string& method, const std::string& body,
                                 std::string* reply = nullptr) {
  grpc::Slice slice(body);
  grpc::ByteBuffer request(&slice, 1), reply_buffer;
  grpc::Status status;
  grpc::CompletionQueue queue;
  auto call = stub.PrepareUnaryCall(&context, method, request, &queue);
  call->StartCall();
  int finished_tag = 0;
  call->Finish(&reply_buffer, &status, &finished_tag);
  void* tag = nullptr;
  bool ok = false;
  while (queue.Next(&tag, &ok) && tag != &finished_tag) {}
  queue.Shutdown();
  while (queue.Next(&tag, &ok)) {}
  std::vector<grpc::Slice> slices;
  if (reply != nullptr && status.ok() && reply_buffer.Dump(&slices).ok()) {
    for (const auto& s : slices) reply->append(reinterpret_cast<const char*>(s.begin()), s.size());
  }
  return status;
}

// Reads the stream of `reader` (opened with `context`) to its end, or, with first_only, to its
// first message and then cancels it; returns its status, OK for a stream this client cancelled
// after its first message.
template <class Reply, class Reader>
grpc::Status ReadStream(grpc::ClientContext& context, Reader& reader, bool first_only) {
  Reply reply;
  bool first = false;
  while (reader.Read(&reply)) {
    first = true;
    if (first_only) {
      context.TryCancel();
      break;
    }
  }
  grpc::Status status = reader.Finish();
  if (first_only && first && status.error_code() == grpc::StatusCode::CANCELLED) {
    return grpc::Status::OK;  // cancelled by this client after the first message
  }
  return status;
}

}  // namespace dlmfd::testing
