// One run of the Marchuk-Yanenko scheme (33)-(38) of the paper, section 4:
//   SolveStokes (33) -> AdvectVelocity (34) -> UpdateConformation (35) -> particles (36)-(38).
// A step models no more than the scene needs: no conformation step for a Newtonian liquid, no
// multiplier step without particles. Time t_n = n dt exactly (no accumulation); the run ends after
// round(end / dt) steps.
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/observer.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"

namespace dlmfd {

class Simulation {
 public:
  // Throws InvalidParameter for a configuration the engine cannot run.
  explicit Simulation(const Params& params);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  void AddObserver(Observer* observer);
  // Notifies OnParticles and OnSnapshot for the current state (call once before the first Step of a
  // fresh run, not after Restore).
  void EmitInitial();
  // Advances one time step and notifies the observers (OnStep, OnParticles and OnSnapshot when due,
  // then OnStepEnd). Throws RunFailure (and subclasses).
  void Step();
  // The time loop: steps until the end time or until *stop becomes true (checked between steps);
  // a run stopped early notifies OnStopped. What a step throws propagates.
  void Run(const std::atomic<bool>* stop = nullptr);
  bool Done() const;
  long TotalSteps() const;

  // Replaces the state by one read from a checkpoint (same scene).
  void Restore(const FlowState& state);

  const Params& params() const;
  const Grid& grid() const;           // velocity / A grid
  const Grid& pressure_grid() const;  // 2h grid
  const FlowState& state() const;
  FlowState& mutable_state();  // for tests that set initial fields

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dlmfd
