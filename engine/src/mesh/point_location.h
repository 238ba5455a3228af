// Point location on the uniform SW-NE mesh: which h-square and which of its two triangles hold a
// point, and the P1 interpolation weights there (method notes 2, section 1.1). Small inline kernels
// beside grid_kernels.h, for everything that evaluates a fluid field at points that are not nodes
// (the coupling operator E of the DLM step (37)).
//
// Square (i, j) = floor((x - x0) / h, (y - y0) / h) with local coordinates (xi, eta) in [0, 1]^2;
// its diagonal runs from a = (i, j) to c = (i+1, j+1). For xi >= eta the point lies in
// T1 = (a, b, c), weights (1 - xi, xi - eta, eta); otherwise in T2 = (a, c, d), weights
// (1 - eta, xi, eta - xi) (b = (i+1, j), d = (i, j+1)). On a periodic axis the square index wraps
// and the node line after the last square is the first one; on a non-periodic axis a point on the
// far side (t = 0 in square n) belongs to the last square at t = 1, and a point beyond a side is
// not located (the caller says which side it crossed).
#pragma once

#include <cmath>

#include "dlmfd/core/grid.h"
#include "grid_kernels.h"

namespace dlmfd::kernels {

// The square of one axis that holds coordinate s (in units of h from the origin): true with its
// index *cell and local coordinate *local; false when s lies beyond a non-periodic end, with *cell
// the unwrapped index (< 0 below the low end, >= cells above the high end).
inline bool LocateOnAxis(double s, int cells, bool periodic, int* cell, double* local) {
  int c = static_cast<int>(std::floor(s));
  double t = s - c;
  if (periodic) {
    c = Wrap(c, cells);
  } else if (c == cells && t == 0.0) {
    c = cells - 1;
    t = 1.0;
  } else if (c < 0 || c >= cells) {
    *cell = c;
    return false;
  }
  *cell = c;
  *local = t;
  return true;
}

// The node line after square c of an axis: c + 1, or 0 after the last square of a periodic axis.
inline int NextLine(int c, int cells, bool periodic) {
  return (periodic && c + 1 == cells) ? 0 : c + 1;
}

// The P1 stencil of a point: the three vertices (i[q], j[q]) of the triangle that holds it and
// their weights (its barycentric coordinates there).
struct P1Stencil {
  int i[3];
  int j[3];
  double weight[3];
};

// The stencil at local coordinates (xi, eta) of square (i0, j0), with (i1, j1) its next node lines.
inline P1Stencil P1StencilInSquare(int i0, int j0, int i1, int j1, double xi, double eta) {
  if (xi >= eta) return P1Stencil{{i0, i1, i1}, {j0, j0, j1}, {1.0 - xi, xi - eta, eta}};
  return P1Stencil{{i0, i1, i0}, {j0, j1, j1}, {1.0 - eta, xi, eta - xi}};
}

// Locates point (x, y) on the grid: true with its stencil; false when it lies beyond a
// non-periodic side, with *side that side (as Side: 0 left, 1 right, 2 bottom, 3 top; the x axis
// is checked first).
inline bool LocatePoint(const Grid& grid, bool periodic_x, bool periodic_y, double x, double y,
                        P1Stencil* stencil, int* side) {
  int i0 = 0, j0 = 0;
  double xi = 0.0, eta = 0.0;
  if (!LocateOnAxis((x - grid.x0) / grid.h, grid.nx, periodic_x, &i0, &xi)) {
    *side = i0 < 0 ? 0 : 1;
    return false;
  }
  if (!LocateOnAxis((y - grid.y0) / grid.h, grid.ny, periodic_y, &j0, &eta)) {
    *side = j0 < 0 ? 2 : 3;
    return false;
  }
  *stencil = P1StencilInSquare(i0, j0, NextLine(i0, grid.nx, periodic_x),
                               NextLine(j0, grid.ny, periodic_y), xi, eta);
  return true;
}

// Periodic duplicates follow their first node: the last node column (row) of a periodic pair is
// set to the first (the corner of a doubly periodic grid to node (0, 0)).
inline void CopyPeriodicDuplicates(const Grid& grid, bool periodic_x, bool periodic_y, double* f) {
  if (periodic_x) {
    for (int j = 0; j <= grid.ny; ++j) f[grid.Index(grid.nx, j)] = f[grid.Index(0, j)];
  }
  if (periodic_y) {
    for (int i = 0; i <= grid.nx; ++i) f[grid.Index(i, grid.ny)] = f[grid.Index(i, 0)];
  }
}

}  // namespace dlmfd::kernels
