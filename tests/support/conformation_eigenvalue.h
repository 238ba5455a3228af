// The smallest eigenvalue of the conformation tensor A over every node of a flow state (tests that
// check A stays positive definite, inside the bodies' bands included).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "dlmfd/core/state.h"

namespace dlmfd::testing {

inline double SmallestConformationEigenvalue(const FlowState& s) {
  double m = 1e300;
  for (std::size_t k = 0; k < s.a11.size(); ++k) {
    const double mean = 0.5 * (s.a11[k] + s.a22[k]), half = 0.5 * (s.a11[k] - s.a22[k]);
    m = std::min(m, mean - std::sqrt(half * half + s.a12[k] * s.a12[k]));
  }
  return m;
}

}  // namespace dlmfd::testing
