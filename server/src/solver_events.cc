#include "solver_events.h"

#include <sstream>
#include <string>

namespace dlmfd::server {
namespace {

v1::WatchEvent LogLine(const std::string& level, const std::string& text) {
  v1::WatchEvent event;
  event.mutable_log()->set_level(level);
  event.mutable_log()->set_text(text);
  return event;
}

void Progress(const v1::Progress& src, PublishedSolverEvent& out) {
  out.origin.lane = "progress";
  out.origin.step = src.step();
  auto* p = out.event.mutable_progress();
  p->set_step(src.step());
  p->set_time(src.time());
  p->set_end_time(src.end_time());
  p->set_steps_per_second(src.steps_per_second());
  p->set_eta_seconds(src.eta_seconds());
  p->set_max_tra(src.max_tra());
  p->set_min_eig_a(src.min_eig_a());
  out.reports_progress = true;
  out.step = src.step();
  out.time = src.time();
  out.end_time = src.end_time();
}

void Snapshot(const v1::FieldSnapshot& src, PublishedSolverEvent& out) {
  out.origin.lane = "snapshot";
  out.origin.step = src.step();
  auto* s = out.event.mutable_snapshot();
  s->set_nx(src.nx());
  s->set_ny(src.ny());
  *s->mutable_values() = src.values();
  s->set_time(src.time());
  s->set_step(src.step());
  s->set_quantity(src.quantity());
  s->set_width(src.nx() * src.h());
  s->set_height(src.ny() * src.h());
}

}  // namespace

std::optional<PublishedSolverEvent> PublishedEventOf(const v1::SolverEvent& in) {
  PublishedSolverEvent out;
  // A checkpoint and the end replace the event with a log line, which carries no wall time.
  out.event.set_wall_time(in.wall_time());
  switch (in.event_case()) {
    case v1::SolverEvent::kStarted: {
      out.origin.lane = "progress";
      out.origin.step = in.started().step();
      auto* p = out.event.mutable_progress();
      p->set_step(in.started().step());
      p->set_time(in.started().time());
      p->set_end_time(in.started().end_time());
      out.reports_progress = true;
      out.step = in.started().step();
      out.time = in.started().time();
      out.end_time = in.started().end_time();
      break;
    }
    case v1::SolverEvent::kProgress:
      Progress(in.progress(), out);
      break;
    case v1::SolverEvent::kParticles:
      *out.event.mutable_particles() = in.particles();
      out.origin.lane = "particles";
      out.origin.step = in.particles().step();
      break;
    case v1::SolverEvent::kSnapshot:
      Snapshot(in.snapshot(), out);
      break;
    case v1::SolverEvent::kLog:
      *out.event.mutable_log() = in.log();
      break;
    case v1::SolverEvent::kCheckpointed: {
      out.origin.lane = "checkpoint";
      out.origin.step = in.checkpointed().step();
      std::ostringstream text;
      text << "checkpoint at step " << in.checkpointed().step()
           << ", t = " << in.checkpointed().time();
      out.event = LogLine("info", text.str());
      break;
    }
    case v1::SolverEvent::kFinished:
      out.event = LogLine("info", "solver finished: " + in.finished().status());
      out.reports_progress = true;
      out.step = in.finished().steps();
      out.time = in.finished().time();
      break;
    default:
      return std::nullopt;
  }
  return out;
}

}  // namespace dlmfd::server
