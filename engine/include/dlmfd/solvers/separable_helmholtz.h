// Fast direct solver for (a M_l + b K) x = f on the unknown nodes of a uniform grid (method notes
// 1, section 2): the operator is separable, K = K1x (x) Dy + Dx (x) K1y and M_l = h^2 Dx (x) Dy, so
// the generalized eigenvectors of (K1x, Dx) diagonalise it in x. By end kinds in x:
// Dirichlet-Dirichlet -> DST-I (FFTW RODFT00); Neumann-Neumann -> DCT-I (REDFT00);
// Dirichlet-Neumann / Neumann-Dirichlet -> quarter-wave transforms (RODFT01/10, REDFT01/10 pairs);
// periodic -> real DFT. Then one tridiagonal solve in y per mode (cyclic for periodic y), swept
// across modes so that the inner loop is contiguous. Plans and factorisations are made once, at
// construction; Solve allocates nothing. A solve runs on the calling thread's OpenMP team (at most
// the omp_get_max_threads() of construction), in phases shared by the team
// (separable_helmholtz.cc), and gives the same bits on any number of threads.
//
// a >= 0, b > 0. With a == 0 and no Dirichlet side (HasNullSpace) the zero mode is singular: f is
// projected to zero sum over the unknowns and x is returned with zero M_l-weighted mean.
#pragma once

#include <memory>

#include "dlmfd/core/grid.h"
#include "dlmfd/mesh/boundary_topology.h"

namespace dlmfd {

class SeparableHelmholtz {
 public:
  // workspaces: 1, or 2 for SolvePair (the transform buffers of two systems).
  SeparableHelmholtz(const Grid& grid, const BoundaryTopology& topo, double a, double b,
                     int workspaces = 2);
  ~SeparableHelmholtz();
  SeparableHelmholtz(const SeparableHelmholtz&) = delete;
  SeparableHelmholtz& operator=(const SeparableHelmholtz&) = delete;

  // On entry x holds the Dirichlet data on Dirichlet nodes (other values are ignored); on return
  // x solves (a M_l + b K) x = f at every unknown node, Dirichlet nodes unchanged, periodic
  // duplicates equal to their first node. f is read at unknown nodes only. f and x may not alias.
  // One call at a time per solver (the calls share its buffers).
  void Solve(const double* f, double* x) const;
  // The two components of a vector field as one batch: Solve(fu, u) and Solve(fv, v), the same
  // bits, in one OpenMP region whose phases share the two systems' rows and modes between all the
  // threads of the team (u and v side by side on two threads, each split further on more). Needs
  // workspaces = 2.
  void SolvePair(const double* fu, double* u, const double* fv, double* v) const;

  const Grid& grid() const;
  const BoundaryTopology& topology() const;
  double a() const;
  double b() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dlmfd
