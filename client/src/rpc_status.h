// gRPC status -> exit code and one clear line on stderr ("dlmfd submit: not found: job 12 ...").
#pragma once

#include <grpcpp/support/status.h>

#include <string>

namespace dlmfd::cli {

int ExitCodeFor(grpc::StatusCode code);
// The code's name in lower case words ("invalid argument").
std::string StatusCodeName(grpc::StatusCode code);
// Prints "dlmfd <command>: <code name>: <message>" and returns ExitCodeFor(status).
int ReportRpcError(const std::string& command, const grpc::Status& status);
// Prints "dlmfd <command>: <message>" and returns `code`.
int ReportError(const std::string& command, const std::string& message, int code);

}  // namespace dlmfd::cli
