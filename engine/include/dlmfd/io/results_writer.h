// The results directory of one run (design.md 3.2), written by an Observer of Simulation:
//   scene.toml (the scene as run, every default filled in), diagnostics.csv (OnStep),
//   particles.h5 (OnParticles; np = 0 when the scene has none), fields/snap_NNNNNN.h5 and
//   fields.xmf (OnSnapshot), checkpoint.h5 (OnStepEnd, every output.checkpoint_every of simulated
//   time, and OnStopped: a run stopped by a signal). summary.json is not written here: it is the
//   solver's, written when the run has ended (solver/include/dlmfd/solver/run_summary.h).
//
// Each particle's orientation angle theta is the engine's (ParticleState::angle, integrated by the
// corrector (38) with the trapezoidal rule theta_{n+1} = theta_n + dt (omega_n + omega_{n+1})/2
// from the scene's initial angle; particles/particle_step.h): an ellipse's dynamics depend on it.
// It is written with every particle record, snapshot and checkpoint (results format 2,
// results_format.h); a resumed run reads it back from the checkpoint.
//
// Checkpoints are written by OnStepEnd, after every observer has seen the step, so that every
// record of a step at or before the checkpoint is on disk before the checkpoint exists. Resume()
// cuts particles.h5 and diagnostics.csv back to the records at or before the checkpoint step, drops
// the snapshots after it and rebuilds fields.xmf: the resumed run then appends exactly what an
// uninterrupted run would have written.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/observer.h"
#include "dlmfd/core/params.h"
#include "dlmfd/io/diagnostics_csv.h"
#include "dlmfd/io/fields_xdmf.h"
#include "dlmfd/io/particle_history.h"

namespace dlmfd {

class ResultsWriter : public Observer {
 public:
  // A fresh run: creates DIR and DIR/fields, removes the results of an earlier run there
  // (snapshots, fields.xmf, checkpoint.h5, particles.h5), writes scene.toml.
  static std::unique_ptr<ResultsWriter> Start(const std::string& dir, const Params& params,
                                              const Grid& grid, const FlowState& initial);
  // Goes on from the checkpoint at `checkpoint_step` in DIR (see the header comment).
  static std::unique_ptr<ResultsWriter> Resume(const std::string& dir, const Params& params,
                                               const Grid& grid, long checkpoint_step);

  void OnStep(const FlowState& state, const StepReport& report) override;
  void OnParticles(const FlowState& state) override;
  void OnSnapshot(const FlowState& state) override;

  // Writes the checkpoint when one falls due at this step.
  void OnStepEnd(const FlowState& state) override;
  // Writes the checkpoint of the step reached (a cancelled run resumes from it).
  void OnStopped(const FlowState& state) override;
  // Closes diagnostics.csv and particles.h5 (the run has ended; nothing is written after this).
  void Finish();

  // Called with (step, time, file relative to DIR) after each checkpoint.
  void SetCheckpointCallback(std::function<void(long, double, const std::string&)> callback) {
    on_checkpoint_ = std::move(callback);
  }
  const std::string& dir() const { return dir_; }
  // The report of the last step seen (its columns go into summary.json).
  const StepReport& last_report() const { return last_report_; }
  // The particles' rotation angles at the last step seen.
  const std::vector<double>& particle_angles() const { return angles_; }

  static constexpr const char* kScene = "scene.toml";
  static constexpr const char* kParticles = "particles.h5";
  static constexpr const char* kDiagnostics = "diagnostics.csv";
  static constexpr const char* kCheckpoint = "checkpoint.h5";
  static constexpr const char* kXdmf = "fields.xmf";
  static constexpr const char* kFields = "fields";

 private:
  ResultsWriter(const std::string& dir, const Params& params, const Grid& grid);
  std::string Path(const std::string& name) const { return dir_ + "/" + name; }
  void SaveCheckpoint(const FlowState& state);
  void TakeAngles(const FlowState& state);

  std::string dir_;
  Params params_;
  std::string scene_text_;
  Grid grid_;
  std::unique_ptr<DiagnosticsWriter> diagnostics_;
  std::unique_ptr<ParticleHistoryWriter> particles_;
  std::vector<XdmfEntry> snapshots_;
  std::vector<double> angles_;  // per particle, radians
  StepReport last_report_;
  bool checkpoint_due_ = false;
  std::function<void(long, double, const std::string&)> on_checkpoint_;
};

}  // namespace dlmfd
