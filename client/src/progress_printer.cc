// ProgressPrinter: the live line, the plain log and NDJSON.
#include "progress_printer.h"

#include <cstdio>
#include <iostream>

#include "exit_codes.h"
#include "job_text.h"
#include "rpc_status.h"
#include "terminal_width.h"

namespace dlmfd::cli {

ProgressPrinter::ProgressPrinter(std::string job_id, PrintMode mode, std::ostream& out)
    : job_id_(std::move(job_id)),
      mode_(mode),
      out_(out) {}

std::vector<LineField> ProgressPrinter::StatusFields() const {
  char state[64], step[48], time[64], rate[48];
  std::snprintf(state, sizeof(state), "%s %-9s", job_id_.c_str(), state_.c_str());
  std::snprintf(step, sizeof(step), "step %lld", static_cast<long long>(step_));
  std::snprintf(time, sizeof(time), "t %.4g/%.4g", time_, end_time_);
  std::snprintf(rate, sizeof(rate), "%.1f steps/s", steps_per_second_);
  std::string particles;
  if (particles_ >= 0)
    particles = std::to_string(particles_) + (particles_ == 1 ? " particle" : " particles");
  // What matters most survives a narrow terminal: the state, the time, the ETA.
  return {
      {state, 10},   {step, 4}, {time, 8}, {rate, 3}, {"ETA " + FormatDuration(eta_seconds_), 7},
      {particles, 2}};
}

std::string ProgressPrinter::StatusLine() const {
  return FitToWidth(StatusFields(), std::string::npos);
}

void ProgressPrinter::PrintAbove(const std::string& line) {
  if (mode_ == PrintMode::kLive && line_shown_) out_ << "\r\033[K";
  out_ << line << "\n";
  line_shown_ = false;
  if (mode_ == PrintMode::kLive) Redraw();
  out_.flush();
}

void ProgressPrinter::Redraw() {
  const std::size_t columns = static_cast<std::size_t>(TerminalColumns() - 1);
  out_ << "\r\033[K" << FitToWidth(StatusFields(), columns) << std::flush;
  line_shown_ = true;
  last_redraw_ = std::chrono::steady_clock::now();
}

bool ProgressPrinter::OnEvent(const v1::WatchEvent& event) {
  if (mode_ == PrintMode::kJson) {
    out_ << ToJsonLine(event) << "\n" << std::flush;
    return true;
  }
  const auto now = std::chrono::steady_clock::now();
  if (event.has_state()) {
    const v1::StateChange& s = event.state();
    const bool repeated = state_ == StateName(s.state());  // a reconnect replays the current state
    state_ = StateName(s.state());
    if (s.has_job()) {
      step_ = s.job().step();
      time_ = s.job().time();
      end_time_ = s.job().end_time();
    }
    if (!repeated)
      PrintAbove(job_id_ + " " + state_ + (s.reason().empty() ? "" : ": " + s.reason()));
  } else if (event.has_progress()) {
    const v1::JobProgress& p = event.progress();
    step_ = p.step();
    time_ = p.time();
    end_time_ = p.end_time();
    steps_per_second_ = p.steps_per_second();
    eta_seconds_ = p.eta_seconds();
    if (mode_ == PrintMode::kLive) {
      if (now - last_redraw_ > std::chrono::milliseconds(100)) Redraw();
    } else if (now - last_plain_ > std::chrono::seconds(10)) {
      out_ << StatusLine() << "\n" << std::flush;
      last_plain_ = now;
    }
  } else if (event.has_particles()) {
    particles_ = event.particles().particles_size();
  } else if (event.has_log()) {
    const std::string& level = event.log().level();
    if (level == "warn" || level == "error")
      PrintAbove(job_id_ + " " + level + ": " + event.log().text());
  } else if (event.has_gap()) {
    PrintAbove(job_id_ + " missed events " + std::to_string(event.gap().from_seq()) + "-" +
               std::to_string(event.gap().to_seq()) + " (" + event.gap().reason() + ")");
  }
  return true;
}

void ProgressPrinter::OnReconnect(const grpc::Status& status, double delay) {
  char text[64];
  std::snprintf(text, sizeof(text), "; reconnecting in %.2g s", delay);
  const std::string line =
      job_id_ + " stream broken (" + StatusCodeName(status.error_code()) + ")" + text;
  if (mode_ == PrintMode::kJson) {
    std::cerr << line << "\n";
  } else {
    PrintAbove(line);
  }
}

int ProgressPrinter::Finish(const WatchOutcome& outcome, const std::string& command) {
  if (mode_ == PrintMode::kLive && line_shown_) {
    out_ << "\n" << std::flush;  // keep the last live line
    line_shown_ = false;
  }
  if (outcome.interrupted) {
    std::cerr << "dlmfd " << command << ": interrupted; the job goes on (dlmfd cancel " << job_id_
              << " stops it)\n";
    return kExitInterrupted;
  }
  if (!outcome.status.ok()) return ReportRpcError(command, outcome.status);
  if (!outcome.finished) return kExitOk;
  const v1::Job& job = outcome.job;
  if (mode_ != PrintMode::kJson) {
    char text[160];
    std::snprintf(text, sizeof(text), "%s %s: %lld steps, t = %.6g", job_id_.c_str(),
                  StateName(job.state()).c_str(), static_cast<long long>(job.step()), job.time());
    out_ << text << (job.reason().empty() ? "" : " (" + job.reason() + ")") << "\n" << std::flush;
  }
  return job.state() == v1::COMPLETED ? kExitOk : kExitJobNotCompleted;
}

}  // namespace dlmfd::cli
