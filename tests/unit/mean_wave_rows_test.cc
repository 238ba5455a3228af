// The row kernels of the wave stiffness on both diagonals (engine/src/fluid/mean_wave_rows.h)
// against the element matrices they stand for: on each of a row's cells, with velocities and a
// field drawn at random, the shares CellMatrixRow and CellSharesRow give each corner are half the
// sum over the cell's four triangles T of (h grad phi_k)^T W_T (sum_l h grad phi_l u_l), with
// W_T / h^2 = (1/24) (sum_k V_k V_k^T + S S^T) over T's vertices; GatherRow sums four shares.
#include "../../engine/src/fluid/mean_wave_rows.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace dlmfd::wave_rows {
namespace {

// Unit-square corners a, b, c, d (grid units) and the triangles T1..T4 of mean_wave_rows.h.
constexpr double kCornerX[4] = {0.0, 1.0, 1.0, 0.0};
constexpr double kCornerY[4] = {0.0, 0.0, 1.0, 1.0};
constexpr int kTriangles[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 1, 3}, {1, 2, 3}};

// The shares of corners a..d from the element matrices, triangle by triangle.
std::array<double, 4> ElementShares(const double vx[4], const double vy[4], const double f[4]) {
  std::array<double, 4> share{};
  for (const auto& t : kTriangles) {
    double gx[3], gy[3];  // h grad phi of each vertex on T (signed area in the denominator)
    for (int k = 0; k < 3; ++k) {
      const int p = t[k], q = t[(k + 1) % 3], r = t[(k + 2) % 3];
      const double twice_area = (kCornerX[q] - kCornerX[p]) * (kCornerY[r] - kCornerY[p]) -
                                (kCornerX[r] - kCornerX[p]) * (kCornerY[q] - kCornerY[p]);
      gx[k] = (kCornerY[q] - kCornerY[r]) / twice_area;
      gy[k] = (kCornerX[r] - kCornerX[q]) / twice_area;
    }
    double w11 = 0.0, w12 = 0.0, w22 = 0.0, sx = 0.0, sy = 0.0, ux = 0.0, uy = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double x = vx[t[k]], y = vy[t[k]];
      w11 += x * x;
      w12 += x * y;
      w22 += y * y;
      sx += x;
      sy += y;
      ux += gx[k] * f[t[k]];
      uy += gy[k] * f[t[k]];
    }
    w11 = (w11 + sx * sx) / 24.0;
    w12 = (w12 + sx * sy) / 24.0;
    w22 = (w22 + sy * sy) / 24.0;
    const double fx = w11 * ux + w12 * uy, fy = w12 * ux + w22 * uy;
    for (int k = 0; k < 3; ++k) share[t[k]] += 0.5 * (gx[k] * fx + gy[k] * fy);
  }
  return share;
}

TEST(MeanWaveRows, SharesAreTheMeanOfTheFourTrianglesElementMatrices) {
  constexpr int kCells = 11;  // not a multiple of the vector width: the loops' tails run too
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> draw(-1.0, 1.0);
  std::vector<double> x0(kCells + 1), x1(kCells + 1), y0(kCells + 1), y1(kCells + 1);
  std::vector<double> f0(kCells + 1), f1(kCells + 1);
  for (auto* row : {&x0, &x1, &y0, &y1, &f0, &f1})
    for (double& value : *row) value = draw(rng);
  std::vector<double> m[6], s[4];
  for (auto& row : m) row.assign(kCells, 0.0);
  for (auto& row : s) row.assign(kCells, 0.0);
  double* const m_out[6] = {m[0].data(), m[1].data(), m[2].data(),
                            m[3].data(), m[4].data(), m[5].data()};
  const double* const m_in[6] = {m[0].data(), m[1].data(), m[2].data(),
                                 m[3].data(), m[4].data(), m[5].data()};
  double* const s_out[4] = {s[0].data(), s[1].data(), s[2].data(), s[3].data()};
  CellMatrixRow(kCells, x0.data(), x1.data(), y0.data(), y1.data(), m_out);
  CellSharesRow(kCells, m_in, f0.data(), f1.data(), s_out);
  for (int ci = 0; ci < kCells; ++ci) {
    const double vx[4] = {x0[ci], x0[ci + 1], x1[ci + 1], x1[ci]};
    const double vy[4] = {y0[ci], y0[ci + 1], y1[ci + 1], y1[ci]};
    const double f[4] = {f0[ci], f0[ci + 1], f1[ci + 1], f1[ci]};
    const std::array<double, 4> expected = ElementShares(vx, vy, f);
    for (int k = 0; k < 4; ++k) {
      // Sums of a few dozen terms of size <= 1: round-off of 1e-15 each.
      EXPECT_NEAR(s[k][ci], expected[k], 1e-13) << "cell " << ci << " corner " << k;
    }
  }
  std::vector<double> out(kCells);
  GatherRow(kCells, s[0].data(), s[1].data(), s[2].data(), s[3].data(), out.data());
  for (int ci = 0; ci < kCells; ++ci)
    EXPECT_DOUBLE_EQ(out[ci], s[0][ci] + s[1][ci] + s[2][ci] + s[3][ci]);
}

}  // namespace
}  // namespace dlmfd::wave_rows
