// Replies of the dashboard's HTTP API: JSON bodies, errors as {"error": message} with the status
// that says what went wrong (never a crash, never a stack trace), the daemon's gRPC status mapped
// onto HTTP (NOT_FOUND 404, INVALID_ARGUMENT 400, FAILED_PRECONDITION 409, UNAUTHENTICATED 401,
// PERMISSION_DENIED 403, RESOURCE_EXHAUSTED 429, UNAVAILABLE 503, DEADLINE_EXCEEDED 504, else
// 502), and protobuf messages as JSON (the CLI's --json form: field names as in the .proto,
// 64-bit integers as numbers).
#pragma once

#include <google/protobuf/message.h>
#include <grpcpp/support/status.h>
#include <httplib.h>

#include <nlohmann/json.hpp>

#include <string>

namespace dlmfd::web {

void ReplyJson(httplib::Response& res, const std::string& json, int status = 200);
void ReplyError(httplib::Response& res, int status, const std::string& message);
int HttpStatusOf(grpc::StatusCode code);
// "daemon: not found: job j-1 ..." with the mapped status.
void ReplyRpcError(httplib::Response& res, const grpc::Status& status);
std::string MessageJson(const google::protobuf::Message& message);
// One line of JSON (invalid UTF-8 replaced).
std::string JsonText(const nlohmann::json& value);
// A finite number, else null.
nlohmann::json JsonNumber(double x);

}  // namespace dlmfd::web
