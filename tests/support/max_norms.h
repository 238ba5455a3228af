// Max norms of nodal fields, as the tests compare them: max |f_k| and max |a_k - b_k|.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace dlmfd::testing {

inline double MaxAbs(const std::vector<double>& f) {
  double m = 0.0;
  for (double x : f) m = std::max(m, std::abs(x));
  return m;
}

// a and b of the same size.
inline double MaxAbsDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

}  // namespace dlmfd::testing
