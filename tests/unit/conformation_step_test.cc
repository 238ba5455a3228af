// ConformationStep (step (35)) on simple flows with known answers: homogeneous relaxation, steady
// simple shear, A = I inside particles, inflow data, the report columns, and the velocity gradient.
#include "dlmfd/conformation/conformation_step.h"
#include "dlmfd/core/constants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/conformation/inflow_state.h"
#include "dlmfd/conformation/velocity_gradient.h"
#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

BoundarySide ConformationSide(SideType type, Vec2 value = Vec2::Zero()) {
  BoundarySide s;
  s.type = type;
  s.value = value;
  return s;
}

// A width x height box of cells h with the given side types, Oldroyd-B with relaxation time lambda.
Params MakeParams(int nx, int ny, double h, SideType x_sides, SideType y_sides, double lambda) {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(nx * h, ny * h);
  p.domain.h = h;
  p.domain.sides[int(Side::kLeft)] = ConformationSide(x_sides);
  p.domain.sides[int(Side::kRight)] = ConformationSide(x_sides);
  p.domain.sides[int(Side::kBottom)] = ConformationSide(y_sides);
  p.domain.sides[int(Side::kTop)] = ConformationSide(y_sides);
  p.fluid.relaxation_time = lambda;
  p.fluid.solvent_ratio = 0.5;
  p.fluid.viscosity = 1.0;
  return p;
}

struct Fields {
  std::vector<double> u, v, a11, a12, a22;
  explicit Fields(std::size_t n)
      : u(n, 0.0),
        v(n, 0.0),
        a11(n, 1.0),
        a12(n, 0.0),
        a22(n, 1.0) {}
};

TEST(ConformationStep, NewtonianSceneHasNoConformationStep) {
  Params p = MakeParams(4, 4, 0.25, SideType::kWall, SideType::kWall, 0.0);
  const Grid grid{4, 4, 0.25, 0.0, 0.0};
  EXPECT_THROW(ConformationStep(p, grid), InvalidParameter);
  p.fluid.relaxation_time = 1.0;
  p.fluid.solvent_ratio = 1.0;
  EXPECT_THROW(ConformationStep(p, grid), InvalidParameter);
}

TEST(ConformationStep, HomogeneousRelaxationIsExactToRoundOff) {
  // u = 0: A(t) = I + (A0 - I) e^{-t/lambda} at every node, whatever dt. The pointwise update is
  // exact for L = 0 (pointwise_update.h), so the error is round-off: about (steps) ulp of |A0|.
  const Grid grid{8, 8, 0.125, 0.0, 0.0};
  const double lambda = 0.7;
  for (double dt : {0.01, 0.1, 0.5}) {
    const Params p = MakeParams(8, 8, 0.125, SideType::kWall, SideType::kWall, lambda);
    ConformationStep step(p, grid);
    Fields f(grid.NodeCount());
    std::vector<double> b11(grid.NodeCount()), b12(grid.NodeCount()), b22(grid.NodeCount());
    for (int j = 0; j <= 8; ++j) {
      for (int i = 0; i <= 8; ++i) {
        const std::size_t k = grid.Index(i, j);
        b11[k] = 2.0 + std::sin(i + 0.3 * j);  // A0 - I: symmetric, A0 SPD
        b12[k] = 0.5 * std::cos(0.7 * i - j);
        b22[k] = 1.5 + 0.5 * std::sin(0.2 * i * j);
        f.a11[k] = 1.0 + b11[k];
        f.a12[k] = b12[k];
        f.a22[k] = 1.0 + b22[k];
      }
    }
    const int steps = 20;
    StepReport report;
    for (int n = 0; n < steps; ++n) {
      step.Advance(n * dt, dt, f.u.data(), f.v.data(), nullptr, f.a11.data(), f.a12.data(),
                   f.a22.data(), report);
    }
    const double decay = std::exp(-steps * dt / lambda);
    double error = 0.0;
    for (std::size_t k = 0; k < grid.NodeCount(); ++k) {
      error = std::max({error, std::abs(f.a11[k] - (1.0 + b11[k] * decay)),
                        std::abs(f.a12[k] - b12[k] * decay),
                        std::abs(f.a22[k] - (1.0 + b22[k] * decay))});
    }
    std::printf("dt = %.2f: max error after %d steps %.2e\n", dt, steps, error);
    EXPECT_LT(error, steps * 4.0 * 2.2e-16 * 4.0);
    EXPECT_EQ(report.Get("conformation_substeps", -1), 1.0);
    EXPECT_EQ(report.Get("blended_nodes", -1), 0.0);
    EXPECT_EQ(report.Get("elastic_courant", -1), 0.0);
    EXPECT_GT(report.Get("min_eig_A", -1), 0.0);
  }
}

TEST(ConformationStep, SteadySimpleShearReachesTheAnalyticState) {
  // u = g (y - y0), v = 0 in a box periodic in x with velocity sides at y = 0 and 1 (data u = 0 and
  // g, so u . n = 0: no inflow). L is uniform and exact at every node (P1 gradient of a linear
  // field), A stays uniform in x, so every node converges to A11 = 1 + 2 (lambda g)^2, A12 = lambda
  // g, A22 = 1 (reference README). Error budget: the pointwise quadrature, measured in
  // conformation_pointwise_test (<= 2.7e-13 relative at dt/lambda = 1/16), and the transient
  // (t^2 e^{-t/lambda} (lambda g)^2 at t = 60 lambda: < 1e-20).
  const int n = 8;
  const Grid grid{n, n, 1.0 / n, 0.0, 0.0};
  for (double wi : {0.5, 2.0, 10.0}) {
    const double lambda = 1.0, g = wi / lambda, dt = lambda / 16.0;
    Params p = MakeParams(n, n, 1.0 / n, SideType::kPeriodic, SideType::kVelocity, lambda);
    p.domain.sides[int(Side::kTop)].value = Vec2(g, 0.0);
    ConformationStep step(p, grid);
    Fields f(grid.NodeCount());
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) f.u[grid.Index(i, j)] = g * grid.Y(j);
    }
    StepReport report;
    for (int s = 0; s < 60 * 16; ++s) {
      step.Advance(s * dt, dt, f.u.data(), f.v.data(), nullptr, f.a11.data(), f.a12.data(),
                   f.a22.data(), report);
    }
    const SymTensor exact = SimpleShearConformation(lambda, g);
    double error = 0.0;
    for (std::size_t k = 0; k < grid.NodeCount(); ++k) {
      error = std::max({error, std::abs(f.a11[k] - exact.a11), std::abs(f.a12[k] - exact.a12),
                        std::abs(f.a22[k] - exact.a22)});
    }
    std::printf(
        "lambda g = %4.1f: max |A - A_exact| / trA = %.2e, trA on the wall %.6f (2 + 2 (lambda "
        "g)^2 = "
        "%.6f)\n",
        wi, error / Trace(exact), f.a11[0] + f.a22[0], 2.0 + 2.0 * wi * wi);
    EXPECT_LT(error / Trace(exact), 1e-12);
    EXPECT_NEAR(report.Get("elastic_courant"), lambda * g * dt, 1e-14 * g);
    EXPECT_EQ(report.Get("blended_nodes", -1), 0.0);
  }
}

TEST(ConformationStep, IdentityInsideParticlesAndInflowDataOnUpstreamNodes) {
  // Uniform flow u = (1, 0) through a channel: left side velocity (inflow), right side outflow,
  // walls at y = 0, 1 (slip data in the array, which the step reads as given). A0 = 3 I everywhere:
  // inflow nodes get A_L = I (uniform profile), nodes flagged inside a particle get I, the outflow
  // side keeps advected values.
  const int n = 8;
  const Grid grid{n, n, 1.0 / n, 0.0, 0.0};
  Params p = MakeParams(n, n, 1.0 / n, SideType::kVelocity, SideType::kWall, 1.0);
  p.domain.sides[int(Side::kRight)] = ConformationSide(SideType::kOutflow);
  ConformationStep step(p, grid);
  Fields f(grid.NodeCount());
  std::vector<unsigned char> inside(grid.NodeCount(), 0);
  for (std::size_t k = 0; k < grid.NodeCount(); ++k) {
    f.u[k] = 1.0;
    f.a11[k] = f.a22[k] = 3.0;
  }
  inside[grid.Index(4, 4)] = 1;
  StepReport report;
  const double dt = 0.01;
  step.Advance(0.0, dt, f.u.data(), f.v.data(), inside.data(), f.a11.data(), f.a12.data(),
               f.a22.data(), report);
  EXPECT_EQ(f.a11[grid.Index(4, 4)], 1.0);
  EXPECT_EQ(f.a12[grid.Index(4, 4)], 0.0);
  EXPECT_EQ(f.a22[grid.Index(4, 4)], 1.0);
  for (int j = 0; j <= n; ++j) {
    EXPECT_EQ(f.a11[grid.Index(0, j)], 1.0) << j;
    EXPECT_EQ(f.a22[grid.Index(0, j)], 1.0) << j;
    // Outflow side: only relaxation acts there (uniform A upstream of it): 1 + 2 e^{-dt}.
    EXPECT_NEAR(f.a11[grid.Index(n, j)], 1.0 + 2.0 * std::exp(-dt), 1e-14) << j;
  }
  // The first interior column sees the jump from the inflow value: A decreases but stays >= 1.
  EXPECT_LT(f.a11[grid.Index(1, 3)], 1.0 + 2.0 * std::exp(-dt));
  EXPECT_GT(report.Get("min_eig_A"), 0.99);
}

// The report's min_eig_A is the smallest eigenvalue over the nodes, also where a node's diagonal
// is large and its off-diagonal term makes it small: at rest A relaxes exactly,
// A -> I + (A - I) e^{-dt / lambda}. A node of lambda_min 0.5 (diagonal 0.6) comes first in its
// row, one of lambda_min 0.1 (diagonal 1, A12 0.9) after it: the minimum is the second's,
// 1 - 0.9 e^{-dt}. (The report used to skip nodes whose diagonal was above the running minimum,
// and gave the first's, 1 - 0.5 e^{-dt}.)
TEST(ConformationStep, ReportsTheSmallestEigenvalueOverTheNodes) {
  const int n = 8;
  const Grid grid{n, n, 1.0 / n, 0.0, 0.0};
  Params p = MakeParams(n, n, 1.0 / n, SideType::kWall, SideType::kWall, 1.0);
  ConformationStep step(p, grid);
  Fields f(grid.NodeCount());
  f.a11[grid.Index(1, 3)] = f.a22[grid.Index(1, 3)] = 0.6;
  f.a12[grid.Index(1, 3)] = 0.1;
  f.a12[grid.Index(5, 3)] = 0.9;
  StepReport report;
  const double dt = 0.01;
  step.Advance(0.0, dt, f.u.data(), f.v.data(), nullptr, f.a11.data(), f.a12.data(), f.a22.data(),
               report);
  EXPECT_NEAR(f.a12[grid.Index(5, 3)], 0.9 * std::exp(-dt), 1e-14);
  EXPECT_NEAR(report.Get("min_eig_A"), 1.0 - 0.9 * std::exp(-dt), 1e-14);
}

TEST(ConformationStep, SubCyclesToTheCourantLimit) {
  const int n = 8;
  const Grid grid{n, n, 1.0 / n, 0.0, 0.0};
  Params p = MakeParams(n, n, 1.0 / n, SideType::kPeriodic, SideType::kPeriodic, 1.0);
  p.conformation.max_courant = 0.4;
  ConformationStep step(p, grid);
  Fields f(grid.NodeCount());
  for (std::size_t k = 0; k < grid.NodeCount(); ++k) {
    f.u[k] = 1.0;
    f.v[k] = -0.5;
  }
  StepReport report;
  // (|u| + |v|) dt / h = 1.5 * 0.1 * 8 = 1.2 -> 3 sub-steps.
  step.Advance(0.0, 0.1, f.u.data(), f.v.data(), nullptr, f.a11.data(), f.a12.data(), f.a22.data(),
               report);
  EXPECT_EQ(report.Get("conformation_substeps"), 3.0);
}

TEST(NodeVelocityGradient, ExactForLinearFieldsAtEveryNode) {
  const Grid grid{6, 5, 0.2, -0.3, 0.1};
  const std::size_t count = grid.NodeCount();
  std::vector<double> u(count), v(count), l11(count), l12(count), l21(count), l22(count);
  for (int j = 0; j <= grid.ny; ++j) {
    for (int i = 0; i <= grid.nx; ++i) {
      u[grid.Index(i, j)] = 0.3 + 1.5 * grid.X(i) - 0.7 * grid.Y(j);
      v[grid.Index(i, j)] = -1.0 + 0.4 * grid.X(i) + 2.5 * grid.Y(j);
    }
  }
  NodeVelocityGradient(grid, false, false, u.data(), v.data(), l11.data(), l12.data(), l21.data(),
                       l22.data());
  for (std::size_t k = 0; k < count; ++k) {
    EXPECT_NEAR(l11[k], 1.5, 1e-13);
    EXPECT_NEAR(l12[k], -0.7, 1e-13);
    EXPECT_NEAR(l21[k], 0.4, 1e-13);
    EXPECT_NEAR(l22[k], 2.5, 1e-13);
  }
}

TEST(NodeVelocityGradient, SecondOrderOnAPeriodicBox) {
  // u = sin(2 pi x) cos(2 pi y), v = cos(2 pi x + 1) sin(4 pi y) on the doubly periodic unit box:
  // the 6-triangle average is a centred stencil, second order; the error must fall by ~4 per
  // halving.
  double previous = 0.0;
  for (int n : {16, 32, 64}) {
    const Grid grid{n, n, 1.0 / n, 0.0, 0.0};
    const std::size_t count = grid.NodeCount();
    std::vector<double> u(count), v(count), l11(count), l12(count), l21(count), l22(count);
    const double tp = 2.0 * kPi;
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const double x = grid.X(i), y = grid.Y(j);
        u[grid.Index(i, j)] = std::sin(tp * x) * std::cos(tp * y);
        v[grid.Index(i, j)] = std::cos(tp * x + 1.0) * std::sin(2.0 * tp * y);
      }
    }
    NodeVelocityGradient(grid, true, true, u.data(), v.data(), l11.data(), l12.data(), l21.data(),
                         l22.data());
    double error = 0.0;
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const double x = grid.X(i), y = grid.Y(j);
        const std::size_t k = grid.Index(i, j);
        error = std::max(
            {error, std::abs(l11[k] - tp * std::cos(tp * x) * std::cos(tp * y)),
             std::abs(l12[k] + tp * std::sin(tp * x) * std::sin(tp * y)),
             std::abs(l21[k] + tp * std::sin(tp * x + 1.0) * std::sin(2.0 * tp * y)),
             std::abs(l22[k] - 2.0 * tp * std::cos(tp * x + 1.0) * std::cos(2.0 * tp * y))});
      }
    }
    if (previous > 0.0) {
      std::printf("n = %d: max error %.3e, order %.2f\n", n, error, std::log2(previous / error));
      EXPECT_GT(std::log2(previous / error), 1.8);  // expected 2 (centred stencil)
    }
    previous = error;
  }
}

// The gradient of (u, v) on the given diagonals.
struct NodeGradient {
  std::vector<double> l11, l12, l21, l22;
};

NodeGradient GradientOf(const Grid& g, bool px, bool py, const std::vector<double>& u,
                        const std::vector<double>& v, MeshDiagonals diagonals) {
  const std::size_t n = g.NodeCount();
  NodeGradient l{std::vector<double>(n), std::vector<double>(n), std::vector<double>(n),
                 std::vector<double>(n)};
  NodeVelocityGradient(g, px, py, u.data(), v.data(), l.l11.data(), l.l12.data(), l.l21.data(),
                       l.l22.data(), diagonals);
  return l;
}

TEST(NodeVelocityGradient, BothDiagonalsGiveTheMeanStencilAndCommuteWithTheMirror) {
  // domain.diagonals = "both": exact for linear fields at every node; at interior nodes the mean of
  // the SW-NE and NW-SE 6-triangle averages, (4 (f_{i+1,j} - f_{i-1,j}) + f_{i+1,j+1} - f_{i-1,j+1}
  // + f_{i+1,j-1} - f_{i-1,j-1}) / 12h for d/dx and the same in y; and at every node the gradient
  // of the mirrored velocity (-u(W - x), v(W - x)) is the mirror image of the gradient with
  // L12, L21 negated (walls, and a periodic x axis).
  for (const bool px : {false, true}) {
    const Grid g{8, 6, 0.125, 0.0, 0.0};
    const std::size_t n = g.NodeCount();
    std::vector<double> u(n), v(n), ul(n), vl(n);
    const double tp = 2.0 * kPi;
    for (int j = 0; j <= g.ny; ++j) {
      for (int i = 0; i <= g.nx; ++i) {
        const double x = g.X(i), y = g.Y(j);
        const std::size_t k = g.Index(i, j);
        u[k] = std::sin(tp * x + 0.3) * std::cos(2.0 * y) + 0.5 * x * y;
        v[k] = std::cos(tp * x - 0.7) * std::exp(y);
        ul[k] = 0.3 + 1.5 * x - 0.7 * y;
        vl[k] = -1.0 + 0.4 * x + 2.5 * y;
      }
    }
    if (px) {  // the repeated last column equals the first
      for (int j = 0; j <= g.ny; ++j) u[g.Index(g.nx, j)] = u[g.Index(0, j)];
      for (int j = 0; j <= g.ny; ++j) v[g.Index(g.nx, j)] = v[g.Index(0, j)];
    }
    if (!px) {
      const NodeGradient l = GradientOf(g, false, false, ul, vl, MeshDiagonals::kBoth);
      for (std::size_t k = 0; k < n; ++k) {
        EXPECT_NEAR(l.l11[k], 1.5, 1e-13);
        EXPECT_NEAR(l.l12[k], -0.7, 1e-13);
        EXPECT_NEAR(l.l21[k], 0.4, 1e-13);
        EXPECT_NEAR(l.l22[k], 2.5, 1e-13);
      }
    }
    const NodeGradient both = GradientOf(g, px, false, u, v, MeshDiagonals::kBoth);
    const NodeGradient sw_ne = GradientOf(g, px, false, u, v, MeshDiagonals::kSwNe);
    const long row = g.nx + 1;
    auto mean_dx = [&](const std::vector<double>& f, long k) {
      return (4.0 * (f[k + 1] - f[k - 1]) + f[k + row + 1] - f[k + row - 1] + f[k - row + 1] -
              f[k - row - 1]) /
             (12.0 * g.h);
    };
    auto mean_dy = [&](const std::vector<double>& f, long k) {
      return (4.0 * (f[k + row] - f[k - row]) + f[k + row + 1] - f[k - row + 1] + f[k + row - 1] -
              f[k - row - 1]) /
             (12.0 * g.h);
    };
    double sw_ne_offset = 0.0;
    for (int j = 1; j < g.ny; ++j) {
      for (int i = 1; i < g.nx; ++i) {
        const long k = long(g.Index(i, j));
        EXPECT_NEAR(both.l11[k], mean_dx(u, k), 1e-12);
        EXPECT_NEAR(both.l12[k], mean_dy(u, k), 1e-12);
        EXPECT_NEAR(both.l21[k], mean_dx(v, k), 1e-12);
        EXPECT_NEAR(both.l22[k], mean_dy(v, k), 1e-12);
        sw_ne_offset = std::max(sw_ne_offset, std::abs(sw_ne.l11[k] - both.l11[k]));
      }
    }
    EXPECT_GT(sw_ne_offset, 1e-2);  // the SW-NE average is another stencil
    std::vector<double> um(n), vm(n);
    for (int j = 0; j <= g.ny; ++j) {
      for (int i = 0; i <= g.nx; ++i) {
        const std::size_t image = g.Index(px ? (g.nx - i) % g.nx : g.nx - i, j);
        um[g.Index(i, j)] = -u[image];
        vm[g.Index(i, j)] = v[image];
      }
      if (px) um[g.Index(g.nx, j)] = um[g.Index(0, j)], vm[g.Index(g.nx, j)] = vm[g.Index(0, j)];
    }
    for (const MeshDiagonals diagonals : {MeshDiagonals::kBoth, MeshDiagonals::kSwNe}) {
      const NodeGradient l = GradientOf(g, px, false, u, v, diagonals);
      const NodeGradient m = GradientOf(g, px, false, um, vm, diagonals);
      double mismatch = 0.0;
      for (int j = 0; j <= g.ny; ++j) {
        for (int i = 0; i <= g.nx; ++i) {
          const std::size_t k = g.Index(i, j);
          const std::size_t image = g.Index(px ? (g.nx - i) % g.nx : g.nx - i, j);
          mismatch = std::max({mismatch, std::abs(m.l11[k] - l.l11[image]),
                               std::abs(m.l12[k] + l.l12[image]), std::abs(m.l21[k] + l.l21[image]),
                               std::abs(m.l22[k] - l.l22[image])});
        }
      }
      if (diagonals == MeshDiagonals::kBoth) {
        EXPECT_LT(mismatch, 1e-13) << "periodic x " << px;
      } else {
        EXPECT_GT(mismatch, 1e-2) << "periodic x " << px;  // the SW-NE mesh is not symmetric
      }
    }
  }
}

}  // namespace
}  // namespace dlmfd
