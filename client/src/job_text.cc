// Formatting of jobs for people (tables, details) and for programs (JSON lines).
#include "job_text.h"

#include <google/protobuf/util/json_util.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "connection.h"

namespace dlmfd::cli {

std::string StateName(v1::JobState state) {
  switch (state) {
    case v1::QUEUED:
      return "queued";
    case v1::RUNNING:
      return "running";
    case v1::COMPLETED:
      return "completed";
    case v1::FAILED:
      return "failed";
    case v1::CANCELLED:
      return "cancelled";
    default:
      return "unspecified";
  }
}

v1::JobState ParseState(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  for (v1::JobState s : {v1::QUEUED, v1::RUNNING, v1::COMPLETED, v1::FAILED, v1::CANCELLED}) {
    if (StateName(s) == lower) return s;
  }
  throw UsageError("--state " + name +
                   " is not allowed: expected queued, running, completed, failed or cancelled");
}

bool IsFinal(v1::JobState state) {
  return state == v1::COMPLETED || state == v1::FAILED || state == v1::CANCELLED;
}

std::string FormatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "-";
  const long long s = std::llround(seconds);
  char text[32];
  if (s < 60) {
    std::snprintf(text, sizeof(text), "%llds", s);
  } else if (s < 3600) {
    std::snprintf(text, sizeof(text), "%lldm%02llds", s / 60, s % 60);
  } else if (s < 86400) {
    std::snprintf(text, sizeof(text), "%lldh%02lldm", s / 3600, (s % 3600) / 60);
  } else {
    std::snprintf(text, sizeof(text), "%lldd%02lldh", s / 86400, (s % 86400) / 3600);
  }
  return text;
}

std::string FormatTimestamp(double epoch_seconds) {
  if (epoch_seconds <= 0) return "-";
  const std::time_t t = static_cast<std::time_t>(epoch_seconds);
  std::tm local{};
  localtime_r(&t, &local);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%d %H:%M:%S", &local);
  return text;
}

namespace {

std::string Join(const google::protobuf::RepeatedPtrField<std::string>& items,
                 const char* separator) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

std::string Progress(const v1::Job& job) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.4g/%.4g", job.time(), job.end_time());
  return text;
}

}  // namespace

std::string JobTable(const std::vector<v1::Job>& jobs) {
  const std::vector<std::string> header = {"ID",       "NAME", "STATE", "STEP",
                                           "TIME/END", "PRIO", "TAGS",  "CREATED"};
  std::vector<std::vector<std::string>> rows = {header};
  for (const v1::Job& job : jobs) {
    rows.push_back({job.id(), job.name(), StateName(job.state()), std::to_string(job.step()),
                    Progress(job), std::to_string(job.priority()), Join(job.tags(), ","),
                    FormatTimestamp(job.created_time())});
  }
  std::vector<std::size_t> width(header.size(), 0);
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  }
  std::ostringstream out;
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c) {
      line += row[c];
      if (c + 1 < row.size()) line += std::string(width[c] - row[c].size() + 2, ' ');
    }
    out << line << "\n";
  }
  return out.str();
}

std::string JobDetails(const v1::Job& job) {
  std::ostringstream out;
  out << "id:          " << job.id() << "\n"
      << "name:        " << job.name() << "\n"
      << "owner:       " << job.owner() << "\n"
      << "state:       " << StateName(job.state()) << "\n";
  if (!job.reason().empty()) out << "reason:      " << job.reason() << "\n";
  out << "priority:    " << job.priority() << "\n"
      << "tags:        " << Join(job.tags(), ", ") << "\n";
  if (!job.sweep_id().empty()) out << "sweep:       " << job.sweep_id() << "\n";
  out << "overrides:   " << Join(job.overrides(), " ") << "\n"
      << "progress:    step " << job.step() << ", time " << Progress(job) << "\n"
      << "created:     " << FormatTimestamp(job.created_time()) << "\n"
      << "started:     " << FormatTimestamp(job.started_time()) << "\n"
      << "finished:    " << FormatTimestamp(job.finished_time()) << "\n";
  if (job.started_time() > 0 && job.finished_time() > 0) {
    out << "ran for:     " << FormatDuration(job.finished_time() - job.started_time()) << "\n";
  }
  out << "attempts:    " << job.attempts() << "\n"
      << "results:     " << job.results_dir() << "\n";
  if (!job.slurm_job_id().empty()) out << "slurm job:   " << job.slurm_job_id() << "\n";
  // Settings outside the accuracy envelope: what to change, and to what (docs/scenes.md).
  for (const v1::AccuracyWarning& w : job.warnings()) {
    char value[32];
    std::snprintf(value, sizeof(value), "%.4g", w.value());
    out << "warning:     " << w.setting() << " = " << value << " (allowed " << w.allowed() << ", "
        << w.source() << "): set " << w.key() << " = " << w.suggested() << " (now " << w.current()
        << ")\n";
  }
  return out.str();
}

std::string ToJsonLine(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = false;
  options.preserve_proto_field_names = true;
  options.always_print_primitive_fields = true;
  std::string out;
  if (!google::protobuf::util::MessageToJsonString(message, &out, options).ok()) {
    out = "{\"error\":\"cannot convert " + message.GetTypeName() + " to JSON\"}";
  }
  return out;
}

}  // namespace dlmfd::cli
