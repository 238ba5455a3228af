// Step (33) with no-slip walls all round, against a manufactured solution: the generalized Stokes
// problem of the step,
//   (rho/dt) u - nu Lap u + grad p = f in the unit square,  div u = 0,  u = 0 on the walls,
// with rho/dt = 1, nu = 1 and the smooth solenoidal field of the stream function
// psi = sin^2(pi x) sin^2(pi y) / pi (u = psi_y, v = -psi_x, zero on every wall, non-zero shear
// at the walls) and p = cos(pi x) cos(pi y) (mean-free); f follows, integrated against the test
// functions by the lumped mass (an O(h^2) load, consistent with the lumped mass of the step). The
// solve is StokesSolver itself from u^n = 0 with the load as its dual forcing, to tolerance 1e-10.
//
// What it separates (issue 13 point 4): the walls, the wall rows of B and B^T and the Neumann
// pressure at walls, from the lid corners of the driven cavity. The cavity's first-order error was
// at its corners (the lid leaked through the side walls: boundary_data.h); with smooth data the
// walls converge at second order. Measured (this test's output; docs/evidence/validation.md, "Fluid
// steps: convergence"), 16 / 32 / 64 / 128 cells:
//   velocity, max over the nodes    1.23e-2  3.08e-3  7.72e-4  1.93e-4   orders 2.00 2.00 2.00
//   pressure, L2 (M_p)              1.15e-1  3.28e-2  1.07e-2  3.68e-3   orders 1.81 1.61 1.54
//   pressure, max over the nodes    3.55e-1  1.29e-1  5.77e-2  2.72e-2   orders 1.45 1.17 1.08
// The pressure's largest error sits at the corner nodes (interior max 9.1e-2 -> 8.1e-3); its L2
// order falls towards about 3/2, above the order 1 the P1-iso-P2 / P1 theory guarantees.
// Asserted on every pair: the velocity order within 2 +/- 0.3
// (it separates second order from first), the pressure L2 order >= 1.3 (below the 1.54 the
// finest pair shows, above first order).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/core/params.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/fluid/stokes_solver.h"
#include "dlmfd/mesh/fem_operators.h"

namespace dlmfd {
namespace {

constexpr double kNu = 1.0;
constexpr double kVelocityOrderBand = 0.3;  // see the header
constexpr double kPressureOrderMin = 1.3;

// The exact fields (psi = sin^2(pi x) sin^2(pi y) / pi).
double ExactU(double x, double y) {
  return 2.0 * std::pow(std::sin(kPi * x), 2) * std::sin(kPi * y) * std::cos(kPi * y);
}
double ExactV(double x, double y) { return -ExactU(y, x); }
double ExactP(double x, double y) { return std::cos(kPi * x) * std::cos(kPi * y); }
// u - nu Lap u of the x component (rho/dt = 1): u = sin^2(pi x) sin(2 pi y), so
// Lap u = 2 pi^2 cos(2 pi x) sin(2 pi y) - 4 pi^2 sin^2(pi x) sin(2 pi y).
double MomentumX(double x, double y) {
  const double s2 = std::pow(std::sin(kPi * x), 2), t = std::sin(2.0 * kPi * y);
  const double lap = 2.0 * kPi * kPi * std::cos(2.0 * kPi * x) * t - 4.0 * kPi * kPi * s2 * t;
  return s2 * t - kNu * lap;
}
// f = u - nu Lap u + grad p; v(x, y) = -u(y, x), so its part is -MomentumX(y, x).
double ForceX(double x, double y) {
  return MomentumX(x, y) - kPi * std::sin(kPi * x) * std::cos(kPi * y);
}
double ForceY(double x, double y) {
  return -MomentumX(y, x) - kPi * std::cos(kPi * x) * std::sin(kPi * y);
}

struct Errors {
  double u_max = 0.0, p_max = 0.0, p_l2 = 0.0, p_interior = 0.0;
  int iterations = 0;
};

Errors Solve(int cells) {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(1.0, 1.0);
  p.domain.h = 1.0 / cells;
  p.fluid.density = 1.0;
  p.fluid.viscosity = kNu;
  p.fluid.solvent_ratio = 1.0;
  p.solvers.stokes_tolerance = 1e-10;
  p.solvers.stokes_max_iterations = 500;
  const Grid g = p.domain.VelocityGrid();
  const Grid pg = g.Coarse();
  const BoundaryData data(g, p.domain);
  StokesSolver stokes(g, p.domain, p.fluid, /*alpha=*/1.0, p.solvers, data);

  const BoundaryTopology topo = BoundaryTopology::ForVelocity(p.domain);
  std::vector<double> mass(g.NodeCount());
  LumpedMassDiagonal(g, topo, mass.data());
  std::vector<double> fx(g.NodeCount()), fy(g.NodeCount());
  std::vector<double> u(g.NodeCount(), 0.0), v(g.NodeCount(), 0.0), pr(pg.NodeCount(), 0.0);
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const std::size_t k = g.Index(i, j);
      fx[k] = mass[k] * ForceX(g.X(i), g.Y(j));
      fy[k] = mass[k] * ForceY(g.X(i), g.Y(j));
    }
  }
  const StokesReport report =
      stokes.Solve(/*dt=*/1.0, fx.data(), fy.data(), u.data(), v.data(), pr.data());
  Errors e;
  e.iterations = report.iterations;
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const std::size_t k = g.Index(i, j);
      e.u_max = std::max(e.u_max,
                         std::hypot(u[k] - ExactU(g.X(i), g.Y(j)), v[k] - ExactV(g.X(i), g.Y(j))));
    }
  }
  // Pressure up to its (M_p-weighted) mean: the exact one's discrete mean is O(h^2), not zero.
  const BoundaryTopology ptopo = BoundaryTopology::ForPressure(p.domain);
  std::vector<double> pmass(pg.NodeCount());
  LumpedMassDiagonal(pg, ptopo, pmass.data());
  double mean = 0.0, area = 0.0;
  for (int j = 0; j <= pg.ny; ++j) {
    for (int i = 0; i <= pg.nx; ++i) {
      const std::size_t k = pg.Index(i, j);
      mean += pmass[k] * (pr[k] - ExactP(pg.X(i), pg.Y(j)));
      area += pmass[k];
    }
  }
  mean /= area;
  for (int j = 0; j <= pg.ny; ++j) {
    for (int i = 0; i <= pg.nx; ++i) {
      const std::size_t k = pg.Index(i, j);
      const double d = std::abs(pr[k] - ExactP(pg.X(i), pg.Y(j)) - mean);
      e.p_max = std::max(e.p_max, d);
      e.p_l2 += pmass[k] * d * d;
      if (i > 0 && j > 0 && i < pg.nx && j < pg.ny) e.p_interior = std::max(e.p_interior, d);
    }
  }
  e.p_l2 = std::sqrt(e.p_l2);
  std::printf(
      "walls MMS %3d cells: |u - u_exact|_max %.4e  |p - p_exact|_max %.4e  L2 %.4e  interior %.4e "
      "(%d Uzawa)\n",
      cells, e.u_max, e.p_max, e.p_l2, e.p_interior, e.iterations);
  return e;
}

TEST(StokesWallsConvergence, ManufacturedSolutionWithWallsConvergesAtSecondOrder) {
  std::vector<Errors> e;
  for (int cells : {16, 32, 64, 128}) e.push_back(Solve(cells));
  for (std::size_t k = 1; k < e.size(); ++k) {
    const double ou = std::log2(e[k - 1].u_max / e[k].u_max);
    const double op = std::log2(e[k - 1].p_l2 / e[k].p_l2);
    std::printf("observed orders %zu: u max %.3f  p L2 %.3f  p max %.3f\n", k, ou, op,
                std::log2(e[k - 1].p_max / e[k].p_max));
    EXPECT_NEAR(ou, 2.0, kVelocityOrderBand) << k;
    EXPECT_GE(op, kPressureOrderMin) << k;
  }
}

}  // namespace
}  // namespace dlmfd
