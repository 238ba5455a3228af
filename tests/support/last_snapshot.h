// An observer that keeps the velocity of the last snapshot, as a results writer gets it (with the
// tendency correction, the Stokes step's u^{n+1/4}; core/simulation.cc).
#pragma once

#include <vector>

#include "dlmfd/core/observer.h"

namespace dlmfd {

class LastSnapshot : public Observer {
 public:
  void OnSnapshot(const FlowState& state) override {
    u = state.u;
    v = state.v;
  }
  std::vector<double> u, v;
};

}  // namespace dlmfd
