#include "http_reply.h"

#include <cmath>

#include "job_text.h"
#include "rpc_status.h"

namespace dlmfd::web {

void ReplyJson(httplib::Response& res, const std::string& json, int status) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  res.set_content(json, "application/json");
}

void ReplyError(httplib::Response& res, int status, const std::string& message) {
  nlohmann::json body;
  body["error"] = message;
  body["status"] = status;
  ReplyJson(res, JsonText(body), status);
}

int HttpStatusOf(grpc::StatusCode code) {
  switch (code) {
    case grpc::StatusCode::OK:
      return 200;
    case grpc::StatusCode::NOT_FOUND:
      return 404;
    case grpc::StatusCode::INVALID_ARGUMENT:
    case grpc::StatusCode::OUT_OF_RANGE:
      return 400;
    case grpc::StatusCode::FAILED_PRECONDITION:
    case grpc::StatusCode::ALREADY_EXISTS:
    case grpc::StatusCode::ABORTED:
      return 409;
    case grpc::StatusCode::UNAUTHENTICATED:
      return 401;
    case grpc::StatusCode::PERMISSION_DENIED:
      return 403;
    case grpc::StatusCode::RESOURCE_EXHAUSTED:
      return 429;
    case grpc::StatusCode::UNAVAILABLE:
      return 503;
    case grpc::StatusCode::DEADLINE_EXCEEDED:
      return 504;
    default:
      return 502;
  }
}

void ReplyRpcError(httplib::Response& res, const grpc::Status& status) {
  ReplyError(res, HttpStatusOf(status.error_code()),
             "daemon: " + cli::StatusCodeName(status.error_code()) + ": " + status.error_message());
}

std::string MessageJson(const google::protobuf::Message& message) {
  return cli::ToJsonLine(message);
}

std::string JsonText(const nlohmann::json& value) {
  return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

nlohmann::json JsonNumber(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

}  // namespace dlmfd::web
