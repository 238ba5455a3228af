#include "event_stream.h"

#include <sys/resource.h>

#include <cmath>

#include "dlmfd/core/time_stepping.h"
#include "dlmfd/io/field_snapshot.h"

namespace dlmfd::solver {

EventStream::EventStream(int fd) {
  if (fd >= 0) out_ = std::make_unique<EventFileWriter>(fd);
}

EventStream::~EventStream() = default;

void EventStream::Send(v1::SolverEvent& event) {
  if (!out_) return;
  event.set_seq(++seq_);
  event.set_wall_time(
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count());
  if (!out_->Write(event)) out_.reset();
}

void EventStream::Log(const std::string& level, const std::string& text) {
  v1::SolverEvent e;
  e.mutable_log()->set_level(level);
  e.mutable_log()->set_text(text);
  Send(e);
}

void EventStream::Finished(const std::string& status, const std::string& reason, long steps,
                           double time, int exit_code) {
  v1::SolverEvent e;
  v1::Finished* f = e.mutable_finished();
  f->set_status(status);
  f->set_reason(reason);
  f->set_steps(steps);
  f->set_time(time);
  f->set_exit_code(exit_code);
  rusage self{};
  if (getrusage(RUSAGE_SELF, &self) == 0) {
    f->set_cpu_seconds(static_cast<double>(self.ru_utime.tv_sec + self.ru_stime.tv_sec) +
                       1e-6 * static_cast<double>(self.ru_utime.tv_usec + self.ru_stime.tv_usec));
    f->set_peak_memory_bytes(static_cast<int64_t>(self.ru_maxrss) * 1024);  // ru_maxrss: KiB
  }
  Send(e);
}

EventObserver::EventObserver(EventStream* stream, const Params& params, const Grid& grid)
    : stream_(stream),
      params_(params),
      grid_(grid),
      total_steps_(StepCount(params.time)) {
  v1::ParticleStates* ps = particles_event_.mutable_particles();
  for (std::size_t i = 0; i < params.particles.size(); ++i) ps->add_particles();
  snapshot_event_.mutable_snapshot()->mutable_values()->Resize(static_cast<int>(grid.NodeCount()),
                                                               0.0f);
  progress_event_.mutable_progress();
  Begin(0);
}

void EventObserver::Begin(long first_step) {
  first_step_ = first_step;
  start_ = std::chrono::steady_clock::now();
  last_progress_ = start_;
}

void EventObserver::OnStep(const FlowState& state, const StepReport& report) {
  if (!stream_->enabled()) return;
  const auto now = std::chrono::steady_clock::now();
  const bool last = state.step >= total_steps_;
  if (!last && now - last_progress_ < std::chrono::milliseconds(500)) return;
  last_progress_ = now;
  const double wall = std::chrono::duration<double>(now - start_).count();
  const double rate = wall > 0.0 ? static_cast<double>(state.step - first_step_) / wall : 0.0;
  v1::Progress* p = progress_event_.mutable_progress();
  p->set_step(state.step);
  p->set_time(state.time);
  p->set_end_time(params_.time.end);
  p->set_wall_seconds(wall);
  p->set_steps_per_second(rate);
  p->set_eta_seconds(rate > 0.0 ? static_cast<double>(total_steps_ - state.step) / rate : 0.0);
  p->set_max_tra(report.Get("max_trA", 0.0));
  p->set_min_eig_a(report.Get("min_eig_A", 0.0));
  stream_->Send(progress_event_);
}

void EventObserver::OnParticles(const FlowState& state) {
  if (!stream_->enabled() || state.particles.empty()) return;
  v1::ParticleStates* ps = particles_event_.mutable_particles();
  ps->set_step(state.step);
  ps->set_time(state.time);
  for (std::size_t i = 0; i < state.particles.size() && static_cast<int>(i) < ps->particles_size();
       ++i) {
    const ParticleState& q = state.particles[i];
    v1::Particle* out = ps->mutable_particles(static_cast<int>(i));
    out->set_id(q.id);
    out->set_x(q.position.x());
    out->set_y(q.position.y());
    out->set_u(q.velocity.x());
    out->set_v(q.velocity.y());
    out->set_omega(q.angular_velocity);
    out->set_fx(q.force.x());
    out->set_fy(q.force.y());
    out->set_torque(q.torque);
    out->set_radius(q.radius);
    out->set_angle(q.angle);
    const bool disk = q.shape == ShapeKind::kDisk;
    out->set_shape(disk ? "disk" : "ellipse");
    out->set_semi_axis_a(disk ? q.radius : q.semi_axes.x());
    out->set_semi_axis_b(disk ? q.radius : q.semi_axes.y());
  }
  stream_->Send(particles_event_);
}

void EventObserver::OnSnapshot(const FlowState& state) {
  if (!stream_->enabled() || params_.output.fields_every <= 0.0) return;
  v1::FieldSnapshot* s = snapshot_event_.mutable_snapshot();
  s->set_step(state.step);
  s->set_time(state.time);
  s->set_nx(grid_.nx);
  s->set_ny(grid_.ny);
  s->set_h(grid_.h);
  s->set_file(std::string("fields/") + SnapshotFileName(state.step));
  float* values = s->mutable_values()->mutable_data();
  const bool newtonian = state.a11.empty();
  s->set_quantity(newtonian ? "speed" : "trA");
  for (std::size_t k = 0; k < grid_.NodeCount(); ++k) {
    values[k] = newtonian ? static_cast<float>(std::hypot(state.u[k], state.v[k]))
                          : static_cast<float>(state.a11[k] + state.a22[k]);
  }
  stream_->Send(snapshot_event_);
}

}  // namespace dlmfd::solver
