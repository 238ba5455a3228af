// Formatting of jobs for people (tables, details) and for programs (JSON lines).
#include "job_text.h"

#include <google/protobuf/util/json_util.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
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

double NowEpochSeconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
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

std::string Progress(const v1::Job& job) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.4g/%.4g", job.time(), job.end_time());
  return text;
}

}  // namespace

std::string JoinText(const google::protobuf::RepeatedPtrField<std::string>& items,
                     const char* separator) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

std::string LabelsText(const google::protobuf::Map<std::string, std::string>& labels) {
  std::string out;
  for (const auto& [key, value] :
       std::map<std::string, std::string>(labels.begin(), labels.end())) {
    out += (out.empty() ? "" : ", ") + key + "=" + value;
  }
  return out;
}

std::string ExitText(const v1::Job& job) {
  if (job.exit_signal() > 0) return "signal " + std::to_string(job.exit_signal());
  return job.has_exit_code() ? std::to_string(job.exit_code()) : "-";
}

std::string MemoryText(int64_t bytes) {
  if (bytes <= 0) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return text;
}

std::string SecondsText(double seconds) {
  if (seconds <= 0) return "-";
  if (seconds >= 60) return FormatDuration(seconds);
  char text[16];
  std::snprintf(text, sizeof text, "%.1fs", seconds);
  return text;
}

std::string JobTable(const std::vector<v1::Job>& jobs) {
  const std::vector<std::string> header = {"ID",       "NAME", "STATE", "STEP",
                                           "TIME/END", "PRIO", "TAGS",  "CREATED",
                                           "ELAPSED",  "EXIT", "CPU",   "MAXRSS"};
  std::vector<std::vector<std::string>> rows = {header};
  for (const v1::Job& job : jobs) {
    const bool held = job.held() && job.state() == v1::QUEUED;
    rows.push_back({job.id(), job.name(), held ? "held" : StateName(job.state()),
                    std::to_string(job.step()), Progress(job), std::to_string(job.priority()),
                    JoinText(job.tags(), ","), FormatTimestamp(job.created_time()),
                    SecondsText(job.elapsed_seconds()), ExitText(job),
                    SecondsText(job.cpu_seconds()), MemoryText(job.peak_memory_bytes())});
  }
  return TextTable(rows);
}

std::string TextTable(const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::size_t> width;
  for (const auto& row : rows) {
    width.resize(std::max(width.size(), row.size()), 0);
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
      << "state:       " << StateName(job.state())
      << (job.held() && job.state() == v1::QUEUED ? " (held)" : "") << "\n";
  if (!job.reason().empty()) out << "reason:      " << job.reason() << "\n";
  out << "priority:    " << job.priority() << "\n"
      << "tags:        " << JoinText(job.tags(), ", ") << "\n";
  if (!job.study_id().empty()) out << "study:       " << job.study_id() << "\n";
  if (!job.after().empty()) out << "after:       " << JoinText(job.after(), ", ") << "\n";
  out << "overrides:   " << JoinText(job.overrides(), " ") << "\n"
      << "progress:    step " << job.step() << ", time " << Progress(job) << "\n"
      << "created:     " << FormatTimestamp(job.created_time()) << "\n"
      << "started:     " << FormatTimestamp(job.started_time()) << "\n"
      << "finished:    " << FormatTimestamp(job.finished_time()) << "\n";
  if (job.elapsed_seconds() > 0) {
    out << "elapsed:     " << SecondsText(job.elapsed_seconds())
        << (job.finished_time() > 0 ? "" : " (so far)") << "\n";
  }
  if (job.has_exit_code() || job.exit_signal() > 0) {
    out << "exit code:   " << ExitText(job) << " (of the latest solver run)\n";
  }
  if (job.cpu_seconds() > 0) {
    char cpu[32];
    std::snprintf(cpu, sizeof cpu, "%.2f s", job.cpu_seconds());
    out << "cpu time:    " << cpu << " (user + system, this attempt)\n";
  }
  if (job.peak_memory_bytes() > 0) {
    out << "peak memory: " << MemoryText(job.peak_memory_bytes()) << " (largest resident set)\n";
  }
  if (!job.labels().empty()) out << "labels:      " << LabelsText(job.labels()) << "\n";
  for (const v1::ParameterValue& p : job.parameters()) {
    out << "parameter:   " << p.key() << " = " << p.text() << " (" << p.type() << ")\n";
  }
  out << "attempt:     " << std::max(1, job.attempt()) << " (solver starts: " << job.attempts()
      << ")\n";
  for (const v1::AttemptRecord& a : job.previous_attempts()) {
    char time[32];
    std::snprintf(time, sizeof(time), "%.6g", a.time());
    out << "  attempt " << a.attempt() << ": " << StateName(a.state())
        << (a.reason().empty() ? "" : " (" + a.reason() + ")") << ", step " << a.step()
        << ", t = " << time << ", ended " << FormatTimestamp(a.finished_time()) << "\n";
  }
  out << "results:     " << job.results_dir() << "\n";
  if (job.disk_bytes() > 0) out << "disk:        " << job.disk_bytes() << " bytes\n";
  if (job.time_limit_seconds() > 0) {
    out << "time limit:  " << FormatDuration(static_cast<double>(job.time_limit_seconds())) << " ("
        << job.time_limit_seconds() << " s, of one run)\n";
  }
  if (!job.slurm_job_id().empty()) {
    out << "slurm job:   " << job.slurm_job_id();
    if (!job.slurm_state().empty()) {
      out << " (" << job.slurm_state()
          << (job.slurm_reason().empty() ? "" : ", " + job.slurm_reason()) << ")";
    }
    out << "\n";
  }
  // Schemes chosen by "auto", with the numbers behind the choice (docs/scenes.md).
  for (const v1::NumericsChoice& c : job.numerics()) {
    out << "numerics:    " << c.key() << " = \"" << c.value() << "\" (auto: " << c.rule();
    for (int k = 0; k < c.numbers_size(); ++k) {
      char value[32];
      std::snprintf(value, sizeof(value), "%.4g", c.numbers(k).value());
      out << (k == 0 ? "; " : ", ") << c.numbers(k).name() << " = " << value;
    }
    out << ")\n";
  }
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

namespace {

bool IsInt64(google::protobuf::FieldDescriptor::CppType type) {
  using F = google::protobuf::FieldDescriptor;
  return type == F::CPPTYPE_INT64 || type == F::CPPTYPE_UINT64;
}

// The proto3 JSON mapping writes 64-bit integers as strings (for JavaScript's doubles); scripts
// expect numbers (issue 14), so each 64-bit integer field of `descriptor` becomes a number again.
void Int64AsNumbers(nlohmann::ordered_json& json, const google::protobuf::Descriptor* descriptor) {
  if (!json.is_object()) return;
  for (int k = 0; k < descriptor->field_count(); ++k) {
    const google::protobuf::FieldDescriptor* field = descriptor->field(k);
    auto it = json.find(field->name());
    if (it == json.end() || field->is_map()) continue;
    auto convert = [&](nlohmann::ordered_json& value) {
      if (IsInt64(field->cpp_type()) && value.is_string()) {
        const std::string text = value.get<std::string>();
        if (field->cpp_type() == google::protobuf::FieldDescriptor::CPPTYPE_UINT64) {
          value = std::stoull(text);
        } else {
          value = std::stoll(text);
        }
      } else if (field->cpp_type() == google::protobuf::FieldDescriptor::CPPTYPE_MESSAGE) {
        Int64AsNumbers(value, field->message_type());
      }
    };
    if (it->is_array()) {
      for (auto& element : *it) convert(element);
    } else {
      convert(*it);
    }
  }
}

}  // namespace

std::string ToJsonLine(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = false;
  options.preserve_proto_field_names = true;
  options.always_print_primitive_fields = true;
  std::string out;
  if (!google::protobuf::util::MessageToJsonString(message, &out, options).ok()) {
    return "{\"error\":\"cannot convert " + message.GetTypeName() + " to JSON\"}";
  }
  nlohmann::ordered_json json = nlohmann::ordered_json::parse(out, nullptr, false);
  if (json.is_discarded()) return out;
  Int64AsNumbers(json, message.GetDescriptor());
  return json.dump();
}

}  // namespace dlmfd::cli
