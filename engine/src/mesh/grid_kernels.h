// Stencil kernels of the P1 operators on the uniform SW-NE mesh: the only place where node indices
// are computed. Each kernel gathers one node's row from the (up to) six triangles around it, so the
// rows can be computed in parallel without write conflicts and the element-wise boundary rows come
// out exactly (method notes 1, section 1). The gather itself (ForEachSquareAround,
// ForEachTriangleAround) serves the FEM operators (fem_operators.cc) and the conformation kernels
// (the polymer force of (33), the nodal velocity gradient of (35)); periodic wrap (Wrap, AxisWrap,
// CellsBeside) and the nodes a disk covers (CoveredNodes) live here too.
//
// Triangles of the h-square with corners a = (i,j), b = (i+1,j), c = (i+1,j+1), d = (i,j+1):
//   T1 = (a,b,c): h dx f = f_b - f_a, h dy f = f_c - f_b;
//   T2 = (a,c,d): h dx f = f_c - f_d, h dy f = f_d - f_a.
// Around node n = (i,j): square (i,j) [NE of n; n = a of T1 and T2], (i-1,j) [NW; n = b of T1],
// (i-1,j-1) [SW; n = c of T1 and T2], (i,j-1) [SE; n = d of T2].
// The mirrored triangulation (NW-SE diagonals, domain.diagonals = "both") cuts the square along
// b-d instead:
//   T3 = (a,b,d): h dx f = f_b - f_a, h dy f = f_d - f_a;
//   T4 = (b,c,d): h dx f = f_c - f_d, h dy f = f_c - f_b.
// Around node n: NE square, n = a of T3; NW, n = b of T3 and T4; SW, n = c of T4; SE, n = d of T3
// and T4. The kernels below take the triangulation as a template argument (Diagonal), so that the
// mean of the two forms is one sweep over the nodes (fem_operators.cc).
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

// The node (i, j) stored at index k of a node array of the grid: the inverse of Grid::Index.
struct NodeLines {
  int i, j;
};
inline NodeLines NodeAt(const Grid& grid, std::size_t k) {
  const std::size_t row = std::size_t(grid.nx + 1);
  return NodeLines{static_cast<int>(k % row), static_cast<int>(k / row)};
}

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

// ---- The six-triangle gather ----------------------------------------------------------------
// Every row of a P1 operator, and every nodal average of P1 gradients, sums over the (up to) six
// triangles around the node: both triangles of the squares NE and SW of the node, T1 of the square
// NW of it and T2 of the square SE of it. The gather is written once, here: one axis at a time,
// the two cells beside the node line (CellsBeside) name the node lines of their sides, and
// ForEachSquareAround visits the squares that exist, with their corner indices and the gradient of
// the node's hat function in each of their triangles.
//
// Two layouts of a periodic axis, both of a node array whose last line repeats the first:
//   folded (FoldedCells): the repeated line is no unknown, and the cell after line n - 1 ends on
//     line 0. The layout of the Galerkin rows (fem_operators.h), which never read the duplicate.
//   own lines (OwnCells): every cell ends on the line after its first, so the last cell ends on the
//     repeated line, and a node on the repeated line has cells too. The layout of the conformation
//     kernels (polymer_force.h, velocity_gradient.h), whose node arrays keep the duplicate equal
//     to the first line.

// The node lines of the cells before and after a node line (x) or their row offsets
// Index(0, line) (y); lo < 0 where there is no such cell.
struct CellsBeside {
  long before_lo, before_hi;
  long after_lo, after_hi;
};

// Folded layout, from the neighbour lines prev / next of `line` (-1 where absent: AxisWrap).
inline CellsBeside FoldedCells(int prev, int line, int next) {
  return CellsBeside{prev, line, next >= 0 ? line : -1, next};
}

// Own-lines layout: the cells (line - 1, line) and (line, line + 1) of an axis of `cells` cells,
// wrapped across a periodic side to cells (cells - 1, cells) and (0, 1).
inline CellsBeside OwnCells(int line, int cells, bool periodic) {
  auto cell = [&](int first) -> long {
    if (first >= 0 && first < cells) return first;
    return periodic ? Wrap(first, cells) : -1;
  };
  const long before = cell(line - 1), after = cell(line);
  return CellsBeside{before, before >= 0 ? before + 1 : -1, after, after >= 0 ? after + 1 : -1};
}

// Node lines of a y axis as row offsets of the grid.
inline CellsBeside RowOffsets(const Grid& grid, const CellsBeside& y) {
  const long row = grid.NodesX();
  auto offset = [row](long line) { return line >= 0 ? line * row : -1; };
  return CellsBeside{offset(y.before_lo), offset(y.before_hi), offset(y.after_lo),
                     offset(y.after_hi)};
}

// The y cells of node row j in the folded layout, as row offsets.
inline CellsBeside FoldedRows(const Grid& grid, const AxisWrap& ay, int j) {
  return RowOffsets(grid, FoldedCells(ay.Prev(j), j, ay.Next(j)));
}

// The triangulation of the squares: SW-NE diagonals (the mesh's, T1 and T2) or NW-SE ones (T3 and
// T4, the mirror image; domain.diagonals = "both" takes the mean of the forms on the two).
enum class Diagonal { kSwNe, kNwSe };

// One square around a node: corners a = SW, b = SE, c = NE, d = NW (node indices); the triangles
// of the triangulation that touch the node, `lower` (T1, or T3) and `upper` (T2, or T4), and in
// each h grad phi of the node's hat function (unit mesh: components -1, 0 or 1).
struct SquareAround {
  std::size_t a, b, c, d;
  bool lower, upper;  // T1 / T3 and T2 / T4 touch the node
  int lx, ly;         // h grad phi on T1 / T3
  int ux, uy;         // h grad phi on T2 / T4
};

// h times the derivatives of a P1 field f on the lower and upper triangle of a square.
template <Diagonal kD = Diagonal::kSwNe>
inline double LowerDx(const double* f, const SquareAround& s) {
  return f[s.b] - f[s.a];
}
template <Diagonal kD = Diagonal::kSwNe>
inline double LowerDy(const double* f, const SquareAround& s) {
  return kD == Diagonal::kSwNe ? f[s.c] - f[s.b] : f[s.d] - f[s.a];
}
template <Diagonal kD = Diagonal::kSwNe>
inline double UpperDx(const double* f, const SquareAround& s) {
  return f[s.c] - f[s.d];
}
template <Diagonal kD = Diagonal::kSwNe>
inline double UpperDy(const double* f, const SquareAround& s) {
  return kD == Diagonal::kSwNe ? f[s.d] - f[s.a] : f[s.c] - f[s.b];
}
// Sums of f over the vertices of the lower and upper triangle.
template <Diagonal kD = Diagonal::kSwNe>
inline double LowerSum(const double* f, const SquareAround& s) {
  return kD == Diagonal::kSwNe ? f[s.a] + f[s.b] + f[s.c] : f[s.a] + f[s.b] + f[s.d];
}
template <Diagonal kD = Diagonal::kSwNe>
inline double UpperSum(const double* f, const SquareAround& s) {
  return kD == Diagonal::kSwNe ? f[s.a] + f[s.c] + f[s.d] : f[s.b] + f[s.c] + f[s.d];
}

// The order in which the squares are visited (sums are not associative: each caller keeps its
// own). kCounterClockwise: NE, NW, SW, SE. kFullSquaresFirst: NE, SW, NW, SE.
enum class SquareOrder { kCounterClockwise, kFullSquaresFirst };

// The node's part in each square around it, per triangulation (the header's T1-T4): which of the
// lower and upper triangle touch it and h grad phi of its hat function on them (lx, ly; ux, uy).
struct CornerRole {
  bool lower, upper;
  int lx, ly, ux, uy;
};
// Indexed by the square: 0 NE (the node is a), 1 NW (b), 2 SW (c), 3 SE (d).
inline constexpr CornerRole kSwNeRoles[4] = {{true, true, -1, 0, 0, -1},   // T1, T2
                                             {true, false, 1, -1, 0, 0},   // T1
                                             {true, true, 0, 1, 1, 0},     // T1, T2
                                             {false, true, 0, 0, -1, 1}};  // T2
inline constexpr CornerRole kNwSeRoles[4] = {{true, false, -1, -1, 0, 0},  // T3
                                             {true, true, 1, 0, 0, -1},    // T3, T4
                                             {false, true, 0, 0, 1, 1},    // T4
                                             {true, true, 0, 1, -1, 0}};   // T3, T4

// Calls visit(SquareAround) for each square around the node whose cells exist: x holds node lines,
// y row offsets (RowOffsets). Each node row is written by its node alone: rows can be computed in
// parallel without write conflicts, and the element-wise boundary rows come out exactly. Always
// inlined: a sweep that gathers from both triangulations instantiates it twice per node, beyond
// what the compiler inlines on its own (measured: the NW-SE call stayed a call, 3 times slower).
template <SquareOrder kOrder = SquareOrder::kCounterClockwise, Diagonal kD = Diagonal::kSwNe,
          typename Visit>
[[gnu::always_inline]] inline void ForEachSquareAround(const CellsBeside& x, const CellsBeside& y,
                                                       Visit&& visit) {
  constexpr const CornerRole* kRoles = kD == Diagonal::kSwNe ? kSwNeRoles : kNwSeRoles;
  auto square = [&](bool exists, long xlo, long xhi, long ylo, long yhi, const CornerRole& r)
      __attribute__((always_inline)) {
    if (!exists) return;
    visit(SquareAround{std::size_t(ylo + xlo), std::size_t(ylo + xhi), std::size_t(yhi + xhi),
                       std::size_t(yhi + xlo), r.lower, r.upper, r.lx, r.ly, r.ux, r.uy});
  };
  const bool west = x.before_lo >= 0, east = x.after_lo >= 0;
  const bool south = y.before_lo >= 0, north = y.after_lo >= 0;
  auto ne = [&]() __attribute__((always_inline)) {
    square(east && north, x.after_lo, x.after_hi, y.after_lo, y.after_hi, kRoles[0]);
  };
  auto nw = [&]() __attribute__((always_inline)) {
    square(west && north, x.before_lo, x.before_hi, y.after_lo, y.after_hi, kRoles[1]);
  };
  auto sw = [&]() __attribute__((always_inline)) {
    square(west && south, x.before_lo, x.before_hi, y.before_lo, y.before_hi, kRoles[2]);
  };
  auto se = [&]() __attribute__((always_inline)) {
    square(east && south, x.after_lo, x.after_hi, y.before_lo, y.before_hi, kRoles[3]);
  };
  ne();
  if constexpr (kOrder == SquareOrder::kCounterClockwise) {
    nw();
    sw();
  } else {
    sw();
    nw();
  }
  se();
}

// One triangle around a node: its vertices k0, k1, k2 (T1: a, b, c; T2: a, c, d; T3: a, b, d; T4:
// b, c, d), which one of the square's two it is, and h grad phi of the node's hat function on it.
struct TriangleAround {
  std::size_t k0, k1, k2;
  bool upper;  // T2 or T4
  int gx, gy;
};

// h times the derivatives of a P1 field f on the triangle (the x one is k1 - k0 on T1 and T3, k1 -
// k2 on T2 and T4).
template <Diagonal kD = Diagonal::kSwNe>
inline double TriangleDx(const double* f, const TriangleAround& t) {
  return t.upper ? f[t.k1] - f[t.k2] : f[t.k1] - f[t.k0];
}
template <Diagonal kD = Diagonal::kSwNe>
inline double TriangleDy(const double* f, const TriangleAround& t) {
  if constexpr (kD == Diagonal::kSwNe) return t.upper ? f[t.k2] - f[t.k0] : f[t.k2] - f[t.k1];
  return t.upper ? f[t.k1] - f[t.k0] : f[t.k2] - f[t.k0];
}

// Calls visit(TriangleAround) for each triangle of the triangulation around the node, the lower
// before the upper in each square.
template <SquareOrder kOrder = SquareOrder::kCounterClockwise, Diagonal kD = Diagonal::kSwNe,
          typename Visit>
[[gnu::always_inline]] inline void ForEachTriangleAround(const CellsBeside& x, const CellsBeside& y,
                                                         Visit&& visit) {
  ForEachSquareAround<kOrder, kD>(x, y, [&](const SquareAround& s) {
    if constexpr (kD == Diagonal::kSwNe) {
      if (s.lower) visit(TriangleAround{s.a, s.b, s.c, false, s.lx, s.ly});
      if (s.upper) visit(TriangleAround{s.a, s.c, s.d, true, s.ux, s.uy});
    } else {
      if (s.lower) visit(TriangleAround{s.a, s.b, s.d, false, s.lx, s.ly});
      if (s.upper) visit(TriangleAround{s.b, s.c, s.d, true, s.ux, s.uy});
    }
  });
}

// acc += unit * value for unit in {-1, 0, 1}, without a multiplication (a zero unit adds nothing).
inline void AddUnit(double& acc, int unit, double value) {
  if (unit > 0) acc += value;
  if (unit < 0) acc -= value;
}

// h/6-scaled sums of the element gradients of f over the triangles around the node:
// (G_x f)_n = (h/6) gx, (G_y f)_n = (h/6) gy. The two triangles of a square are added as a pair.
template <Diagonal kD = Diagonal::kSwNe>
[[gnu::always_inline]] inline void GradientSumsAt(const double* f, const CellsBeside& x,
                                                  const CellsBeside& y, double& gx, double& gy) {
  gx = 0.0;
  gy = 0.0;
  ForEachSquareAround<SquareOrder::kCounterClockwise, kD>(x, y, [&](const SquareAround& s) {
    if (s.lower && s.upper) {
      gx += LowerDx<kD>(f, s) + UpperDx<kD>(f, s);
      gy += LowerDy<kD>(f, s) + UpperDy<kD>(f, s);
    } else if (s.lower) {
      gx += LowerDx<kD>(f, s);
      gy += LowerDy<kD>(f, s);
    } else {
      gx += UpperDx<kD>(f, s);
      gy += UpperDy<kD>(f, s);
    }
  });
}

// h/6-scaled divergence row, (G_x u + G_y v)_n = (h/6) of the result: the x sums of u plus the y
// sums of v over the same triangles as GradientSumsAt.
template <Diagonal kD = Diagonal::kSwNe>
[[gnu::always_inline]] inline double DivergenceSumsAt(const double* u, const double* v,
                                                      const CellsBeside& x, const CellsBeside& y) {
  double sum = 0.0;
  ForEachSquareAround<SquareOrder::kCounterClockwise, kD>(x, y, [&](const SquareAround& s) {
    if (s.lower && s.upper) {
      sum += LowerDx<kD>(u, s) + UpperDx<kD>(u, s);
      sum += LowerDy<kD>(v, s) + UpperDy<kD>(v, s);
    } else if (s.lower) {
      sum += LowerDx<kD>(u, s) + LowerDy<kD>(v, s);
    } else {
      sum += UpperDx<kD>(u, s) + UpperDy<kD>(v, s);
    }
  });
  return sum;
}

// h/6-scaled rows of the transposed gradients, (G_x^T g)_n = (h/6) ox, (G_y^T g)_n = (h/6) oy:
// each triangle adds (sum of g at its vertices) times h times the gradient of the node's basis.
template <Diagonal kD = Diagonal::kSwNe>
[[gnu::always_inline]] inline void GradientTransposeSumsAt(const double* g, const CellsBeside& x,
                                                           const CellsBeside& y, double& ox,
                                                           double& oy) {
  ox = 0.0;
  oy = 0.0;
  ForEachSquareAround<SquareOrder::kCounterClockwise, kD>(x, y, [&](const SquareAround& s) {
    if (s.lower) {
      const double sum = LowerSum<kD>(g, s);
      AddUnit(ox, s.lx, sum);
      AddUnit(oy, s.ly, sum);
    }
    if (s.upper) {
      const double sum = UpperSum<kD>(g, s);
      AddUnit(ox, s.ux, sum);
      AddUnit(oy, s.uy, sum);
    }
  });
}

// Full-weighting restriction I_p^T at the fine node under a pressure node: the node itself plus
// half of its six P1 neighbours E, W, N, S and, along the 2h-squares' diagonal, NE and SW (SW-NE)
// or NW and SE (NW-SE).
template <Diagonal kD = Diagonal::kSwNe>
[[gnu::always_inline]] inline double RestrictAt(const Rows& w, int im, int i, int ip) {
  constexpr bool kSwNe = kD == Diagonal::kSwNe;
  double sum = 0.0;
  if (im >= 0) sum += w.row[im];
  if (ip >= 0) sum += w.row[ip];
  if (w.below) {
    sum += w.below[i];
    const int diagonal = kSwNe ? im : ip;
    if (diagonal >= 0) sum += w.below[diagonal];
  }
  if (w.above) {
    sum += w.above[i];
    const int diagonal = kSwNe ? ip : im;
    if (diagonal >= 0) sum += w.above[diagonal];
  }
  return w.row[i] + 0.5 * sum;
}

// The mean of both restrictions, 0.5 (I_p^T(SW-NE) w + I_p^T(NW-SE) w2), at the fine node under a
// pressure node, where the two differ only at the odd-odd neighbours: `s` holds w + w2 at the node
// and at E, W, N, S and w at the odd-odd nodes (their SW-NE values), `w2` the NW-SE values there.
[[gnu::always_inline]] inline double RestrictBothAt(const Rows& s, const Rows& w2, int im, int i,
                                                    int ip) {
  double sum = 0.0;
  if (im >= 0) sum += s.row[im];
  if (ip >= 0) sum += s.row[ip];
  if (s.below) {
    sum += s.below[i];
    if (im >= 0) sum += s.below[im];   // SW, SW-NE
    if (ip >= 0) sum += w2.below[ip];  // SE, NW-SE
  }
  if (s.above) {
    sum += s.above[i];
    if (ip >= 0) sum += s.above[ip];   // NE, SW-NE
    if (im >= 0) sum += w2.above[im];  // NW, NW-SE
  }
  return 0.5 * (s.row[i] + 0.5 * sum);
}

// P1 interpolation I_p from the 2h-grid along one fine row: `low` is coarse row j/2, `high` the
// next coarse row for odd j (null for even j). Odd-odd fine nodes are midpoints of the diagonal of
// a 2h-square, so they average its SW and NE coarse values (SW-NE) or its NW and SE ones (NW-SE).
// The pairs (2 ci, 2 ci + 1) whose coarse neighbour ci + 1 needs no wrap go first, without a
// branch or a wrap per node (the same sums, so the same bits); the rest by the general rule.
template <Diagonal kD = Diagonal::kSwNe>
inline void ProlongRow(const AxisWrap& cx, const double* low, const double* high, int fine_lines,
                       double* out) {
  const int pairs = std::max(0, std::min(fine_lines / 2, cx.cells - 1));
  if (high) {
    for (int ci = 0; ci < pairs; ++ci) {
      out[2 * ci] = 0.5 * (low[ci] + high[ci]);
      out[2 * ci + 1] =
          kD == Diagonal::kSwNe ? 0.5 * (low[ci] + high[ci + 1]) : 0.5 * (low[ci + 1] + high[ci]);
    }
  } else {
    for (int ci = 0; ci < pairs; ++ci) {
      out[2 * ci] = low[ci];
      out[2 * ci + 1] =
          kD == Diagonal::kSwNe ? 0.5 * (low[ci] + low[ci + 1]) : 0.5 * (low[ci + 1] + low[ci]);
    }
  }
  for (int i = 2 * pairs; i < fine_lines; ++i) {
    const int ci = i / 2;
    if (i % 2 == 0) {
      out[i] = high ? 0.5 * (low[ci] + high[ci]) : low[ci];
    } else {
      const int ci1 = cx.Next(ci);
      if constexpr (kD == Diagonal::kSwNe) {
        out[i] = 0.5 * (low[ci] + (high ? high[ci1] : low[ci1]));
      } else {
        out[i] = 0.5 * (low[ci1] + (high ? high[ci] : low[ci]));
      }
    }
  }
}

}  // namespace dlmfd::kernels
