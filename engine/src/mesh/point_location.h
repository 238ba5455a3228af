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
  // floor(s): the truncation, one less for a negative s off an integer; the value of std::floor,
  // without its generic sequence on a target without SSE4.1's rounding (16 against 5 instructions
  // an axis; docs/evidence/performance.md, "A thousand particles").
  int c = static_cast<int>(s);
  if (static_cast<double>(c) > s) --c;
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

// The square (i0, j0) of point (x, y), its next node lines (i1, j1) and the local coordinates
// (xi, eta): true, or false when the point lies beyond a non-periodic side, with *side that side
// (as Side: 0 left, 1 right, 2 bottom, 3 top; the x axis is checked first).
struct SquareOfPoint {
  int i0 = 0, j0 = 0, i1 = 0, j1 = 0;
  double xi = 0.0, eta = 0.0;
};
inline bool LocateInSquare(const Grid& grid, bool periodic_x, bool periodic_y, double x, double y,
                           SquareOfPoint* q, int* side) {
  if (!LocateOnAxis((x - grid.x0) / grid.h, grid.nx, periodic_x, &q->i0, &q->xi)) {
    *side = q->i0 < 0 ? 0 : 1;
    return false;
  }
  if (!LocateOnAxis((y - grid.y0) / grid.h, grid.ny, periodic_y, &q->j0, &q->eta)) {
    *side = q->j0 < 0 ? 2 : 3;
    return false;
  }
  q->i1 = NextLine(q->i0, grid.nx, periodic_x);
  q->j1 = NextLine(q->j0, grid.ny, periodic_y);
  return true;
}

// Locates point (x, y) on the grid: true with its stencil; false when it lies beyond a
// non-periodic side, with *side that side (LocateInSquare).
inline bool LocatePoint(const Grid& grid, bool periodic_x, bool periodic_y, double x, double y,
                        P1Stencil* stencil, int* side) {
  SquareOfPoint q;
  if (!LocateInSquare(grid, periodic_x, periodic_y, x, y, &q, side)) return false;
  *stencil = P1StencilInSquare(q.i0, q.j0, q.i1, q.j1, q.xi, q.eta);
  return true;
}

// The mean of the P1 interpolants on the square's two SW-NE triangles and on its two NW-SE ones
// (domain.diagonals = "both", core/params.h): weights at the corners (i0, j0), (i1, j0), (i1, j1),
// (i0, j1). Exact for linear fields (a rigid motion) as each P1 is, and symmetric under x -> -x
// and y -> -y. At a node it is the nodal value.
struct MeanP1Stencil {
  int i[4];
  int j[4];
  double weight[4];
};
inline bool LocatePointMean(const Grid& grid, bool periodic_x, bool periodic_y, double x, double y,
                            MeanP1Stencil* stencil, int* side) {
  SquareOfPoint q;
  if (!LocateInSquare(grid, periodic_x, periodic_y, x, y, &q, side)) return false;
  const double xi = q.xi, eta = q.eta;
  // SW-NE: (a, b, c) or (a, c, d); NW-SE: (a, b, d) or (b, c, d); corners a, b, c, d.
  double w[4] = {0.0, 0.0, 0.0, 0.0};
  if (xi >= eta) {
    w[0] += 1.0 - xi, w[1] += xi - eta, w[2] += eta;
  } else {
    w[0] += 1.0 - eta, w[2] += xi, w[3] += eta - xi;
  }
  if (xi + eta <= 1.0) {
    w[0] += 1.0 - xi - eta, w[1] += xi, w[3] += eta;
  } else {
    w[1] += 1.0 - eta, w[2] += xi + eta - 1.0, w[3] += 1.0 - xi;
  }
  *stencil = MeanP1Stencil{{q.i0, q.i1, q.i1, q.i0},
                           {q.j0, q.j0, q.j1, q.j1},
                           {0.5 * w[0], 0.5 * w[1], 0.5 * w[2], 0.5 * w[3]}};
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
