#include "job_proto.h"

#include <algorithm>
#include <chrono>

#include "slurm_states.h"

namespace dlmfd::server {

v1::Job ToProto(const JobRecord& job, double now) {
  v1::Job out;
  out.set_id(job.id);
  out.set_name(job.name);
  out.set_owner(job.owner);
  out.set_state(static_cast<v1::JobState>(ShownState(job)));
  out.set_reason(job.reason);
  // Slurm's word on a job in its hands: a wait (PENDING, ...) or another state than RUNNING
  // (SUSPENDED, COMPLETING) is the reason, unless the daemon has one ("cancel requested").
  if (job.state == JobState::kRunning && job.reason.empty() && !job.slurm_state.empty() &&
      job.slurm_state != "RUNNING") {
    out.set_reason(MapSlurmState(job.slurm_state, job.slurm_reason).reason);
  }
  out.set_priority(job.priority);
  for (const auto& tag : job.tags) out.add_tags(tag);
  out.set_study_id(job.study_id);
  out.set_created_time(job.created_time);
  out.set_started_time(job.slurm_waiting && job.state == JobState::kRunning ? 0.0
                                                                            : job.started_time);
  out.set_finished_time(job.finished_time);
  out.set_step(job.step);
  out.set_time(job.time);
  out.set_end_time(job.end_time);
  out.set_attempts(job.attempts);
  out.set_results_dir(job.results_dir);
  for (const auto& o : job.overrides) out.add_overrides(o);
  out.set_client_request_id(job.client_request_id);
  out.set_last_seq(job.last_seq);
  out.set_held(job.held);
  out.set_disk_bytes(job.disk_bytes);
  for (const AccuracyWarning& w : job.warnings) {
    v1::AccuracyWarning* o = out.add_warnings();
    o->set_setting(w.setting);
    o->set_value(w.value);
    o->set_allowed(w.allowed);
    o->set_key(w.key);
    o->set_current(w.current);
    o->set_suggested(w.suggested);
    o->set_source(w.source);
  }
  for (const ResolvedChoice& c : job.numerics) {
    v1::NumericsChoice* o = out.add_numerics();
    o->set_key(c.key);
    o->set_value(c.value);
    o->set_rule(c.rule);
    for (const auto& [name, value] : c.numbers) {
      v1::NamedNumber* n = o->add_numbers();
      n->set_name(name);
      n->set_value(value);
    }
  }
  for (const auto& [key, value] : job.labels) (*out.mutable_labels())[key] = value;
  for (const ParameterValue& p : job.parameters) {
    v1::ParameterValue* o = out.add_parameters();
    o->set_key(p.key);
    o->set_text(p.text);
    o->set_type(p.type);
    o->set_number(p.number);
  }
  out.set_attempt(job.attempt);
  for (const AttemptRecord& a : job.previous_attempts) {
    v1::AttemptRecord* o = out.add_previous_attempts();
    o->set_attempt(a.attempt);
    o->set_state(static_cast<v1::JobState>(a.state));
    o->set_reason(a.reason);
    o->set_started_time(a.started_time);
    o->set_finished_time(a.finished_time);
    o->set_step(a.step);
    o->set_time(a.time);
    for (const auto& text : a.overrides) o->add_overrides(text);
  }
  out.set_slurm_job_id(job.slurm_job_id);
  out.set_slurm_state(job.slurm_state);
  out.set_slurm_reason(job.slurm_reason);
  out.set_time_limit_seconds(job.time_limit_seconds);
  for (const auto& id : job.after) out.add_after(id);
  if (job.exit_code >= 0) out.set_exit_code(job.exit_code);
  out.set_exit_signal(job.exit_signal);
  out.set_cpu_seconds(job.cpu_seconds);
  out.set_peak_memory_bytes(job.peak_memory_bytes);
  // Counted from the start shown: a job Slurm holds waiting has none yet, so no elapsed time.
  if (out.started_time() > 0) {
    const double end = job.finished_time > 0             ? job.finished_time
                       : job.state == JobState::kRunning ? now
                                                         : job.started_time;
    out.set_elapsed_seconds(std::max(0.0, end - job.started_time));
  }
  return out;
}

v1::Study ToProto(const StudyRecord& study, const StudyStats& stats) {
  v1::Study out;
  out.set_id(study.id);
  out.set_name(study.name);
  out.set_owner(study.owner);
  for (const auto& tag : study.tags) out.add_tags(tag);
  for (const auto& [key, value] : study.labels) (*out.mutable_labels())[key] = value;
  for (const StoredAxis& a : study.axes) {
    v1::StudyAxis* o = out.add_axes();
    o->set_key(a.key);
    o->set_zip(a.zip);
    for (const auto& value : a.values) o->add_values(value);
    if (a.is_range) {
      o->mutable_range()->set_start(a.start);
      o->mutable_range()->set_stop(a.stop);
      o->mutable_range()->set_count(a.count);
      o->mutable_range()->set_logarithmic(a.logarithmic);
    }
  }
  for (const auto& text : study.overrides) out.add_overrides(text);
  out.set_max_running(study.max_running);
  out.set_created_time(study.created_time);
  out.set_jobs(stats.jobs);
  out.set_queued(stats.count[static_cast<size_t>(JobState::kQueued)]);
  out.set_running(stats.count[static_cast<size_t>(JobState::kRunning)]);
  out.set_completed(stats.count[static_cast<size_t>(JobState::kCompleted)]);
  out.set_failed(stats.count[static_cast<size_t>(JobState::kFailed)]);
  out.set_cancelled(stats.count[static_cast<size_t>(JobState::kCancelled)]);
  out.set_progress(stats.jobs > 0 ? stats.progress_sum / stats.jobs : 0.0);
  out.set_first_started_time(stats.first_started_time);
  out.set_last_finished_time(stats.last_finished_time);
  return out;
}

}  // namespace dlmfd::server
