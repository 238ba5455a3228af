// Mirror images of nodal velocity fields, for the tests of domain.diagonals = "both": the image of
// a field under x -> W - x (mirror_x) or y -> H - y, whose normal component changes sign, and the
// mismatch between a run from a mirrored start and the mirror image of a run.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "dlmfd/core/grid.h"

namespace dlmfd::testing {

// The node that node (i, j) maps to.
inline std::size_t MirrorNode(const Grid& g, bool mirror_x, int i, int j) {
  return mirror_x ? g.Index(g.nx - i, j) : g.Index(i, g.ny - j);
}

// (um, vm) = the mirror image of (u, v).
inline void MirrorVelocity(const Grid& g, bool mirror_x, const std::vector<double>& u,
                           const std::vector<double>& v, std::vector<double>& um,
                           std::vector<double>& vm) {
  um.assign(u.size(), 0.0);
  vm.assign(v.size(), 0.0);
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const std::size_t k = g.Index(i, j), m = MirrorNode(g, mirror_x, i, j);
      um[m] = (mirror_x ? -1.0 : 1.0) * u[k];
      vm[m] = (mirror_x ? 1.0 : -1.0) * v[k];
    }
  }
}

// max |(um, vm) - image of (u, v)| / max |(u, v)|.
inline double MirrorMismatch(const Grid& g, bool mirror_x, const std::vector<double>& u,
                             const std::vector<double>& v, const std::vector<double>& um,
                             const std::vector<double>& vm) {
  std::vector<double> iu, iv;
  MirrorVelocity(g, mirror_x, u, v, iu, iv);
  double mismatch = 0.0, size = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    mismatch = std::max({mismatch, std::abs(um[k] - iu[k]), std::abs(vm[k] - iv[k])});
    size = std::max({size, std::abs(u[k]), std::abs(v[k])});
  }
  return mismatch / size;
}

}  // namespace dlmfd::testing
