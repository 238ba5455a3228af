// The engine's only output port (design.md 2). Simulation calls these after a step; the cadence of
// OnParticles and OnSnapshot follows output.particles_every and output.fields_every (and both are
// called once for the initial state by Simulation::EmitInitial).
#pragma once

#include "dlmfd/core/state.h"

namespace dlmfd {

class Observer {
 public:
  virtual ~Observer() = default;
  virtual void OnStep(const FlowState& state, const StepReport& report) {}
  virtual void OnParticles(const FlowState& state) {}
  virtual void OnSnapshot(const FlowState& state) {}
};

}  // namespace dlmfd
