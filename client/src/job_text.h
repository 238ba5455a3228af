// How jobs and events look on a terminal and in scripts: state names, the list table, the details
// of one job, durations, and one-line JSON of any message (NDJSON).
#pragma once

#include <google/protobuf/message.h>

#include <string>
#include <vector>

#include "dlmfd/v1/jobs.pb.h"

namespace dlmfd::cli {

std::string StateName(v1::JobState state);  // "queued", "running", ...
// Accepts a state name in any case; throws UsageError naming the allowed names otherwise.
v1::JobState ParseState(const std::string& name);
bool IsFinal(v1::JobState state);
// "45s", "3m05s", "2h10m", "3d04h"; "-" for a negative or non-finite value.
std::string FormatDuration(double seconds);
// Seconds since the Unix epoch, now.
double NowEpochSeconds();
// Local time "YYYY-MM-DD HH:MM:SS" of seconds since the epoch; "-" for 0.
std::string FormatTimestamp(double epoch_seconds);
// Rows as columns padded to their widest cell, two spaces apart.
std::string TextTable(const std::vector<std::vector<std::string>>& rows);
std::string JoinText(const google::protobuf::RepeatedPtrField<std::string>& items,
                     const char* separator);
// "k=v, k=v" in key order.
std::string LabelsText(const google::protobuf::Map<std::string, std::string>& labels);
// The list table: one header line and one line per job.
// The accounting columns: "0", "signal 9", "-" (no run ended yet); "12.5 MiB"; "1m05s".
std::string ExitText(const v1::Job& job);
std::string MemoryText(int64_t bytes);
std::string SecondsText(double seconds);
std::string JobTable(const std::vector<v1::Job>& jobs);
// "key: value" lines describing one job.
std::string JobDetails(const v1::Job& job);
// The message as one line of JSON (proto3 JSON mapping, field names as in the .proto).
std::string ToJsonLine(const google::protobuf::Message& message);

}  // namespace dlmfd::cli
