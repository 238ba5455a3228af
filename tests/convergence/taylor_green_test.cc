// Convergence of the fluid steps (33)-(34) on an exact unsteady Navier-Stokes solution: the
// decaying Taylor-Green vortex in the doubly periodic box [0, 2 pi]^2 (k = 1, nu = eta / rho),
//   u = -cos(x) sin(y) F(t),  v = sin(x) cos(y) F(t),  F = exp(-2 nu t),
//   p = -(rho / 4) (cos 2x + cos 2y) F(t)^2.
// Each grid runs the whole Simulation (Stokes by Uzawa-PCG, then the least-squares CG or the
// wave-like advection, alpha = beta = 1/2) from the exact field at t = 0 to t = 1/2 and compares
// nodal values with the exact ones at t = 1/2.
//
// What to expect: P1-iso-P2 velocity is second order in space (L2 and, on the uniform mesh, at the
// nodes); the Marchuk-Yanenko splitting is first order in time. With dt = 0.25 h^2 both parts of
// the velocity error scale as h^2, so the observed order of u is 2. The pressure is P1 on the 2h
// mesh (second order at its nodes on a uniform mesh) and lags the convection it balances by one
// step (O(dt) = O(h^2)), so its expected order is also 2. Measured (docs/evidence/validation.md):
// pressure 2.01-2.04 on both pairs; velocity 2.4-2.6 between 16 and 32 cells and 2.25-2.43 between
// 32 and 64, falling towards 2 (on 16 cells the error is 7 % of the field: pre-asymptotic).
// Asserted: 2 +/- 0.5 on the finest pair, which separates second order from first or third, and
// >= 1.5 on the coarse pair (a lost order would show there too).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/simulation.h"

namespace dlmfd {
namespace {

constexpr double kViscosity = 0.05;  // rho = 1: nu = 0.05
constexpr double kEnd = 0.5;

struct TaylorGreenErrors {
  double h, dt;
  double u_l2, u_max, p_l2, p_max;
};

Params TaylorGreenParams(int cells, AdvectionScheme scheme) {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(2.0 * kPi, 2.0 * kPi);
  p.domain.h = 2.0 * kPi / cells;
  for (BoundarySide& s : p.domain.sides) s.type = SideType::kPeriodic;
  p.fluid.density = 1.0;
  p.fluid.viscosity = kViscosity;
  p.fluid.solvent_ratio = 1.0;
  const double h = p.domain.h;
  const long steps = std::lround(std::ceil(kEnd / (0.25 * h * h)));
  p.time.dt = kEnd / static_cast<double>(steps);
  p.time.end = kEnd;
  p.splitting.alpha = 0.5;
  p.splitting.beta = 0.5;
  p.splitting.advection = scheme;
  // Solver errors far below the discretisation error: LS-CG at 1e-4 leaves about 2e-5 of the
  // step's change u - u* (method notes 1, section 4), i.e. about 1e-5 summed over the steps of the
  // finest grid, against a velocity error of 2e-3 there.
  p.solvers.stokes_tolerance = 1e-8;
  p.solvers.advection_tolerance = 1e-4;
  p.output.fields_every = 0.0;
  p.output.particles_every = 0.0;
  p.output.checkpoint_every = 0.0;
  return p;
}

TaylorGreenErrors RunTaylorGreen(int cells, AdvectionScheme scheme) {
  const Params params = TaylorGreenParams(cells, scheme);
  Simulation sim(params);
  const Grid& g = sim.grid();
  const Grid& pg = sim.pressure_grid();
  FlowState& s = sim.mutable_state();
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      s.u[g.Index(i, j)] = -std::cos(g.X(i)) * std::sin(g.Y(j));
      s.v[g.Index(i, j)] = std::sin(g.X(i)) * std::cos(g.Y(j));
    }
  }
  const long steps = sim.TotalSteps();
  for (long n = 0; n < steps; ++n) sim.Step();
  const FlowState& end = sim.state();
  const double t = end.time;
  const double f = std::exp(-2.0 * kViscosity * t);

  TaylorGreenErrors e{g.h, params.time.dt, 0.0, 0.0, 0.0, 0.0};
  // Distinct nodes only (the last row and column repeat the first).
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double du = end.u[g.Index(i, j)] + std::cos(g.X(i)) * std::sin(g.Y(j)) * f;
      const double dv = end.v[g.Index(i, j)] - std::sin(g.X(i)) * std::cos(g.Y(j)) * f;
      e.u_l2 += g.h * g.h * (du * du + dv * dv);
      e.u_max = std::max({e.u_max, std::abs(du), std::abs(dv)});
    }
  }
  e.u_l2 = std::sqrt(e.u_l2);
  // Pressure up to a constant: both the exact and the computed one have zero mean on the box.
  double mean = 0.0;
  for (int j = 0; j < pg.ny; ++j) {
    for (int i = 0; i < pg.nx; ++i) mean += end.p[pg.Index(i, j)];
  }
  mean /= static_cast<double>(pg.nx) * pg.ny;
  for (int j = 0; j < pg.ny; ++j) {
    for (int i = 0; i < pg.nx; ++i) {
      const double exact = -0.25 * (std::cos(2.0 * pg.X(i)) + std::cos(2.0 * pg.Y(j))) * f * f;
      const double dp = end.p[pg.Index(i, j)] - mean - exact;
      e.p_l2 += pg.h * pg.h * dp * dp;
      e.p_max = std::max(e.p_max, std::abs(dp));
    }
  }
  e.p_l2 = std::sqrt(e.p_l2);
  return e;
}

double TaylorGreenOrder(double e_coarse, double e_fine, double h_coarse, double h_fine) {
  return std::log(e_coarse / e_fine) / std::log(h_coarse / h_fine);
}

void CheckOrders(AdvectionScheme scheme, const char* name) {
  const int cells[] = {16, 32, 64};
  std::vector<TaylorGreenErrors> e;
  for (int c : cells) e.push_back(RunTaylorGreen(c, scheme));
  std::printf(
      "Taylor-Green, %s advection, nu = %.2f, t = %.1f, dt = 0.25 h^2 (rounded to divide t)\n",
      name, kViscosity, kEnd);
  std::printf("%6s %9s %9s %11s %11s %11s %11s | %6s %6s %6s %6s\n", "cells", "h", "dt", "u L2",
              "u max", "p L2", "p max", "o uL2", "o umax", "o pL2", "o pmax");
  for (std::size_t k = 0; k < e.size(); ++k) {
    std::printf("%6d %9.3e %9.2e %11.4e %11.4e %11.4e %11.4e", cells[k], e[k].h, e[k].dt, e[k].u_l2,
                e[k].u_max, e[k].p_l2, e[k].p_max);
    if (k == 0) {
      std::printf(" |\n");
      continue;
    }
    const TaylorGreenErrors& a = e[k - 1];
    const TaylorGreenErrors& b = e[k];
    const double orders[4] = {
        TaylorGreenOrder(a.u_l2, b.u_l2, a.h, b.h), TaylorGreenOrder(a.u_max, b.u_max, a.h, b.h),
        TaylorGreenOrder(a.p_l2, b.p_l2, a.h, b.h), TaylorGreenOrder(a.p_max, b.p_max, a.h, b.h)};
    std::printf(" | %6.2f %6.2f %6.2f %6.2f\n", orders[0], orders[1], orders[2], orders[3]);
    const char* labels[4] = {"u L2", "u max", "p L2", "p max"};
    for (int q = 0; q < 4; ++q) {
      if (k + 1 == e.size()) {
        EXPECT_NEAR(orders[q], 2.0, 0.5) << name << " " << labels[q] << " between " << cells[k - 1]
                                         << " and " << cells[k] << " cells";
      } else {
        EXPECT_GE(orders[q], 1.5) << name << " " << labels[q] << " between " << cells[k - 1]
                                  << " and " << cells[k] << " cells";
      }
    }
  }
}

TEST(TaylorGreen, SecondOrderWithLeastSquaresAdvection) {
  CheckOrders(AdvectionScheme::kLeastSquares, "least-squares");
}

TEST(TaylorGreen, SecondOrderWithWaveAdvection) { CheckOrders(AdvectionScheme::kWave, "wave"); }

}  // namespace
}  // namespace dlmfd
