// Step (33): discrete divergence after the solve, exact steady solutions, and agreement with a
// direct sparse solve of the assembled KKT system.
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <cmath>
#include <vector>

#include "../support/max_norms.h"
#include "../support/studied_numerics.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/simulation.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/fluid/stokes_solver.h"
#include "dlmfd/mesh/fem_operators.h"

namespace dlmfd {
namespace {

BoundarySide Wall() { return BoundarySide{}; }
BoundarySide Periodic() {
  BoundarySide s;
  s.type = SideType::kPeriodic;
  return s;
}
BoundarySide Outflow() {
  BoundarySide s;
  s.type = SideType::kOutflow;
  return s;
}
BoundarySide Uniform(double ux, double uy) {
  BoundarySide s;
  s.type = SideType::kVelocity;
  s.value = Vec2(ux, uy);
  return s;
}
BoundarySide Poiseuille(double mx, double my) {
  BoundarySide s;
  s.type = SideType::kVelocity;
  s.profile = Profile::kPoiseuille;
  s.max = Vec2(mx, my);
  return s;
}

Params MakeParams(double width, double height, double h, BoundarySide left, BoundarySide right,
                  BoundarySide bottom, BoundarySide top) {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(width, height);
  p.domain.h = h;
  p.domain.sides[0] = left;
  p.domain.sides[1] = right;
  p.domain.sides[2] = bottom;
  p.domain.sides[3] = top;
  p.fluid.density = 1.0;
  p.fluid.viscosity = 0.05;
  p.fluid.solvent_ratio = 1.0;
  p.time.dt = 0.01;
  p.time.end = 0.1;
  p.output.fields_every = 0.0;
  return p;
}

// A smooth, non-solenoidal field to start from (not a solution of anything).
void FillSmooth(const Grid& g, std::vector<double>& u, std::vector<double>& v) {
  u.assign(g.NodeCount(), 0.0);
  v.assign(g.NodeCount(), 0.0);
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const double x = g.X(i), y = g.Y(j);
      u[g.Index(i, j)] = std::sin(3.0 * x + 1.0) * std::cos(2.0 * y) + 0.3;
      v[g.Index(i, j)] = std::cos(x - 2.0 * y) * 0.7;
    }
  }
}

using testing::MaxAbs;
using testing::MaxAbsDiff;

TEST(StokesSolver, DivergenceBelowToleranceAfterSolve) {
  // Lid-driven box, and inflow with an outflow side: the true residual sqrt(Bu . P^-1 Bu),
  // recomputed from scratch, is below tol * ref, the stopping rule's own scale.
  const std::vector<Params> cases = {
      MakeParams(1.0, 1.0, 1.0 / 16, Wall(), Wall(), Wall(), Uniform(1.0, 0.0)),
      MakeParams(1.0, 2.0, 1.0 / 16, Wall(), Wall(), Poiseuille(0.0, 1.0), Outflow()),
      MakeParams(1.0, 1.0, 1.0 / 16, Periodic(), Periodic(), Uniform(0.2, 0.5), Outflow())};
  for (const Params& p : cases) {
    const Grid g = p.domain.VelocityGrid();
    BoundaryData data(g, p.domain);
    StokesSolver stokes(g, p.domain, p.fluid, 1.0, p.solvers, data);
    std::vector<double> u, v, pr(g.Coarse().NodeCount(), 0.0);
    FillSmooth(g, u, v);
    stokes.velocity_nodes().SyncPeriodic(u.data());
    stokes.velocity_nodes().SyncPeriodic(v.data());
    const double before = stokes.ResidualNorm(p.time.dt, u.data(), v.data());
    const StokesReport r = stokes.Solve(p.time.dt, nullptr, nullptr, u.data(), v.data(), pr.data());
    const double after = stokes.ResidualNorm(p.time.dt, u.data(), v.data());
    EXPECT_GT(r.iterations, 0);
    EXPECT_LE(r.residual, p.solvers.stokes_tolerance);
    // Recomputed residual versus the recursive one: they differ by round-off only (1e-12 of ref).
    EXPECT_LE(after, p.solvers.stokes_tolerance * r.reference + 1e-12 * r.reference);
    EXPECT_GT(before, 1e3 * after);
    EXPECT_NEAR(stokes.DivergenceNorm(u.data(), v.data()), r.divergence,
                1e-14 + 1e-12 * r.divergence);
  }
}

// Plane Couette flow u = U y / H between a fixed and a moving wall, periodic in x. The nodal
// interpolant of a linear profile is exactly the P1 field, K u = 0 at interior rows (5-point
// Laplacian of a linear function), B u = int q du/dx = 0, N(u, u) = u G_x u = 0 and the wave
// stiffness K_V u = 0 (V = (u(y), 0) only weights x-differences, which vanish). So every substep
// leaves it unchanged up to round-off, for any splitting weights and both advection schemes.
TEST(Simulation, PlaneCouetteIsReproducedToRoundOff) {
  for (AdvectionScheme scheme : {AdvectionScheme::kLeastSquares, AdvectionScheme::kWave}) {
    Params p = MakeParams(1.0, 1.0, 1.0 / 16, Periodic(), Periodic(), Wall(), Uniform(1.5, 0.0));
    p.splitting.alpha = 0.5;
    p.splitting.beta = 0.5;
    p.splitting.advection = scheme;
    Simulation sim(p);
    const Grid& g = sim.grid();
    FlowState& s = sim.mutable_state();
    for (int j = 0; j <= g.ny; ++j) {
      for (int i = 0; i <= g.nx; ++i) s.u[g.Index(i, j)] = 1.5 * g.Y(j) / g.Height();
    }
    const std::vector<double> u0 = s.u;
    for (int n = 0; n < 10; ++n) sim.Step();
    EXPECT_LE(MaxAbsDiff(sim.state().u, u0), 1e-12 * 1.5);
    EXPECT_LE(MaxAbs(sim.state().v), 1e-12 * 1.5);
    EXPECT_LE(MaxAbs(sim.state().p), 1e-12);
  }
}

// Plane Poiseuille flow driven by a body force f between walls, periodic in x: u = f y (H - y) / (2
// eta). The 5-point stiffness of a quadratic is exact: K u = h^2 f / eta = M_l f / eta at interior
// rows, so the nodal parabola solves (33) exactly when all the viscosity is in (33), alpha = 1,
// beta = 0. With alpha < 1 it does not: the Marchuk-Yanenko steady state differs from the parabola
// by O(dt) (the splitting error, u^{n+1/4} = u + beta dt f / rho away from the walls), so it is not
// a test of round-off. N(u, u) = 0 and K_V u = 0 as for Couette flow.
TEST(Simulation, PlanePoiseuilleBodyForceIsReproducedToRoundOff) {
  for (AdvectionScheme scheme : {AdvectionScheme::kLeastSquares, AdvectionScheme::kWave}) {
    Params p = MakeParams(0.5, 1.0, 1.0 / 16, Periodic(), Periodic(), Wall(), Wall());
    p.splitting.alpha = 1.0;
    p.splitting.beta = 0.0;
    p.splitting.advection = scheme;
    p.fluid.body_force = Vec2(2.0, 0.0);
    Simulation sim(p);
    const Grid& g = sim.grid();
    FlowState& s = sim.mutable_state();
    const double eta = p.fluid.viscosity, f = 2.0, hh = g.Height();
    for (int j = 0; j <= g.ny; ++j) {
      for (int i = 0; i <= g.nx; ++i) s.u[g.Index(i, j)] = f * g.Y(j) * (hh - g.Y(j)) / (2 * eta);
    }
    const std::vector<double> u0 = s.u;
    const double umax = MaxAbs(u0);
    for (int n = 0; n < 10; ++n) sim.Step();
    EXPECT_LE(MaxAbsDiff(sim.state().u, u0), 1e-12 * umax);
    EXPECT_LE(MaxAbs(sim.state().v), 1e-12 * umax);
  }
}

// Inflow with a parabolic profile through the bottom, walls left and right, outflow at the top:
// v = 4 V x (W - x) / W^2, u = 0, p = (8 eta V / W^2)(H - y) (zero on the outflow side, where the
// do-nothing condition eta dv/dy - p = 0 holds). v is quadratic in x (K exact as above), p is
// linear and so exactly P1 on the 2h mesh, and B^T p = -(dp/dy) M_l holds row by row, natural top
// rows included (trapezoid mass h^2/2 there). Started from the exact pressure the Uzawa residual is
// round-off and the state is a fixed point of (33)-(34) with alpha = 1, beta = 0.
TEST(Simulation, InflowPoiseuilleWithOutflowIsReproducedToRoundOff) {
  for (AdvectionScheme scheme : {AdvectionScheme::kLeastSquares, AdvectionScheme::kWave}) {
    const double vmax = 0.8;
    Params p = MakeParams(1.0, 2.0, 1.0 / 16, Wall(), Wall(), Poiseuille(0.0, vmax), Outflow());
    p.splitting.alpha = 1.0;
    p.splitting.beta = 0.0;
    p.splitting.advection = scheme;
    Simulation sim(p);
    const Grid& g = sim.grid();
    const Grid& pg = sim.pressure_grid();
    FlowState& s = sim.mutable_state();
    const double eta = p.fluid.viscosity, w = g.Width(), hh = g.Height();
    for (int j = 0; j <= g.ny; ++j) {
      for (int i = 0; i <= g.nx; ++i)
        s.v[g.Index(i, j)] = 4 * vmax * g.X(i) * (w - g.X(i)) / (w * w);
    }
    for (int j = 0; j <= pg.ny; ++j) {
      for (int i = 0; i <= pg.nx; ++i)
        s.p[pg.Index(i, j)] = 8 * eta * vmax / (w * w) * (hh - pg.Y(j));
    }
    const std::vector<double> v0 = s.v, p0 = s.p;
    for (int n = 0; n < 10; ++n) sim.Step();
    EXPECT_LE(MaxAbsDiff(sim.state().v, v0), 1e-12 * vmax);
    EXPECT_LE(MaxAbs(sim.state().u), 1e-12 * vmax);
    EXPECT_LE(MaxAbsDiff(sim.state().p, p0), 1e-12 * MaxAbs(p0));
  }
}

// Uzawa/PCG against Eigen's SparseLU on the assembled KKT system
//   [A 0 -Bx^T 0; 0 A -By^T 0; Bx By 0 m; 0 0 m^T 0] (u, v, p, l) = (F - A_D u_D, -B_D u_D, 0)
// restricted to the unknown nodes (m = M_p weights fix the constant pressure when it is in the
// kernel).
// NOLINTNEXTLINE(readability-function-size): predates the limit; split it when you change it
void CompareWithDirectSolve(const Params& p) {
  const Grid g = p.domain.VelocityGrid(), pg = g.Coarse();
  const double rdt = p.fluid.density / p.time.dt,
               nu = p.splitting.alpha * p.fluid.NewtonianViscosity();
  BoundaryData data(g, p.domain);
  SolverParams tight = p.solvers;
  tight.stokes_tolerance = 1e-12;
  StokesSolver stokes(g, p.domain, p.fluid, p.splitting.alpha, tight, data);
  const BoundaryTopology vt = stokes.velocity_topology(), pt = stokes.pressure_topology();

  std::vector<double> u, v, pr(pg.NodeCount(), 0.0), fx(g.NodeCount()), fy(g.NodeCount());
  FillSmooth(g, u, v);
  stokes.velocity_nodes().SyncPeriodic(u.data());
  stokes.velocity_nodes().SyncPeriodic(v.data());
  for (std::size_t k = 0; k < fx.size(); ++k) {
    fx[k] = 0.01 * std::sin(0.1 * k);
    fy[k] = 0.02 * std::cos(0.3 * k);
  }
  std::vector<double> mass(g.NodeCount()), pmass(pg.NodeCount());
  LumpedMassDiagonal(g, vt, mass.data());
  LumpedMassDiagonal(pg, pt, pmass.data());

  // Numbering of unknowns.
  std::vector<int> vid(g.NodeCount(), -1), pid(pg.NodeCount(), -1);
  int nv = 0, np = 0;
  for (std::size_t k = 0; k < vid.size(); ++k)
    if (stokes.velocity_nodes().IsUnknown(k)) vid[k] = nv++;
  for (std::size_t k = 0; k < pid.size(); ++k)
    if (stokes.pressure_nodes().IsUnknown(k)) pid[k] = np++;
  const bool null_space = pt.HasNullSpace();
  const int n = 2 * nv + np + (null_space ? 1 : 0);

  std::vector<double> ud = u, vd = v;  // Dirichlet data at t^{n+1}
  data.Apply(ud.data(), vd.data());
  const Eigen::SparseMatrix<double> k_mat = AssembleStiffness(g, vt);
  const Eigen::SparseMatrix<double> bx = AssembleDivergenceX(g, pt),
                                    by = AssembleDivergenceY(g, pt);
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for (std::size_t k = 0; k < vid.size(); ++k) {
    if (vid[k] < 0) continue;
    rhs[vid[k]] = mass[k] * (rdt * u[k] + p.fluid.body_force.x()) + fx[k];
    rhs[nv + vid[k]] = mass[k] * (rdt * v[k] + p.fluid.body_force.y()) + fy[k];
    t.emplace_back(vid[k], vid[k], rdt * mass[k]);
    t.emplace_back(nv + vid[k], nv + vid[k], rdt * mass[k]);
  }
  for (int c = 0; c < k_mat.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(k_mat, c); it; ++it) {
      const int r = vid[it.row()];
      if (r < 0) continue;
      if (vid[it.col()] >= 0) {
        t.emplace_back(r, vid[it.col()], nu * it.value());
        t.emplace_back(nv + r, nv + vid[it.col()], nu * it.value());
      } else {
        rhs[r] -= nu * it.value() * ud[it.col()];
        rhs[nv + r] -= nu * it.value() * vd[it.col()];
      }
    }
  }
  for (int comp = 0; comp < 2; ++comp) {
    const Eigen::SparseMatrix<double>& b = comp == 0 ? bx : by;
    const std::vector<double>& dd = comp == 0 ? ud : vd;
    for (int c = 0; c < b.outerSize(); ++c) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(b, c); it; ++it) {
        const int r = pid[it.row()];
        if (r < 0) continue;
        const int col = vid[it.col()];
        if (col >= 0) {
          t.emplace_back(2 * nv + r, comp * nv + col, it.value());
          t.emplace_back(comp * nv + col, 2 * nv + r, -it.value());
        } else {
          rhs[2 * nv + r] -= it.value() * dd[it.col()];
        }
      }
    }
  }
  if (null_space) {
    for (std::size_t k = 0; k < pid.size(); ++k) {
      if (pid[k] < 0) continue;
      t.emplace_back(2 * nv + pid[k], n - 1, pmass[k]);
      t.emplace_back(n - 1, 2 * nv + pid[k], pmass[k]);
    }
  }
  Eigen::SparseMatrix<double> kkt(n, n);
  kkt.setFromTriplets(t.begin(), t.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(kkt);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Eigen::VectorXd x = lu.solve(rhs);

  const StokesReport r =
      stokes.Solve(p.time.dt, fx.data(), fy.data(), u.data(), v.data(), pr.data());
  EXPECT_GT(r.iterations, 3);
  double du = 0.0, umax = 0.0, dp = 0.0, pmax = 0.0;
  // Periodic duplicates are compared through their first node.
  const std::vector<double>& vdistinct = stokes.velocity_nodes().distinct();
  const std::vector<double>& pdistinct = stokes.pressure_nodes().distinct();
  for (std::size_t k = 0; k < vid.size(); ++k) {
    if (vdistinct[k] == 0.0) continue;
    umax = std::max({umax, std::abs(u[k]), std::abs(v[k])});
    if (vid[k] < 0) {
      du = std::max({du, std::abs(u[k] - ud[k]), std::abs(v[k] - vd[k])});
    } else {
      du = std::max({du, std::abs(u[k] - x[vid[k]]), std::abs(v[k] - x[nv + vid[k]])});
    }
  }
  for (std::size_t k = 0; k < pid.size(); ++k) {
    if (pdistinct[k] == 0.0) continue;
    const double exact = pid[k] < 0 ? 0.0 : x[2 * nv + pid[k]];
    pmax = std::max(pmax, std::abs(exact));
    dp = std::max(dp, std::abs(pr[k] - exact));
  }
  EXPECT_LE(du, 1e-8 * umax);
  EXPECT_LE(dp, 1e-8 * pmax);
}

TEST(StokesSolver, MatchesDirectKktSolveLidDriven) {
  Params p = MakeParams(1.0, 1.0, 1.0 / 8, Wall(), Wall(), Wall(), Uniform(1.0, 0.0));
  p.splitting.alpha = 0.5;
  p.fluid.body_force = Vec2(0.3, -0.2);
  CompareWithDirectSolve(p);
}

TEST(StokesSolver, MatchesDirectKktSolvePeriodicWithOutflow) {
  Params p = MakeParams(1.0, 1.0, 1.0 / 8, Periodic(), Periodic(), Uniform(0.2, 0.7), Outflow());
  CompareWithDirectSolve(p);
}

TEST(StokesSolver, MatchesDirectKktSolveInflowOutflow) {
  Params p = MakeParams(1.0, 1.5, 1.0 / 8, Wall(), Outflow(), Poiseuille(0.0, 1.0), Wall());
  CompareWithDirectSolve(p);
}

TEST(Simulation, RejectsWhatTheEngineCannotRun) {
  Params p = MakeParams(1.0, 1.0, 1.0 / 8, Wall(), Wall(), Wall(), Wall());
  p.splitting.alpha = 0.4;
  p.splitting.beta = 0.4;
  EXPECT_THROW(Simulation{p}, InvalidParameter);
}

}  // namespace
}  // namespace dlmfd
