#include "retry_plan.h"

#include "scene_values.h"

namespace dlmfd::server {
namespace {

std::string Trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

std::string KeyOf(const std::string& override_text) {
  return Trimmed(override_text.substr(0, override_text.find('=')));
}

std::string ValueOf(const std::string& override_text) {
  const auto eq = override_text.find('=');
  return eq == std::string::npos ? "" : Trimmed(override_text.substr(eq + 1));
}

// "[key=value,...]": a study point's label as SubmitStudy writes it (study_expansion.cc).
std::string PointLabel(const std::vector<ParameterValue>& parameters) {
  std::string label = "[";
  for (size_t i = 0; i < parameters.size(); ++i) {
    label += (i ? "," : "") + parameters[i].key + "=" + parameters[i].text;
  }
  return label + "]";
}

}  // namespace

std::vector<std::string> MergeOverrides(const std::vector<std::string>& current,
                                        const std::vector<std::string>& changes) {
  std::vector<std::string> out = current;
  for (const std::string& change : changes) {
    bool replaced = false;
    for (std::string& existing : out) {
      if (KeyOf(existing) == KeyOf(change)) {
        existing = change;
        replaced = true;
      }
    }
    if (!replaced) out.push_back(change);
  }
  return out;
}

std::vector<ParameterValue> UpdatedParameters(const std::vector<ParameterValue>& parameters,
                                              const std::vector<std::string>& changes) {
  std::vector<ParameterValue> out = parameters;
  for (ParameterValue& p : out) {
    for (const std::string& change : changes) {
      if (KeyOf(change) == p.key) p = TypedValue(p.key, ValueOf(change));
    }
  }
  return out;
}

std::string RenamedPoint(const std::string& name, const std::vector<ParameterValue>& before,
                         const std::vector<ParameterValue>& after) {
  if (before.empty()) return name;
  const std::string old_label = PointLabel(before);
  if (name.size() < old_label.size() ||
      name.compare(name.size() - old_label.size(), old_label.size(), old_label) != 0) {
    return name;
  }
  return name.substr(0, name.size() - old_label.size()) + PointLabel(after);
}

bool ResumesFromCheckpoint(const JobRecord& job, const std::vector<std::string>& next_overrides) {
  return job.state != JobState::kCompleted && next_overrides == job.overrides;
}

}  // namespace dlmfd::server
