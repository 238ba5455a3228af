#include "dlmfd/io/results_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/time_stepping.h"
#include "dlmfd/io/atomic_file.h"
#include "dlmfd/io/checkpoint.h"
#include "dlmfd/io/field_snapshot.h"
#include "dlmfd/scene/scene_file.h"

namespace fs = std::filesystem;

namespace dlmfd {
namespace {

// The step of "snap_NNNNNN.h5", or -1 for any other name.
long SnapshotStep(const std::string& name) {
  if (name.size() < 9 || name.compare(0, 5, "snap_") != 0 ||
      name.compare(name.size() - 3, 3, ".h5") != 0)
    return -1;
  const std::string digits = name.substr(5, name.size() - 8);
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::strtol(digits.c_str(), nullptr, 10);
}

// The angles at `step` from the records of particles.h5 (trapezoidal rule over the records): a
// checkpoint written before results format 2 has none.
std::vector<double> AnglesFromRecords(const std::string& path, long step, std::size_t np) {
  std::vector<double> angles(np, 0.0);
  std::error_code ec;
  if (!fs::exists(path, ec)) return angles;
  const ParticleHistory h = ReadParticleHistory(path);
  if (h.particles != np) return angles;
  for (std::size_t r = 1; r < h.records && h.step[r] <= step; ++r) {
    for (std::size_t k = 0; k < np; ++k) {
      angles[k] += 0.5 * (h.time[r] - h.time[r - 1]) *
                   (h.angular_velocity[r * np + k] + h.angular_velocity[(r - 1) * np + k]);
    }
  }
  return angles;
}

void MakeDirectory(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw Error("cannot create the results directory " + dir + ": " + ec.message());
}

}  // namespace

ResultsWriter::ResultsWriter(const std::string& dir, const Params& params, const Grid& grid)
    : dir_(dir),
      params_(params),
      scene_text_(WriteScene(params)),
      grid_(grid) {}

std::unique_ptr<ResultsWriter> ResultsWriter::Start(const std::string& dir, const Params& params,
                                                    const Grid& grid, const FlowState& initial) {
  std::unique_ptr<ResultsWriter> w(new ResultsWriter(dir, params, grid));
  MakeDirectory(dir);
  MakeDirectory(w->Path(kFields));
  for (const auto& entry : fs::directory_iterator(w->Path(kFields))) {
    if (SnapshotStep(entry.path().filename().string()) >= 0) fs::remove(entry.path());
  }
  for (const char* stale : {kXdmf, kCheckpoint, kParticles}) fs::remove(w->Path(stale));
  WriteTextAtomically(w->Path(kScene), w->scene_text_);
  w->diagnostics_ = std::make_unique<DiagnosticsWriter>(w->Path(kDiagnostics));
  w->particles_ = ParticleHistoryWriter::Create(w->Path(kParticles), initial, w->scene_text_);
  for (const ParticleState& q : initial.particles) w->angles_.push_back(q.angle);
  return w;
}

std::unique_ptr<ResultsWriter> ResultsWriter::Resume(const std::string& dir, const Params& params,
                                                     const Grid& grid, long checkpoint_step) {
  std::unique_ptr<ResultsWriter> w(new ResultsWriter(dir, params, grid));
  MakeDirectory(w->Path(kFields));
  std::vector<std::pair<long, std::string>> kept;
  for (const auto& entry : fs::directory_iterator(w->Path(kFields))) {
    const std::string name = entry.path().filename().string();
    const long step = SnapshotStep(name);
    if (step < 0) continue;
    if (step > checkpoint_step) {
      fs::remove(entry.path());
    } else {
      kept.emplace_back(step, name);
    }
  }
  std::sort(kept.begin(), kept.end());
  for (const auto& [step, name] : kept) {
    const FieldSnapshot snapshot = ReadFieldSnapshot(w->Path(kFields) + "/" + name);
    w->snapshots_.push_back({std::string(kFields) + "/" + name, snapshot.time,
                             snapshot.particles.Count(), !snapshot.particles.angle.empty(),
                             !snapshot.particles.semi_axes.empty()});
  }
  WriteFieldsXdmf(w->Path(kXdmf), grid, w->snapshots_, !params.fluid.IsNewtonian());
  if (fs::exists(w->Path(kDiagnostics))) {
    w->diagnostics_ = std::make_unique<DiagnosticsWriter>(w->Path(kDiagnostics), checkpoint_step);
  } else {
    w->diagnostics_ = std::make_unique<DiagnosticsWriter>(w->Path(kDiagnostics));
  }
  const Checkpoint checkpoint = ReadCheckpoint(w->Path(kCheckpoint));
  const std::size_t np = checkpoint.state.particles.size();
  w->angles_ = checkpoint.particle_angles.size() == np
                   ? checkpoint.particle_angles
                   : AnglesFromRecords(w->Path(kParticles), checkpoint_step, np);
  w->particles_ = ParticleHistoryWriter::Resume(w->Path(kParticles), checkpoint_step);
  return w;
}

void ResultsWriter::TakeAngles(const FlowState& state) {
  if (state.particles.size() != angles_.size()) return;
  for (std::size_t k = 0; k < angles_.size(); ++k) angles_[k] = state.particles[k].angle;
}

void ResultsWriter::OnStep(const FlowState& state, const StepReport& report) {
  TakeAngles(state);
  diagnostics_->Append(report);
  last_report_ = report;
  if (OutputDue(state.step, params_.time.dt, params_.output.checkpoint_every)) {
    checkpoint_due_ = true;
  }
}

void ResultsWriter::OnParticles(const FlowState& state) {
  if (particles_) particles_->Append(state, angles_);
}

void ResultsWriter::OnSnapshot(const FlowState& state) {
  if (params_.output.fields_every <= 0.0)
    return;  // no snapshots asked for (not even the initial one)
  const std::string relative = std::string(kFields) + "/" + SnapshotFileName(state.step);
  WriteFieldSnapshot(Path(relative), grid_, state, SnapshotExtras{scene_text_, angles_});
  snapshots_.push_back({relative, state.time, state.particles.size(),
                        state.particles.size() == angles_.size(), true});
  WriteFieldsXdmf(Path(kXdmf), grid_, snapshots_, !state.a11.empty());
}

void ResultsWriter::OnStepEnd(const FlowState& state) {
  if (!checkpoint_due_) return;
  checkpoint_due_ = false;
  SaveCheckpoint(state);
}

void ResultsWriter::OnStopped(const FlowState& state) { SaveCheckpoint(state); }

void ResultsWriter::SaveCheckpoint(const FlowState& state) {
  WriteCheckpoint(Path(kCheckpoint), state, scene_text_, angles_);
  if (on_checkpoint_) on_checkpoint_(state.step, state.time, kCheckpoint);
}

void ResultsWriter::Finish() {
  diagnostics_.reset();
  particles_.reset();
}

}  // namespace dlmfd
