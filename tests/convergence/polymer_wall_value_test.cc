// The polymer's wall value at a fixed disk with cut cells (issue 33 point 3; docs/evidence/
// cut_cell_boundary.md, "The polymer's wall value"): on a no-slip wall at rest the steady
// Oldroyd-B liquid is in viscometric flow, grad u = gamma_dot t n^T, and L A + A L^T = (A - I) /
// lambda gives trA = 2 + 2 (lambda gamma_dot)^2 there (the paper's section 5.1).
// The case: cases/verification/couette_disk_oldroyd_b.toml (a disk of diameter 1 fixed in plane
// Couette flow, Wi = 0.5, cut cells) at R/h = 8 and 16. At 128 points x_b of the true circle,
// theta_k = 2 pi (k + 1/2) / 128: trA_h(x_b) the P1 interpolant of the nodal trA (the mean of the
// two triangulations' with domain.diagonals = "both"; the triangle holding x_b is cut, its nodes
// inside the disk carry the extension of the fluid's A), gamma_dot_h = (4 u_t(h) - u_t(2h)) / (2h)
// the one-sided quadratic along the normal through u_t(0) = 0 (u_t the P1 interpolant of t . u),
// and the residual r = trA_h - 2 - 2 (lambda gamma_dot_h)^2; e = its RMS over the points.
// Measured (bench/wall_value.py, the same estimators): e = 2.316 / 1.994 / 1.621 / 1.289 / 1.058 /
// 0.928 at R/h = 4 / 8 / 16 / 32 / 64 / 128, observed orders 0.22 / 0.30 / 0.33 / 0.28 / 0.19: the
// wall value is met at an order of about 0.3, not 2, and the largest |r| does not fall (4.1-5.8).
// The liquid's trA at a fixed distance s from the wall converges (at the top of the disk, s = R/32:
// 9.00 / 9.04 / 9.01 at R/h = 32 / 64 / 128), but it rises to the wall value in a layer that does
// not thin with the grid, ever more steeply towards the wall (the wall value less trA: 6.2, 4.1,
// 2.8, 2.3 at s = R/16, R/32, R/64, R/128 on R/h = 128), and the wall shear rate in it keeps
// growing (4.51 / 4.58 / 4.65 / 4.71 at the top at R/h = 16 / 32 / 64 / 128), so the interpolant
// at the wall lags (docs/evidence/cut_cell_boundary.md, "The polymer's wall value", has the
// causes measured and ruled out). Test: the order of e from R/h = 8 to 16 is at least 0.15, the
// study's 0.30 there less the spread of its five orders (0.19-0.33: 0.14), rounded down.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../../engine/src/mesh/point_location.h"
#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

constexpr int kPoints = 128;

// The P1 interpolant of the nodal field f at (x, y): on the SW-NE triangle holding the point, or
// the mean of the SW-NE and NW-SE triangles' (the kernels of the coupling operator,
// mesh/point_location.h).
double P1(const Grid& g, const DomainParams& d, const std::vector<double>& f, double x, double y,
          bool both) {
  int side = -1;
  double value = 0.0;
  if (both) {
    kernels::MeanP1Stencil m;
    EXPECT_TRUE(kernels::LocatePointMean(g, d.PeriodicX(), d.PeriodicY(), x, y, &m, &side));
    for (int q = 0; q < 4; ++q) value += m.weight[q] * f[g.Index(m.i[q], m.j[q])];
  } else {
    kernels::P1Stencil m;
    EXPECT_TRUE(kernels::LocatePoint(g, d.PeriodicX(), d.PeriodicY(), x, y, &m, &side));
    for (int q = 0; q < 3; ++q) value += m.weight[q] * f[g.Index(m.i[q], m.j[q])];
  }
  EXPECT_EQ(side, -1) << "(" << x << ", " << y << ") beyond side " << side;
  return value;
}

// The RMS of r = trA_h - 2 - 2 (lambda gamma_dot_h)^2 over the points (header) at R/h.
double WallValueResidual(int r_over_h) {
  const double radius = 0.5;
  Params params = LoadSceneFile(
      std::string(DLMFD_SOURCE_DIR) + "/cases/verification/couette_disk_oldroyd_b.toml",
      {{"domain.h", std::to_string(radius / r_over_h)}, {"output.particles_every", "0"}});
  params.threads = 1;
  EXPECT_DOUBLE_EQ(params.particles.at(0).diameter, 2.0 * radius);
  Simulation sim(params);
  sim.Run();
  const Grid& g = sim.grid();
  const FlowState& s = sim.state();
  std::vector<double> tra(s.a11.size());
  for (std::size_t k = 0; k < tra.size(); ++k) tra[k] = s.a11[k] + s.a22[k];
  const bool both = params.domain.diagonals == MeshDiagonals::kBoth;
  const double lambda = params.fluid.relaxation_time;
  const Vec2 c = params.particles[0].center;
  auto tangential = [&](const Vec2& q, const Vec2& t) {
    return t.x() * P1(g, params.domain, s.u, q.x(), q.y(), both) +
           t.y() * P1(g, params.domain, s.v, q.x(), q.y(), both);
  };
  double sum = 0.0;
  for (int k = 0; k < kPoints; ++k) {
    const double theta = 2.0 * M_PI * (k + 0.5) / kPoints;
    const Vec2 n(std::cos(theta), std::sin(theta)), t(-n.y(), n.x());
    const Vec2 xb = c + radius * n;
    const double gamma =
        (4.0 * tangential(xb + g.h * n, t) - tangential(xb + 2.0 * g.h * n, t)) / (2.0 * g.h);
    const double r = P1(g, params.domain, tra, xb.x(), xb.y(), both) - 2.0 -
                     2.0 * (lambda * gamma) * (lambda * gamma);
    EXPECT_TRUE(std::isfinite(r)) << "theta = " << theta;
    sum += r * r;
  }
  return std::sqrt(sum / kPoints);
}

TEST(PolymerWallValue, CutCellsMeetTheViscometricWallValueAtTheStudiedOrder) {
  const double coarse = WallValueResidual(8), fine = WallValueResidual(16);
  const double order = std::log2(coarse / fine);
  std::printf(
      "RMS residual of trA = 2 + 2 (lambda gamma_dot)^2: %.4f (R/h = 8), %.4f (16), order %.3f\n",
      coarse, fine, order);
  EXPECT_GE(order, 0.15);
}

}  // namespace
}  // namespace dlmfd
