#include "study_text.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <map>
#include <sstream>

#include "job_text.h"

namespace dlmfd::cli {
namespace {

std::string Percent(double fraction) {
  char text[16];
  std::snprintf(text, sizeof(text), "%.0f%%", 100.0 * std::clamp(fraction, 0.0, 1.0));
  return text;
}

}  // namespace

StudyCounts CountJobs(const std::vector<v1::Job>& jobs) {
  StudyCounts c;
  for (const v1::Job& job : jobs) {
    ++c.jobs;
    switch (job.state()) {
      case v1::QUEUED:
        ++c.queued;
        break;
      case v1::RUNNING:
        ++c.running;
        break;
      case v1::COMPLETED:
        ++c.completed;
        break;
      case v1::FAILED:
        ++c.failed;
        break;
      case v1::CANCELLED:
        ++c.cancelled;
        break;
      default:
        break;
    }
    if (IsFinal(job.state())) {
      c.work_done += 1.0;
    } else if (job.end_time() > 0) {
      c.work_done += std::clamp(job.time() / job.end_time(), 0.0, 1.0);
    }
    if (job.started_time() > 0 && (c.first_started == 0 || job.started_time() < c.first_started)) {
      c.first_started = job.started_time();
    }
  }
  return c;
}

double StudyEta(const StudyCounts& counts, double now) {
  if (counts.Finished()) return 0.0;
  const double elapsed = now - counts.first_started;
  if (counts.first_started <= 0 || elapsed <= 0 || counts.work_done <= 0) return -1.0;
  const double remaining = counts.jobs - counts.work_done;
  return remaining * elapsed / counts.work_done;
}

std::vector<LineField> StudyFields(const std::string& label, const StudyCounts& c,
                                   double eta_seconds) {
  char counts[160];
  std::snprintf(counts, sizeof(counts), "%d queued  %d running  %d done  %d failed", c.queued,
                c.running, c.completed, c.failed);
  std::string cancelled = c.cancelled > 0 ? std::to_string(c.cancelled) + " cancelled" : "";
  return {{label + " " + std::to_string(c.jobs) + " jobs", 10},
          {counts, 9},
          {cancelled, 5},
          {Percent(c.jobs > 0 ? c.work_done / c.jobs : 0.0), 6},
          {"ETA " + FormatDuration(eta_seconds), 8}};
}

std::string StudyListText(const std::vector<v1::Study>& studies, double now) {
  std::vector<std::vector<std::string>> rows = {{"ID", "NAME", "TAGS", "JOBS", "QUEUED", "RUNNING",
                                                 "DONE", "FAILED", "CANCELLED", "PROGRESS", "AGE"}};
  for (const v1::Study& s : studies) {
    rows.push_back({s.id(), s.name(), JoinText(s.tags(), ","), std::to_string(s.jobs()),
                    std::to_string(s.queued()), std::to_string(s.running()),
                    std::to_string(s.completed()), std::to_string(s.failed()),
                    std::to_string(s.cancelled()), Percent(s.progress()),
                    FormatDuration(now - s.created_time())});
  }
  return TextTable(rows);
}

std::string AxisText(const v1::StudyAxis& axis) {
  std::string text = axis.key() + "=" + JoinText(axis.values(), ",");
  if (axis.has_range()) {
    // The range as given, each bound as the shortest text that reads back as it.
    auto shortest = [](double x) {
      char digits[40];
      return std::string(digits, std::to_chars(digits, digits + sizeof digits, x).ptr);
    };
    text += std::string("  (") + (axis.range().logarithmic() ? "log" : "linear") + " range " +
            shortest(axis.range().start()) + ":" + shortest(axis.range().stop()) + ":" +
            std::to_string(axis.range().count()) + ")";
  }
  return text;
}

std::string StudyDetails(const v1::Study& s) {
  std::ostringstream out;
  out << "study:       " << s.id() << "\n"
      << "name:        " << s.name() << "\n"
      << "owner:       " << s.owner() << "\n"
      << "tags:        " << JoinText(s.tags(), ", ") << "\n";
  if (!s.labels().empty()) out << "labels:      " << LabelsText(s.labels()) << "\n";
  for (const v1::StudyAxis& axis : s.axes()) {
    out << "axis:        " << AxisText(axis)
        << (axis.zip().empty() ? "" : "  (zipped: " + axis.zip() + ")") << "\n";
  }
  if (s.overrides_size() > 0) out << "overrides:   " << JoinText(s.overrides(), " ") << "\n";
  out << "max running: " << (s.max_running() > 0 ? std::to_string(s.max_running()) : "no limit")
      << "\n"
      << "jobs:        " << s.jobs() << ": " << s.queued() << " queued, " << s.running()
      << " running, " << s.completed() << " completed, " << s.failed() << " failed, "
      << s.cancelled() << " cancelled\n"
      << "progress:    " << Percent(s.progress()) << "\n"
      << "created:     " << FormatTimestamp(s.created_time()) << "\n";
  return out.str();
}

}  // namespace dlmfd::cli
