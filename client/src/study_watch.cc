#include "study_watch.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <map>
#include <thread>

#include "exit_codes.h"
#include "job_text.h"
#include "rpc_status.h"
#include "study_text.h"
#include "terminal_width.h"

namespace dlmfd::cli {
namespace {

std::atomic<bool> g_study_interrupted{false};

extern "C" void OnStudyInterrupt(int) { g_study_interrupted.store(true); }

nlohmann::ordered_json CountsJson(const JobSelection& selection, const StudyCounts& c, double eta) {
  nlohmann::ordered_json j;
  if (!selection.study.empty()) j["study"] = selection.study;
  if (!selection.tags.empty()) j["tags"] = selection.tags;
  j["jobs"] = c.jobs;
  j["queued"] = c.queued;
  j["running"] = c.running;
  j["completed"] = c.completed;
  j["failed"] = c.failed;
  j["cancelled"] = c.cancelled;
  j["progress"] = c.jobs > 0 ? c.work_done / c.jobs : 0.0;
  j["eta_seconds"] = eta;
  return j;
}

}  // namespace

int WatchStudy(Connection& connection, const JobSelection& selection, PrintMode mode,
               std::ostream& out, double interval_seconds) {
  g_study_interrupted.store(false);
  std::signal(SIGINT, OnStudyInterrupt);
  std::signal(SIGTERM, OnStudyInterrupt);
  const std::string label = !selection.study.empty() ? selection.study : SelectionName(selection);
  std::map<std::string, v1::JobState> seen;
  std::string last_counts;
  bool line_shown = false;
  int code = kExitOk;
  for (bool first = true;; first = false) {
    std::vector<v1::Job> jobs;
    const grpc::Status status = SelectJobs(connection, selection, jobs);
    if (!status.ok()) {
      if (line_shown) out << "\n";
      code = ReportRpcError("watch", status);
      break;
    }
    if (jobs.empty()) {
      code = ReportError("watch", "no job carries " + SelectionName(selection), kExitNotFound);
      break;
    }
    const StudyCounts counts = CountJobs(jobs);
    const double eta = StudyEta(counts, NowEpochSeconds());
    // Jobs that ended since the last look (all finished ones on the first look are not news).
    for (auto it = jobs.rbegin(); it != jobs.rend(); ++it) {
      const auto before = seen.find(it->id());
      const bool news =
          !first && IsFinal(it->state()) && (before == seen.end() || before->second != it->state());
      seen[it->id()] = it->state();
      if (!news || mode == PrintMode::kJson) continue;
      if (line_shown) out << "\r\033[K";
      line_shown = false;
      out << it->id() << " " << it->name() << " " << StateName(it->state())
          << (it->reason().empty() ? "" : ": " + it->reason()) << "\n";
    }
    const std::vector<LineField> fields = StudyFields(label, counts, eta);
    const std::string counts_text = FitToWidth(fields, std::string::npos);
    const std::string key = std::to_string(counts.queued) + "/" + std::to_string(counts.running) +
                            "/" + std::to_string(counts.completed) + "/" +
                            std::to_string(counts.failed) + "/" + std::to_string(counts.cancelled);
    if (mode == PrintMode::kLive) {
      const auto columns = static_cast<std::size_t>(TerminalColumns() - 1);
      out << "\r\033[K" << FitToWidth(fields, columns) << std::flush;
      line_shown = true;
    } else if (key != last_counts) {
      out << (mode == PrintMode::kJson ? CountsJson(selection, counts, eta).dump() : counts_text)
          << "\n"
          << std::flush;
    }
    last_counts = key;
    if (counts.Finished()) {
      if (line_shown) out << "\n" << std::flush;
      code = counts.failed + counts.cancelled > 0 ? kExitJobNotCompleted : kExitOk;
      break;
    }
    for (double slept = 0; slept < interval_seconds && !g_study_interrupted.load(); slept += 0.05) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    if (g_study_interrupted.load()) {
      if (line_shown) out << "\n" << std::flush;
      std::cerr << "dlmfd watch: interrupted; the jobs go on (dlmfd cancel --"
                << (selection.study.empty() ? "tag " + selection.tags.front()
                                            : "study " + selection.study)
                << " stops them)\n";
      code = kExitInterrupted;
      break;
    }
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  return code;
}

}  // namespace dlmfd::cli
