#include "dlmfd/conformation/velocity_gradient.h"

namespace dlmfd {
namespace {

struct GradientSum {
  double ux = 0.0, uy = 0.0, vx = 0.0, vy = 0.0;
  int count = 0;
};

// Maps a square index to [0, n) when periodic; returns false when the square is outside.
inline bool WrapSquare(int& s, int n, bool periodic) {
  if (s >= 0 && s < n) return true;
  if (!periodic) return false;
  s = (s + n) % n;
  return true;
}

// Adds the gradient of the lower (SW, SE, NE) or upper (SW, NE, NW) triangle of square (si, sj).
inline void AddTriangle(const Grid& g, const double* u, const double* v, int si, int sj, bool upper,
                        GradientSum& sum) {
  const double inv_h = 1.0 / g.h;
  const std::size_t sw = g.Index(si, sj), se = g.Index(si + 1, sj);
  const std::size_t ne = g.Index(si + 1, sj + 1), nw = g.Index(si, sj + 1);
  if (upper) {
    sum.ux += (u[ne] - u[nw]) * inv_h;
    sum.uy += (u[nw] - u[sw]) * inv_h;
    sum.vx += (v[ne] - v[nw]) * inv_h;
    sum.vy += (v[nw] - v[sw]) * inv_h;
  } else {
    sum.ux += (u[se] - u[sw]) * inv_h;
    sum.uy += (u[ne] - u[se]) * inv_h;
    sum.vx += (v[se] - v[sw]) * inv_h;
    sum.vy += (v[ne] - v[se]) * inv_h;
  }
  ++sum.count;
}

// The 6 triangles that touch node (i, j): both of squares (i, j) and (i-1, j-1), the lower one of
// (i-1, j) and the upper one of (i, j-1).
GradientSum SumAround(const Grid& g, bool px, bool py, const double* u, const double* v, int i,
                      int j) {
  struct Candidate {
    int di, dj;
    bool lower, upper;
  };
  static constexpr Candidate kCandidates[4] = {
      {0, 0, true, true}, {-1, -1, true, true}, {-1, 0, true, false}, {0, -1, false, true}};
  GradientSum sum;
  for (const Candidate& c : kCandidates) {
    int si = i + c.di, sj = j + c.dj;
    if (!WrapSquare(si, g.nx, px) || !WrapSquare(sj, g.ny, py)) continue;
    if (c.lower) AddTriangle(g, u, v, si, sj, false, sum);
    if (c.upper) AddTriangle(g, u, v, si, sj, true, sum);
  }
  return sum;
}

// Interior nodes i = 1 .. count of one row (p points at node (1, j)): the closed form of the
// 6-triangle average. Compiled for AVX2 and for the baseline, chosen at load time.
__attribute__((target_clones("avx2", "default"))) void InteriorRow(
    int count, std::ptrdiff_t row, double inv_6h, const double* __restrict u,
    const double* __restrict v, double* __restrict l11, double* __restrict l12,
    double* __restrict l21, double* __restrict l22) {
  for (int i = 0; i < count; ++i) {
    const double* p = u + i;
    const double* q = v + i;
    l11[i] = (2.0 * (p[1] - p[-1]) + p[row + 1] - p[row] + p[-row] - p[-row - 1]) * inv_6h;
    l12[i] = (2.0 * (p[row] - p[-row]) + p[row + 1] - p[1] + p[-1] - p[-row - 1]) * inv_6h;
    l21[i] = (2.0 * (q[1] - q[-1]) + q[row + 1] - q[row] + q[-row] - q[-row - 1]) * inv_6h;
    l22[i] = (2.0 * (q[row] - q[-row]) + q[row + 1] - q[1] + q[-1] - q[-row - 1]) * inv_6h;
  }
}

}  // namespace

void NodeVelocityGradient(const Grid& grid, bool periodic_x, bool periodic_y, const double* u,
                          const double* v, double* l11, double* l12, double* l21, double* l22) {
  const int nx = grid.nx, ny = grid.ny;
  const std::ptrdiff_t row = nx + 1;
  const double inv_6h = 1.0 / (6.0 * grid.h);
#pragma omp parallel for schedule(static)
  for (int j = 0; j <= ny; ++j) {
    const bool interior_row = j > 0 && j < ny;
    if (interior_row && nx > 1) {
      const std::size_t k = grid.Index(1, j);
      InteriorRow(nx - 1, row, inv_6h, u + k, v + k, l11 + k, l12 + k, l21 + k, l22 + k);
    }
    for (int i = 0; i <= nx; ++i) {
      if (interior_row && i > 0 && i < nx) continue;  // done above
      const std::size_t k = grid.Index(i, j);
      const GradientSum s = SumAround(grid, periodic_x, periodic_y, u, v, i, j);
      const double inv = 1.0 / s.count;
      l11[k] = s.ux * inv;
      l12[k] = s.uy * inv;
      l21[k] = s.vx * inv;
      l22[k] = s.vy * inv;
    }
  }
}

}  // namespace dlmfd
