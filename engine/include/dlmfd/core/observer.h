// The engine's only output port (design.md 2). Simulation calls these after a step; the cadence of
// OnParticles and OnSnapshot follows output.particles_every and output.fields_every (and both are
// called once for the initial state by Simulation::EmitInitial).
//
// A step notifies in two rounds: first every observer gets OnStep (then OnParticles and OnSnapshot
// when due), then every observer gets OnStepEnd. What must follow every record of the step on disk,
// whoever writes it (a checkpoint: resume cuts the records back to it), belongs in OnStepEnd.
// OnStopped is called once when Simulation::Run stops before the end time (its stop flag), never
// after a step that threw.
#pragma once

#include "dlmfd/core/state.h"

namespace dlmfd {

class Observer {
 public:
  virtual ~Observer() = default;
  virtual void OnStep(const FlowState& state, const StepReport& report) {}
  virtual void OnParticles(const FlowState& state) {}
  virtual void OnSnapshot(const FlowState& state) {}
  virtual void OnStepEnd(const FlowState& state) {}
  virtual void OnStopped(const FlowState& state) {}
};

}  // namespace dlmfd
