#include "job_proto.h"

#include <chrono>
#include <filesystem>
#include <fstream>

#include "slurm_commands.h"

namespace dlmfd::server {

v1::Job ToProto(const JobRecord& job) {
  v1::Job out;
  out.set_id(job.id);
  out.set_name(job.name);
  out.set_owner(job.owner);
  out.set_state(static_cast<v1::JobState>(job.state));
  out.set_reason(job.reason);
  out.set_priority(job.priority);
  for (const auto& tag : job.tags) out.add_tags(tag);
  out.set_sweep_id(job.sweep_id);
  out.set_created_time(job.created_time);
  out.set_started_time(job.started_time);
  out.set_finished_time(job.finished_time);
  out.set_step(job.step);
  out.set_time(job.time);
  out.set_end_time(job.end_time);
  out.set_attempts(job.attempts);
  out.set_results_dir(job.results_dir);
  for (const auto& o : job.overrides) out.add_overrides(o);
  out.set_client_request_id(job.client_request_id);
  out.set_last_seq(job.last_seq);
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
  // The slurm executor writes the id into the job directory, results_dir's parent.
  if (!job.results_dir.empty()) {
    std::ifstream slurm_id(std::filesystem::path(job.results_dir).parent_path() / kSlurmIdFile);
    std::string id;
    if (slurm_id >> id) out.set_slurm_job_id(id);
  }
  return out;
}

double NowSeconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace dlmfd::server
