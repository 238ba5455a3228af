// Stencil kernels of the P1 operators on the uniform SW-NE mesh: the only place where node indices
// are computed. Each kernel gathers one node's row from the (up to) six triangles around it, so the
// rows can be computed in parallel without write conflicts and the element-wise boundary rows come
// out exactly (method notes 1, section 1).
//
// Triangles of the h-square with corners a = (i,j), b = (i+1,j), c = (i+1,j+1), d = (i,j+1):
//   T1 = (a,b,c): h dx f = f_b - f_a, h dy f = f_c - f_b;   T2 = (a,c,d): h dx f = f_c - f_d, h dy
//   f = f_d - f_a.
// Around node n = (i,j): square (i,j) [n = a of T1 and T2], (i-1,j) [n = b of T1],
// (i-1,j-1) [n = c of T1 and T2], (i,j-1) [n = d of T2].
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "dlmfd/core/grid.h"
#include "dlmfd/mesh/boundary_topology.h"

namespace dlmfd::kernels {

// One axis of a grid: which node lines carry rows, and their neighbours with the periodic wrap
// (the repeated last line folds into the first).
struct AxisWrap {
  int cells = 0;
  bool periodic = false;

  AxisWrap(int n_cells, const AxisBoundary& ends)
      : cells(n_cells),
        periodic(ends.low == EndKind::kPeriodic) {}
  // Node lines that own a row: all of them, less the periodic duplicate.
  int Lines() const { return periodic ? cells : cells + 1; }
  // Neighbour line below / above, or -1 where there is none.
  int Prev(int i) const { return i > 0 ? i - 1 : (periodic ? cells - 1 : -1); }
  int Next(int i) const {
    if (i + 1 < cells) return i + 1;
    if (periodic) return 0;
    return i < cells ? cells : -1;
  }
  // Trapezoid weight of the line: 1/2 on a non-periodic end, 1 elsewhere.
  double Weight(int i) const { return (!periodic && (i == 0 || i == cells)) ? 0.5 : 1.0; }
};

// The index of line i on a periodic axis of n cells: i mod n, also for negative i.
inline int Wrap(int i, int n) { return ((i % n) + n) % n; }

// The node range [lo, hi] that the interval [a, b] covers on a line of n cells of size h from x0.
// Periodic lines return an unclamped range (the caller wraps with Wrap); others are clamped to
// 0..n.
inline void CoveredNodes(double a, double b, double x0, double h, int n, bool periodic, int* lo,
                         int* hi) {
  *lo = static_cast<int>(std::ceil((a - x0) / h));
  *hi = static_cast<int>(std::floor((b - x0) / h));
  if (!periodic) {
    *lo = std::max(*lo, 0);
    *hi = std::min(*hi, n);
  }
}

// Three node rows (below, this, above) of a node array; below/above are null where absent.
struct Rows {
  const double* below;
  const double* row;
  const double* above;
};

inline Rows RowsAt(const Grid& grid, const AxisWrap& ay, const double* f, int j) {
  const int jm = ay.Prev(j), jp = ay.Next(j);
  return Rows{jm >= 0 ? f + grid.Index(0, jm) : nullptr, f + grid.Index(0, j),
              jp >= 0 ? f + grid.Index(0, jp) : nullptr};
}

// (K u)_n: 5-point stiffness with trapezoid weights on the lines (K = K1x (x) Dy + Dx (x) K1y).
inline double StiffnessAt(const Rows& u, int im, int i, int ip, double wx, double wy) {
  const double c = u.row[i];
  double kx = 0.0, ky = 0.0;
  if (im >= 0) kx += c - u.row[im];
  if (ip >= 0) kx += c - u.row[ip];
  if (u.below) ky += c - u.below[i];
  if (u.above) ky += c - u.above[i];
  return wy * kx + wx * ky;
}

// h/6-scaled sums of the element gradients of f over the triangles around the node:
// (G_x f)_n = (h/6) gx, (G_y f)_n = (h/6) gy.
inline void GradientSumsAt(const Rows& f, int im, int i, int ip, double& gx, double& gy) {
  gx = 0.0;
  gy = 0.0;
  const double* s = f.below;
  const double* r = f.row;
  const double* n = f.above;
  if (n && ip >= 0) {  // square (i,j): T1 and T2
    gx += (r[ip] - r[i]) + (n[ip] - n[i]);
    gy += (n[ip] - r[ip]) + (n[i] - r[i]);
  }
  if (n && im >= 0) {  // square (i-1,j): T1
    gx += r[i] - r[im];
    gy += n[i] - r[i];
  }
  if (s && im >= 0) {  // square (i-1,j-1): T1 and T2
    gx += (s[i] - s[im]) + (r[i] - r[im]);
    gy += (r[i] - s[i]) + (r[im] - s[im]);
  }
  if (s && ip >= 0) {  // square (i,j-1): T2
    gx += r[ip] - r[i];
    gy += r[i] - s[i];
  }
}

// h/6-scaled divergence row, (G_x u + G_y v)_n = (h/6) of the result: the x sums of u plus the y
// sums of v over the same triangles as GradientSumsAt.
inline double DivergenceSumsAt(const Rows& u, const Rows& v, int im, int i, int ip) {
  double sum = 0.0;
  if (u.above && ip >= 0) {  // square (i,j): T1 and T2
    sum += (u.row[ip] - u.row[i]) + (u.above[ip] - u.above[i]);
    sum += (v.above[ip] - v.row[ip]) + (v.above[i] - v.row[i]);
  }
  if (u.above && im >= 0) {  // square (i-1,j): T1
    sum += (u.row[i] - u.row[im]) + (v.above[i] - v.row[i]);
  }
  if (u.below && im >= 0) {  // square (i-1,j-1): T1 and T2
    sum += (u.below[i] - u.below[im]) + (u.row[i] - u.row[im]);
    sum += (v.row[i] - v.below[i]) + (v.row[im] - v.below[im]);
  }
  if (u.below && ip >= 0) {  // square (i,j-1): T2
    sum += (u.row[ip] - u.row[i]) + (v.row[i] - v.below[i]);
  }
  return sum;
}

// h/6-scaled rows of the transposed gradients, (G_x^T g)_n = (h/6) ox, (G_y^T g)_n = (h/6) oy:
// each triangle adds (sum of g at its vertices) times h times the gradient of the node's basis.
inline void GradientTransposeSumsAt(const Rows& g, int im, int i, int ip, double& ox, double& oy) {
  ox = 0.0;
  oy = 0.0;
  const double* s = g.below;
  const double* r = g.row;
  const double* n = g.above;
  if (n && ip >= 0) {  // square (i,j): n = a; T1 grad (-1, 0), T2 grad (0, -1)
    ox -= r[i] + r[ip] + n[ip];
    oy -= r[i] + n[ip] + n[i];
  }
  if (n && im >= 0) {  // square (i-1,j): n = b of T1, grad (1, -1)
    const double sum = r[im] + r[i] + n[i];
    ox += sum;
    oy -= sum;
  }
  if (s && im >= 0) {  // square (i-1,j-1): n = c; T1 grad (0, 1), T2 grad (1, 0)
    oy += s[im] + s[i] + r[i];
    ox += s[im] + r[i] + r[im];
  }
  if (s && ip >= 0) {  // square (i,j-1): n = d of T2, grad (-1, 1)
    const double sum = s[i] + r[ip] + r[i];
    ox -= sum;
    oy += sum;
  }
}

// Full-weighting restriction I_p^T at the fine node under a pressure node: the node itself plus
// half of its six P1 neighbours E, W, N, S, NE, SW (2h-squares are also cut SW-NE).
inline double RestrictAt(const Rows& w, int im, int i, int ip) {
  double sum = 0.0;
  if (im >= 0) sum += w.row[im];
  if (ip >= 0) sum += w.row[ip];
  if (w.below) {
    sum += w.below[i];
    if (im >= 0) sum += w.below[im];
  }
  if (w.above) {
    sum += w.above[i];
    if (ip >= 0) sum += w.above[ip];
  }
  return w.row[i] + 0.5 * sum;
}

// P1 interpolation I_p from the 2h-grid along one fine row: `low` is coarse row j/2, `high` the
// next coarse row for odd j (null for even j). Odd-odd fine nodes are midpoints of the SW-NE
// diagonal of a 2h-square, so they average the SW and NE coarse values.
inline void ProlongRow(const AxisWrap& cx, const double* low, const double* high, int fine_lines,
                       double* out) {
  for (int i = 0; i < fine_lines; ++i) {
    const int ci = i / 2;
    if (i % 2 == 0) {
      out[i] = high ? 0.5 * (low[ci] + high[ci]) : low[ci];
    } else {
      const int ci1 = cx.Next(ci);
      out[i] = 0.5 * (low[ci] + (high ? high[ci1] : low[ci1]));
    }
  }
}

}  // namespace dlmfd::kernels
