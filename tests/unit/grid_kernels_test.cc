// The six-triangle gather of mesh/grid_kernels.h (engine/src/mesh), which the FEM rows, the polymer
// force and the nodal velocity gradient share: the triangles it visits around a node are the
// triangles of the mesh that have the node as a vertex, each once, with the gradient of the node's
// hat function in it; both visiting orders give the same set; the two periodic layouts name the
// lines the callers read.
#include "../../engine/src/mesh/grid_kernels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <set>
#include <tuple>
#include <vector>

namespace dlmfd::kernels {
namespace {

struct Seen {
  std::array<std::size_t, 3> vertices;
  bool upper;
  int gx, gy;
  bool operator==(const Seen& o) const {
    return std::tie(vertices, upper, gx, gy) == std::tie(o.vertices, o.upper, o.gx, o.gy);
  }
  bool operator<(const Seen& o) const {
    return std::tie(vertices, upper, gx, gy) < std::tie(o.vertices, o.upper, o.gx, o.gy);
  }
};

template <SquareOrder kOrder>
std::vector<Seen> Visit(const Grid& g, const CellsBeside& x, int j_line, bool periodic_y) {
  std::vector<Seen> out;
  const CellsBeside y = RowOffsets(g, OwnCells(j_line, g.ny, periodic_y));
  ForEachTriangleAround<kOrder>(x, y, [&](const TriangleAround& t) {
    out.push_back(Seen{{t.k0, t.k1, t.k2}, t.upper, t.gx, t.gy});
  });
  return out;
}

// h grad phi of the node (i, j) on the triangle, from the vertex coordinates (unit mesh): phi is 1
// at the node's vertex and 0 at the two others.
std::array<int, 2> HatGradient(const Grid& g, const std::array<std::size_t, 3>& k,
                               std::size_t node) {
  double x[3], y[3], f[3];
  for (int m = 0; m < 3; ++m) {
    const NodeLines n = NodeAt(g, k[m]);
    x[m] = n.i;
    y[m] = n.j;
    f[m] = k[m] == node ? 1.0 : 0.0;
  }
  const double det = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  const double gx = ((f[1] - f[0]) * (y[2] - y[0]) - (f[2] - f[0]) * (y[1] - y[0])) / det;
  const double gy = ((x[1] - x[0]) * (f[2] - f[0]) - (x[2] - x[0]) * (f[1] - f[0])) / det;
  return {static_cast<int>(gx), static_cast<int>(gy)};
}

TEST(GridKernels, NodeAtInvertsIndex) {
  const Grid g{5, 3, 0.1, 0.0, 0.0};
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const NodeLines n = NodeAt(g, g.Index(i, j));
      EXPECT_EQ(n.i, i);
      EXPECT_EQ(n.j, j);
    }
  }
}

TEST(GridKernels, GatherVisitsEveryTriangleOfTheNodeOnceWithItsHatGradient) {
  const Grid g{6, 5, 0.1, 0.0, 0.0};
  // Triangles of the mesh (as vertex triples in the gather's order) that have node n as a vertex.
  auto expected = [&](std::size_t n) {
    std::set<std::array<std::size_t, 3>> out;
    for (int sj = 0; sj < g.ny; ++sj) {
      for (int si = 0; si < g.nx; ++si) {
        const std::size_t a = g.Index(si, sj), b = g.Index(si + 1, sj);
        const std::size_t c = g.Index(si + 1, sj + 1), d = g.Index(si, sj + 1);
        for (const auto& t : {std::array<std::size_t, 3>{a, b, c}, {a, c, d}}) {
          if (std::find(t.begin(), t.end(), n) != t.end()) out.insert(t);
        }
      }
    }
    return out;
  };
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const std::size_t n = g.Index(i, j);
      const CellsBeside x = OwnCells(i, g.nx, false);
      const std::vector<Seen> ccw = Visit<SquareOrder::kCounterClockwise>(g, x, j, false);
      const std::vector<Seen> full = Visit<SquareOrder::kFullSquaresFirst>(g, x, j, false);
      std::set<std::array<std::size_t, 3>> seen;
      int sum_gx = 0, sum_gy = 0;
      for (const Seen& s : ccw) {
        EXPECT_TRUE(seen.insert(s.vertices).second) << "twice at " << i << ", " << j;
        const std::array<int, 2> grad = HatGradient(g, s.vertices, n);
        EXPECT_EQ(s.gx, grad[0]) << i << ", " << j;
        EXPECT_EQ(s.gy, grad[1]) << i << ", " << j;
        sum_gx += s.gx;
        sum_gy += s.gy;
      }
      EXPECT_EQ(seen, expected(n)) << i << ", " << j;
      if (i > 0 && i < g.nx && j > 0 && j < g.ny) {
        EXPECT_EQ(ccw.size(), 6u);
        // Equal areas: the hat's gradients over its support integrate to zero.
        EXPECT_EQ(sum_gx, 0);
        EXPECT_EQ(sum_gy, 0);
      }
      EXPECT_EQ(std::set<Seen>(ccw.begin(), ccw.end()), std::set<Seen>(full.begin(), full.end()));
    }
  }
}

TEST(GridKernels, OrdersDifferOnlyInTheNwAndSwSquares) {
  const Grid g{4, 4, 0.25, 0.0, 0.0};
  const CellsBeside x = OwnCells(2, g.nx, false);
  const std::vector<Seen> ccw = Visit<SquareOrder::kCounterClockwise>(g, x, 2, false);
  const std::vector<Seen> full = Visit<SquareOrder::kFullSquaresFirst>(g, x, 2, false);
  ASSERT_EQ(ccw.size(), 6u);
  ASSERT_EQ(full.size(), 6u);
  // NE (T1, T2), NW (T1), SW (T1, T2), SE (T2) against NE (T1, T2), SW (T1, T2), NW (T1), SE (T2).
  const int order[6] = {0, 1, 3, 4, 2, 5};
  for (int k = 0; k < 6; ++k) EXPECT_EQ(full[k].vertices, ccw[order[k]].vertices) << k;
}

TEST(GridKernels, PeriodicLayouts) {
  // Folded (the FEM rows): the cell after the last row-owning line ends on line 0.
  const AxisWrap periodic(4, AxisBoundary{EndKind::kPeriodic, EndKind::kPeriodic});
  const CellsBeside first = FoldedCells(periodic.Prev(0), 0, periodic.Next(0));
  EXPECT_EQ(first.before_lo, 3);
  EXPECT_EQ(first.before_hi, 0);
  EXPECT_EQ(first.after_lo, 0);
  EXPECT_EQ(first.after_hi, 1);
  const CellsBeside last = FoldedCells(periodic.Prev(3), 3, periodic.Next(3));
  EXPECT_EQ(last.after_lo, 3);
  EXPECT_EQ(last.after_hi, 0);
  // Own lines (the conformation kernels): the last cell ends on the repeated line 4; the repeated
  // line itself is a node with the cells (3, 4) and (0, 1).
  const CellsBeside own_first = OwnCells(0, 4, true);
  EXPECT_EQ(own_first.before_lo, 3);
  EXPECT_EQ(own_first.before_hi, 4);
  const CellsBeside own_repeated = OwnCells(4, 4, true);
  EXPECT_EQ(own_repeated.before_lo, 3);
  EXPECT_EQ(own_repeated.before_hi, 4);
  EXPECT_EQ(own_repeated.after_lo, 0);
  EXPECT_EQ(own_repeated.after_hi, 1);
  // Without the wrap the ends have one cell.
  const CellsBeside wall = OwnCells(0, 4, false);
  EXPECT_LT(wall.before_lo, 0);
  EXPECT_EQ(wall.after_lo, 0);
  const AxisWrap walled(4, AxisBoundary{EndKind::kDirichlet, EndKind::kDirichlet});
  const CellsBeside wall_end = FoldedCells(walled.Prev(4), 4, walled.Next(4));
  EXPECT_EQ(wall_end.before_lo, 3);
  EXPECT_LT(wall_end.after_lo, 0);
}

TEST(GridKernels, AddUnitAddsNothingForAZeroUnit) {
  double acc = 0.5;
  AddUnit(acc, 0, 1.0e300);
  EXPECT_EQ(acc, 0.5);
  AddUnit(acc, 1, 0.25);
  EXPECT_EQ(acc, 0.75);
  AddUnit(acc, -1, 0.5);
  EXPECT_EQ(acc, 0.25);
}

}  // namespace
}  // namespace dlmfd::kernels
