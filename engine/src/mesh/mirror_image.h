// The mirror image x -> -x of node arrays, through which the forms of the NW-SE triangulation are
// the SW-NE mesh's (domain.diagonals = "both", core/params.h).
//
// Mirroring the domain about its vertical mid-line maps the mesh of SW-NE diagonals onto the mesh
// of NW-SE diagonals, node onto node (i -> nx - i), and the 2h pressure mesh likewise (nx is even).
// So for a form b on the SW-NE mesh, the same form on the NW-SE mesh is b evaluated on the mirrored
// arguments: a scalar f becomes (S f)(i, j) = f(nx - i, j); a velocity (u, v) becomes (-S u, S v);
// div, grad . grad and V . grad are unchanged by the mirror. On a periodic x axis the image of node
// i is (-i) mod nx (the domain's periodic images are mirrored about x = 0), and the duplicate
// column nx stays equal to column 0. Mirroring about x alone is enough: the mirror in y maps the
// SW-NE mesh onto the same NW-SE mesh, so the mean of the two meshes' forms is symmetric under
// both.
#pragma once

#include <cstddef>
#include <vector>

#include "dlmfd/core/grid.h"

namespace dlmfd::kernels {

// Scratch node arrays of the calling thread for the mirrored pass (two slots). Each grows once and
// is then reused, so the time loop allocates nothing. A slot is its caller's until that returns: a
// form that holds one calls no other form of "both".
inline double* MirrorScratch(int slot, std::size_t size) {
  thread_local std::vector<double> buffers[2];
  if (buffers[slot].size() < size) buffers[slot].resize(size);
  return buffers[slot].data();
}

// out = sign S in (in and out distinct node arrays of the grid).
inline void MirrorInX(const Grid& grid, bool periodic_x, double sign, const double* in,
                      double* out) {
  const int nx = grid.nx, row = grid.nx + 1;
#pragma omp parallel for schedule(static) if (grid.NodeCount() > 16384)
  for (int j = 0; j <= grid.ny; ++j) {
    const double* a = in + std::size_t(j) * row;
    double* b = out + std::size_t(j) * row;
    if (periodic_x) {
      b[0] = sign * a[0];
      for (int i = 1; i < nx; ++i) b[i] = sign * a[nx - i];
      b[nx] = b[0];
    } else {
      for (int i = 0; i <= nx; ++i) b[i] = sign * a[nx - i];
    }
  }
}

// out = (out + sign S in) / 2, in place: the mean of a form on the two triangulations, given the
// SW-NE form's value on the mirrored arguments (in and out distinct).
inline void AverageWithMirrorImage(const Grid& grid, bool periodic_x, double sign, const double* in,
                                   double* out) {
  const int nx = grid.nx, row = grid.nx + 1;
  const double half = 0.5 * sign;
#pragma omp parallel for schedule(static) if (grid.NodeCount() > 16384)
  for (int j = 0; j <= grid.ny; ++j) {
    const double* a = in + std::size_t(j) * row;
    double* b = out + std::size_t(j) * row;
    if (periodic_x) {
      b[0] = 0.5 * b[0] + half * a[0];
      for (int i = 1; i < nx; ++i) b[i] = 0.5 * b[i] + half * a[nx - i];
      b[nx] = b[0];
    } else {
      for (int i = 0; i <= nx; ++i) b[i] = 0.5 * b[i] + half * a[nx - i];
    }
  }
}

}  // namespace dlmfd::kernels
