// Step (34): the least-squares CG and the wave-like scheme (on the mesh's diagonals and on both)
// leave a uniform flow unchanged; both schemes on both diagonals are mirror-symmetric; the LS
// gradient is the adjoint of the linearised residual; LS-CG reaches its tolerance; the wave scheme
// does not amplify perturbations at Courant number 0.7.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "../support/mirror_images.h"
#include "../support/studied_numerics.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/simulation.h"
#include "dlmfd/fluid/advection_least_squares.h"
#include "dlmfd/fluid/advection_wave.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/fluid/velocity_advection.h"

namespace dlmfd {
namespace {

BoundarySide AdvectionSide(SideType type, double ux = 0.0, double uy = 0.0) {
  BoundarySide s;
  s.type = type;
  s.value = Vec2(ux, uy);
  return s;
}

Params MakeParams(double h, BoundarySide left, BoundarySide right, BoundarySide bottom,
                  BoundarySide top) {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(1.0, 1.0);
  p.domain.h = h;
  p.domain.sides[0] = left;
  p.domain.sides[1] = right;
  p.domain.sides[2] = bottom;
  p.domain.sides[3] = top;
  p.fluid.viscosity = 0.02;
  p.fluid.solvent_ratio = 1.0;
  p.time.dt = 0.02;
  p.output.fields_every = 0.0;
  return p;
}

Grid GridOf(const Params& p) {
  return Grid{static_cast<int>(std::lround(1.0 / p.domain.h)),
              static_cast<int>(std::lround(1.0 / p.domain.h)), p.domain.h, 0.0, 0.0};
}

std::vector<Params> UniformFlowCases() {
  const Vec2 w(0.7, 0.4);
  return {MakeParams(1.0 / 16, AdvectionSide(SideType::kVelocity, w.x(), w.y()),
                     AdvectionSide(SideType::kVelocity, w.x(), w.y()),
                     AdvectionSide(SideType::kVelocity, w.x(), w.y()),
                     AdvectionSide(SideType::kVelocity, w.x(), w.y())),
          MakeParams(
              1.0 / 16, AdvectionSide(SideType::kPeriodic), AdvectionSide(SideType::kPeriodic),
              AdvectionSide(SideType::kVelocity, w.x(), w.y()), AdvectionSide(SideType::kOutflow)),
          MakeParams(1.0 / 16, AdvectionSide(SideType::kVelocity, w.x(), w.y()),
                     AdvectionSide(SideType::kOutflow), AdvectionSide(SideType::kPeriodic),
                     AdvectionSide(SideType::kPeriodic))};
}

TEST(Advection, UniformFlowIsUnchangedByBothSchemes) {
  for (const Params& p : UniformFlowCases()) {
    const Grid g = GridOf(p);
    BoundaryData data(g, p.domain);
    AdvectionLeastSquares ls(g, p.domain, p.fluid, 0.5, SteadyCorrection::kNone, p.solvers, data);
    AdvectionWave wave(g, p.domain, p.fluid, 0.5, SteadyCorrection::kNone, p.solvers, data);
    DomainParams both_domain = p.domain;
    both_domain.diagonals = MeshDiagonals::kBoth;
    AdvectionWave both(g, both_domain, p.fluid, 0.5, SteadyCorrection::kNone, p.solvers, data);
    for (int scheme = 0; scheme < 3; ++scheme) {
      std::vector<double> u(g.NodeCount(), 0.7), v(g.NodeCount(), 0.4);
      const AdvectionReport r = scheme == 0   ? ls.Solve(p.time.dt, u.data(), v.data())
                                : scheme == 1 ? wave.Solve(p.time.dt, u.data(), v.data())
                                              : both.Solve(p.time.dt, u.data(), v.data());
      if (scheme == 0) {
        EXPECT_EQ(r.iterations, 0);  // T(u*) = 0 exactly: nothing to minimise
      }
      double change = 0.0;
      for (std::size_t k = 0; k < u.size(); ++k) {
        change = std::max({change, std::abs(u[k] - 0.7), std::abs(v[k] - 0.4)});
      }
      EXPECT_LE(change, 1e-13) << "scheme " << scheme;
    }
  }
}

// domain.diagonals = "both": step (34) on the mean of the two diagonals of each square, with either
// scheme, commutes with the mirror images x -> 1 - x and y -> 1 - y of a closed box (to round-off),
// where the mesh's own diagonal does not (the lift bias of docs/evidence/particle_boundary.md (e)).
// The field: no-slip walls, u = sin(pi x) sin(2 pi y) (1 + x), v = sin(2 pi x) sin(pi y) (1 + y^2),
// the Taylor term removed (steady_correction = "taylor"), no diffusion (beta = 0).
double StepMirrorMismatch(AdvectionScheme scheme, MeshDiagonals diagonals, bool mirror_x) {
  const BoundarySide wall = AdvectionSide(SideType::kWall);
  Params p = MakeParams(1.0 / 16, wall, wall, wall, wall);
  p.time.dt = 0.05;
  p.domain.diagonals = diagonals;
  p.splitting.advection = scheme;
  p.splitting.alpha = 1.0;
  p.splitting.beta = 0.0;
  p.splitting.steady_correction = SteadyCorrection::kTaylor;
  p.solvers.advection_tolerance = 1e-6;
  p.solvers.advection_max_iterations = 1000;
  const Grid g = GridOf(p);
  BoundaryData data(g, p.domain);
  const std::unique_ptr<VelocityAdvection> step = MakeVelocityAdvection(g, p, data);
  const int n = g.nx;
  std::vector<double> u(g.NodeCount()), v(g.NodeCount()), um, vm;
  const double pi = std::acos(-1.0);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = i * g.h, y = j * g.h;
      u[g.Index(i, j)] = std::sin(pi * x) * std::sin(2 * pi * y) * (1 + x);
      v[g.Index(i, j)] = std::sin(2 * pi * x) * std::sin(pi * y) * (1 + y * y);
    }
  }
  testing::MirrorVelocity(g, mirror_x, u, v, um, vm);
  const int iterations = step->Solve(p.time.dt, u.data(), v.data()).iterations;
  const int mirrored_iterations = step->Solve(p.time.dt, um.data(), vm.data()).iterations;
  if (diagonals == MeshDiagonals::kBoth) {
    EXPECT_EQ(iterations, mirrored_iterations);
  }
  return testing::MirrorMismatch(g, mirror_x, u, v, um, vm);
}

TEST(Advection, TheMeanOverBothDiagonalsIsMirrorSymmetric) {
  for (AdvectionScheme scheme : {AdvectionScheme::kWave, AdvectionScheme::kLeastSquares}) {
    for (bool mirror_x : {true, false}) {
      const double both = StepMirrorMismatch(scheme, MeshDiagonals::kBoth, mirror_x);
      const double mesh = StepMirrorMismatch(scheme, MeshDiagonals::kSwNe, mirror_x);
      std::printf("%s, mirror %s: mismatch %.3g on both diagonals, %.3g on the mesh's\n",
                  scheme == AdvectionScheme::kWave ? "wave" : "least squares", mirror_x ? "x" : "y",
                  both, mesh);
      // Least squares: the CG's iterates commute with the mirror too, so round-off alone.
      EXPECT_LE(both, 1e-13);
      // The mesh's diagonal breaks the symmetry at the size of the step's second-order terms.
      EXPECT_GE(mesh, 1e-4);
    }
  }
}

// The wave step on both diagonals, gathered in one sweep, against its definition: with one
// sub-step (Courant number below solvers.wave_max_courant) and no diffusion the step is affine in
// the forms K_V and N(V, .), so on both diagonals it is the mean of the SW-NE mesh's step and the
// NW-SE mesh's, and the NW-SE mesh's step is the mirror image of the SW-NE step of the mirrored
// field (V = u is mirrored with it). Closed box and x-periodic channel, both mirrors, with and
// without the steady correction (linear in u_tt, theta mirror-invariant; where it removes the
// whole Taylor term K_V drops out, so without it K_V is checked everywhere). Round-off only.
double MeanStepMismatch(bool periodic_x, bool mirror_x, SteadyCorrection correction) {
  const BoundarySide wall = AdvectionSide(SideType::kWall);
  const BoundarySide side = periodic_x ? AdvectionSide(SideType::kPeriodic) : wall;
  Params p = MakeParams(1.0 / 16, side, side, wall, wall);
  p.time.dt = 0.01;  // Courant number below 0.35: one sub-step
  p.splitting.advection = AdvectionScheme::kWave;
  p.splitting.alpha = 1.0;
  p.splitting.beta = 0.0;
  p.splitting.steady_correction = correction;
  const Grid g = GridOf(p);
  BoundaryData data(g, p.domain);
  const std::unique_ptr<VelocityAdvection> mesh = MakeVelocityAdvection(g, p, data);
  p.domain.diagonals = MeshDiagonals::kBoth;
  const std::unique_ptr<VelocityAdvection> both = MakeVelocityAdvection(g, p, data);
  const double pi = std::acos(-1.0);
  std::vector<double> u(g.NodeCount()), v(g.NodeCount());
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const double x = i * g.h, y = j * g.h;
      const double wave_x = periodic_x ? std::sin(2 * pi * x + 0.3) : std::sin(pi * x) * (1 + x);
      u[g.Index(i, j)] = wave_x * std::sin(2 * pi * y);
      v[g.Index(i, j)] = (periodic_x ? std::cos(2 * pi * x) : std::sin(2 * pi * x)) *
                         std::sin(pi * y) * (1 + y * y);
    }
  }
  std::vector<double> um, vm, mean_u = u, mean_v = v, iu, iv;
  testing::MirrorVelocity(g, mirror_x, u, v, um, vm);
  EXPECT_EQ(both->Solve(p.time.dt, mean_u.data(), mean_v.data()).iterations, 1);
  EXPECT_EQ(mesh->Solve(p.time.dt, u.data(), v.data()).iterations, 1);
  EXPECT_EQ(mesh->Solve(p.time.dt, um.data(), vm.data()).iterations, 1);
  testing::MirrorVelocity(g, mirror_x, um, vm, iu, iv);  // the NW-SE mesh's step
  double mismatch = 0.0, size = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    mismatch = std::max({mismatch, std::abs(mean_u[k] - 0.5 * (u[k] + iu[k])),
                         std::abs(mean_v[k] - 0.5 * (v[k] + iv[k]))});
    size = std::max({size, std::abs(u[k] - iu[k]), std::abs(v[k] - iv[k])});
  }
  EXPECT_GE(size, 1e-4);  // the two meshes' steps differ: the test can tell the mean from either
  return mismatch / size;
}

TEST(AdvectionWave, TheStepOnBothDiagonalsIsTheMeanOfTheTwoMeshesSteps) {
  for (SteadyCorrection correction : {SteadyCorrection::kNone, SteadyCorrection::kTaylor}) {
    for (bool periodic_x : {false, true}) {
      for (bool mirror_x : {true, false}) {
        const double mismatch = MeanStepMismatch(periodic_x, mirror_x, correction);
        std::printf("%s, %s, mirror %s: mismatch %.3g of the two meshes' difference\n",
                    correction == SteadyCorrection::kNone ? "uncorrected" : "corrected",
                    periodic_x ? "periodic x" : "closed box", mirror_x ? "x" : "y", mismatch);
        EXPECT_LE(mismatch, 1e-12);
      }
    }
  }
}

// MakeVelocityAdvection builds the scheme of splitting.advection; each scheme writes its own
// columns of the step report (the names diagnostics.csv and its readers rely on).
TEST(Advection, TheSchemeIsChosenOnceAndNamesItsReportColumns) {
  Params p = UniformFlowCases()[1];
  const Grid g = GridOf(p);
  BoundaryData data(g, p.domain);
  auto columns = [](const StepReport& r) {
    std::vector<std::string> names;
    for (const auto& c : r.columns) names.push_back(c.first);
    return names;
  };
  for (AdvectionScheme scheme : {AdvectionScheme::kLeastSquares, AdvectionScheme::kWave}) {
    p.splitting.advection = scheme;
    const std::unique_ptr<VelocityAdvection> advection = MakeVelocityAdvection(g, p, data);
    const bool least_squares = scheme == AdvectionScheme::kLeastSquares;
    EXPECT_EQ(dynamic_cast<AdvectionLeastSquares*>(advection.get()) != nullptr, least_squares);
    EXPECT_EQ(dynamic_cast<AdvectionWave*>(advection.get()) != nullptr, !least_squares);
    std::vector<double> u(g.NodeCount(), 0.7), v(g.NodeCount(), 0.4);
    const AdvectionReport r = advection->Solve(p.time.dt, u.data(), v.data());
    StepReport report;
    advection->Record(r, report);
    if (least_squares) {
      EXPECT_EQ(columns(report),
                (std::vector<std::string>{"advection_iterations", "advection_residual"}));
      EXPECT_EQ(report.Get("advection_residual", -1.0), r.residual);
    } else {
      EXPECT_EQ(columns(report), (std::vector<std::string>{"wave_substeps"}));
      EXPECT_GE(report.Get("wave_substeps"), 1.0);
    }
    EXPECT_EQ(report.Get(least_squares ? "advection_iterations" : "wave_substeps", -1.0),
              r.iterations);
  }
}

// A smooth field plus data on the Dirichlet nodes, duplicates synced.
void FillSmooth(const Grid& g, const NodeSet& nodes, const BoundaryData& data,
                std::vector<double>& u, std::vector<double>& v, double phase) {
  u.assign(g.NodeCount(), 0.0);
  v.assign(g.NodeCount(), 0.0);
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const double x = g.X(i), y = g.Y(j);
      u[g.Index(i, j)] = std::sin(6.0 * x + phase) * std::cos(4.0 * y) + 0.5;
      v[g.Index(i, j)] = std::cos(5.0 * x - 3.0 * y + phase) * 0.8;
    }
  }
  nodes.SyncPeriodic(u.data());
  nodes.SyncPeriodic(v.data());
  data.Apply(u.data(), v.data());
}

// <T'(u) w, y> = <w, T'(u)^T y> on unknowns, with outflow and periodic sides (where G^T = -G needs
// its boundary term), and T'(u) w = (T(u + e w) - T(u - e w)) / 2e exactly since T is quadratic.
TEST(AdvectionLeastSquares, GradientIsTheAdjointOfTheLinearisedResidual) {
  const std::vector<Params> cases = {
      MakeParams(1.0 / 8, AdvectionSide(SideType::kPeriodic), AdvectionSide(SideType::kPeriodic),
                 AdvectionSide(SideType::kWall), AdvectionSide(SideType::kOutflow)),
      MakeParams(1.0 / 8, AdvectionSide(SideType::kOutflow), AdvectionSide(SideType::kOutflow),
                 AdvectionSide(SideType::kVelocity, 0.1, 1.0), AdvectionSide(SideType::kOutflow)),
      MakeParams(1.0 / 8, AdvectionSide(SideType::kWall), AdvectionSide(SideType::kWall),
                 AdvectionSide(SideType::kWall), AdvectionSide(SideType::kVelocity, 1.0, 0.0))};
  for (Params p : cases) {
    for (MeshDiagonals diagonals : {MeshDiagonals::kSwNe, MeshDiagonals::kBoth}) {
      p.domain.diagonals = diagonals;  // G on the SW-NE mesh, or the mean over both diagonals
      const Grid g = GridOf(p);
      BoundaryData data(g, p.domain);
      AdvectionLeastSquares ls(g, p.domain, p.fluid, 0.5, SteadyCorrection::kNone, p.solvers, data);
      const NodeSet& nodes = ls.nodes();
      std::vector<double> u, v, wu, wv, yu, yv, su, sv;
      FillSmooth(g, nodes, data, u, v, 0.0);
      FillSmooth(g, nodes, data, su, sv, 0.4);
      FillSmooth(g, nodes, data, wu, wv, 1.1);
      FillSmooth(g, nodes, data, yu, yv, 2.3);
      for (auto* a : {&wu, &wv, &yu, &yv}) nodes.ZeroKnown(a->data());
      for (auto* a : {&wu, &wv}) nodes.SyncPeriodic(a->data());
      ls.SetReference(p.time.dt, su.data(), sv.data());
      const std::size_t n = g.NodeCount();
      std::vector<double> jwu(n), jwv(n), jtu(n), jtv(n);
      ls.Jacobian(u.data(), v.data(), wu.data(), wv.data(), jwu.data(), jwv.data());
      ls.JacobianTranspose(u.data(), v.data(), yu.data(), yv.data(), jtu.data(), jtv.data());
      const double lhs = nodes.Dot2(jwu.data(), yu.data(), jwv.data(), yv.data());
      const double rhs = nodes.Dot2(wu.data(), jtu.data(), wv.data(), jtv.data());
      EXPECT_NEAR(lhs, rhs, 1e-12 * std::abs(lhs));

      const double e = 1e-3;
      std::vector<double> up(n), vp(n), um(n), vm(n), tpu(n), tpv(n), tmu(n), tmv(n);
      for (std::size_t k = 0; k < n; ++k) {
        up[k] = u[k] + e * wu[k];
        vp[k] = v[k] + e * wv[k];
        um[k] = u[k] - e * wu[k];
        vm[k] = v[k] - e * wv[k];
      }
      ls.Residual(up.data(), vp.data(), tpu.data(), tpv.data());
      ls.Residual(um.data(), vm.data(), tmu.data(), tmv.data());
      double diff = 0.0, scale = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        diff = std::max({diff, std::abs((tpu[k] - tmu[k]) / (2 * e) - jwu[k]),
                         std::abs((tpv[k] - tmv[k]) / (2 * e) - jwv[k])});
        scale = std::max({scale, std::abs(jwu[k]), std::abs(jwv[k])});
      }
      EXPECT_LE(diff, 1e-9 * scale);  // round-off of a difference quotient with e = 1e-3
    }
  }
}

// sqrt(g.r / g0.r0), recomputed from scratch after the solve, is below the tolerance, and the
// residual norm <P^-1 T, T> has fallen accordingly.
TEST(AdvectionLeastSquares, GradientRatioIsBelowToleranceAfterSolve) {
  Params p =
      MakeParams(1.0 / 16, AdvectionSide(SideType::kPeriodic), AdvectionSide(SideType::kPeriodic),
                 AdvectionSide(SideType::kWall), AdvectionSide(SideType::kOutflow));
  p.solvers.advection_tolerance = 1e-6;
  p.time.dt = 0.05;
  const Grid g = GridOf(p);
  BoundaryData data(g, p.domain);
  AdvectionLeastSquares ls(g, p.domain, p.fluid, 0.5, SteadyCorrection::kNone, p.solvers, data);
  const NodeSet& nodes = ls.nodes();
  std::vector<double> u, v;
  FillSmooth(g, nodes, data, u, v, 0.0);
  const std::vector<double> su = u, sv = v;
  const std::size_t n = g.NodeCount();
  std::vector<double> tu(n), tv(n), yu(n), yv(n), ru(n), rv(n), gu(n), gv(n);
  auto measure = [&](const std::vector<double>& a, const std::vector<double>& b, double* jval) {
    ls.Residual(a.data(), b.data(), tu.data(), tv.data());
    ls.ApplyPreconditioner(tu.data(), tv.data(), yu.data(), yv.data());
    *jval = nodes.Dot2(tu.data(), yu.data(), tv.data(), yv.data());
    ls.JacobianTranspose(a.data(), b.data(), yu.data(), yv.data(), ru.data(), rv.data());
    ls.ApplyPreconditioner(ru.data(), rv.data(), gu.data(), gv.data());
    return nodes.Dot2(gu.data(), ru.data(), gv.data(), rv.data());
  };
  ls.SetReference(p.time.dt, su.data(), sv.data());
  double j0 = 0.0, j1 = 0.0;
  const double gr0 = measure(su, sv, &j0);
  const AdvectionReport r = ls.Solve(p.time.dt, u.data(), v.data());
  ls.SetReference(p.time.dt, su.data(), sv.data());
  const double gr1 = measure(u, v, &j1);
  EXPECT_GT(r.iterations, 1);
  EXPECT_LE(r.residual, 1e-6);
  EXPECT_LE(std::sqrt(gr1 / gr0), 1e-6 * (1.0 + 1e-6));
  EXPECT_LE(j1, 1e-8 * j0);
}

// A velocity far beyond what the time step can follow (a diverging run) ends the step with
// NumericalBlowUp at once instead of sub-cycling for hours: |u| = 1e6 with dt = 1, h = 1/16 would
// need 3.2e7 sub-steps of Courant 0.5.
TEST(AdvectionWave, AVelocityBeyondAnyBoundThrowsInsteadOfSubCyclingForever) {
  Params p =
      MakeParams(1.0 / 16, AdvectionSide(SideType::kPeriodic), AdvectionSide(SideType::kPeriodic),
                 AdvectionSide(SideType::kPeriodic), AdvectionSide(SideType::kPeriodic));
  p.time.dt = 1.0;
  const Grid g = GridOf(p);
  BoundaryData data(g, p.domain);
  AdvectionWave wave(g, p.domain, p.fluid, 0.5, SteadyCorrection::kNone, p.solvers, data);
  std::vector<double> u(g.NodeCount(), 1e6), v(g.NodeCount(), 0.0);
  try {
    wave.Solve(p.time.dt, u.data(), v.data());
    ADD_FAILURE() << "no exception";
  } catch (const NumericalBlowUp& e) {
    EXPECT_NE(std::string(e.what()).find("wave sub-steps"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("step (34)"), std::string::npos) << e.what();
  }
}

// Von Neumann-type check of the wave scheme alone: a uniform flow U plus a small random
// perturbation in a doubly periodic box, advected by repeated calls (no Stokes step, no diffusion):
// to first order in the perturbation this is constant-coefficient advection, which the scheme must
// not amplify. Measured limit (400 steps, h = 1/32): stable at Courant 0.7 per sub-step for flows
// along x, y = x/2, y = x and y = -x; at 0.8 the flow along y = -x (across the mesh diagonals)
// grows, and along x it grows at 0.9. So 0.7 is asserted, not the 0.9 hoped for; at 1.6 every
// direction grows, so the check can fail. The mean over both diagonals (domain.diagonals = "both")
// has the same bound (fluid/advection_wave.h) and is checked alike.
double PerturbationGrowth(double courant, Vec2 flow,
                          MeshDiagonals diagonals = MeshDiagonals::kSwNe) {
  Params p =
      MakeParams(1.0 / 32, AdvectionSide(SideType::kPeriodic), AdvectionSide(SideType::kPeriodic),
                 AdvectionSide(SideType::kPeriodic), AdvectionSide(SideType::kPeriodic));
  p.solvers.wave_max_courant = courant * 1.01;  // two sub-steps (the minimum) of Courant `courant`
  p.time.dt = 2.0 * courant * p.domain.h / flow.norm();
  p.domain.diagonals = diagonals;
  const Grid g = GridOf(p);
  BoundaryData data(g, p.domain);
  AdvectionWave wave(g, p.domain, p.fluid, 0.0, SteadyCorrection::kNone, p.solvers, data);
  NodeSet nodes(g, BoundaryTopology::ForVelocity(p.domain));
  std::vector<double> u(g.NodeCount()), v(g.NodeCount());
  unsigned state = 12345u;
  auto noise = [&] {
    state = state * 1664525u + 1013904223u;
    return 1e-4 * (static_cast<double>(state >> 8) / 16777216.0 - 0.5);
  };
  for (std::size_t k = 0; k < u.size(); ++k) {
    u[k] = flow.x() + noise();
    v[k] = flow.y() + noise();
  }
  nodes.SyncPeriodic(u.data());
  nodes.SyncPeriodic(v.data());
  auto perturbation = [&] {
    double e = 0.0;
    for (std::size_t k = 0; k < u.size(); ++k) {
      e += nodes.distinct()[k] *
           ((u[k] - flow.x()) * (u[k] - flow.x()) + (v[k] - flow.y()) * (v[k] - flow.y()));
    }
    return e;
  };
  const double e0 = perturbation();
  for (int n = 0; n < 400; ++n) {
    const AdvectionReport r = wave.Solve(p.time.dt, u.data(), v.data());
    if (r.iterations != 2) return 1e300;
  }
  return perturbation() / e0;
}

TEST(AdvectionWave, StableAtCourantSevenTenths) {
  for (const Vec2& flow : {Vec2(1.0, 0.0), Vec2(1.0, 0.5), Vec2(1.0, 1.0), Vec2(1.0, -1.0)}) {
    for (MeshDiagonals diagonals : {MeshDiagonals::kSwNe, MeshDiagonals::kBoth}) {
      const bool both = diagonals == MeshDiagonals::kBoth;
      EXPECT_LE(PerturbationGrowth(0.7, flow, diagonals), 1.0) << flow.transpose() << both;
      EXPECT_GT(PerturbationGrowth(1.6, flow, diagonals), 1e3) << flow.transpose() << both;
    }
  }
}

}  // namespace
}  // namespace dlmfd
