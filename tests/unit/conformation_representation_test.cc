// fluid.conformation = log and sqrt (conformation_representation.h): the matrix functions of a
// symmetric 2x2 tensor, and step (35) with each representation: the same steady shear as the
// standard one at every node, third order in h for the advection of a smooth field, and the step
// bit for bit the composition of its pieces (A -> X, advection of X, X -> A, pointwise update), so
// that a faster arrangement of its passes (fused, reordered) is checked to give the same results.
#include "dlmfd/conformation/conformation_representation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../support/shear_start_up.h"
#include "../support/studied_numerics.h"
#include "dlmfd/conformation/conformation_advection.h"
#include "dlmfd/conformation/conformation_step.h"
#include "dlmfd/conformation/inflow_state.h"
#include "dlmfd/conformation/pointwise_update.h"
#include "dlmfd/conformation/velocity_gradient.h"
#include "dlmfd/core/constants.h"

namespace dlmfd {
namespace {

// R diag(l1, l2) R^T for a rotation by theta.
SymTensor Rotated(double l1, double l2, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return SymTensor{l1 * c * c + l2 * s * s, (l1 - l2) * c * s, l1 * s * s + l2 * c * c};
}

void ExpectRelative(const SymTensor& got, const SymTensor& want, double tol) {
  const double scale = std::max({1.0, std::abs(want.a11), std::abs(want.a22), std::abs(want.a12)});
  EXPECT_NEAR(got.a11, want.a11, tol * scale);
  EXPECT_NEAR(got.a12, want.a12, tol * scale);
  EXPECT_NEAR(got.a22, want.a22, tol * scale);
}

TEST(ConformationRepresentation, MatrixFunctionsOfTheSpectrum) {
  for (double theta : {0.0, 0.3, 1.2, -2.0}) {
    for (const auto& [l1, l2] : std::vector<std::pair<double, double>>{
             {2.0, 0.5}, {1e6, 1e-3}, {3.0, 3.0}, {1.0 + 1e-12, 1.0}, {50.0, 49.0}}) {
      // Rounding A's entries moves l2 by about eps l1: the functions are accurate to eps cond(A).
      const double tol = 1e-13 + 4e-16 * l1 / l2;
      const SymTensor a = Rotated(l1, l2, theta);
      ExpectRelative(MatrixLog(a), Rotated(std::log(l1), std::log(l2), theta), tol);
      ExpectRelative(MatrixSqrt(a), Rotated(std::sqrt(l1), std::sqrt(l2), theta), tol);
      ExpectRelative(MatrixExp(MatrixLog(a)), a, tol);
      ExpectRelative(Square(MatrixSqrt(a)), a, tol);
    }
  }
  // exp of an indefinite Psi is SPD; its eigenvalues e^{4.22}, e^{-5.22} give cond 1.3e4.
  const SymTensor e = MatrixExp(SymTensor{-3.0, 4.0, 2.0});
  EXPECT_GT(MinEigenvalue(e), 0.0);
  ExpectRelative(MatrixLog(e), SymTensor{-3.0, 4.0, 2.0}, 1e-13 + 4e-16 * 1.3e4);
}

Params Channel(int n, ConformationRepresentation r) {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(1.0, 1.0);
  p.domain.h = 1.0 / n;
  for (Side s : {Side::kLeft, Side::kRight, Side::kBottom, Side::kTop})
    p.domain.sides[int(s)].type = SideType::kPeriodic;
  p.fluid.relaxation_time = 1.0;
  p.fluid.solvent_ratio = 0.5;
  p.fluid.viscosity = 1.0;
  p.fluid.conformation = r;
  return p;
}

TEST(ConformationRepresentation, EachRepresentationReachesTheSteadyShear) {
  // u = Wi (y - 1/2) on walls, periodic in x: advection idle, every node reaches the Oldroyd-B
  // steady shear (the transient e^{-20} after t = 20 lambda, times Wi^2).
  const int n = 8;
  const double wi = 4.0, dt = 0.05;
  for (ConformationRepresentation r :
       {ConformationRepresentation::kStandard, ConformationRepresentation::kLog,
        ConformationRepresentation::kSqrt}) {
    Params p = Channel(n, r);
    p.domain.sides[int(Side::kBottom)].type = SideType::kWall;
    p.domain.sides[int(Side::kTop)].type = SideType::kWall;
    const testing::ShearRun run = testing::ShearStartUp(p, wi, dt, 400);
    const SymTensor want = SimpleShearConformation(1.0, wi);
    for (std::size_t k = 0; k < run.a11.size(); ++k) {
      EXPECT_NEAR(run.a11[k], want.a11, 1e-7 * want.a11) << RepresentationName(r);
      EXPECT_NEAR(run.a12[k], want.a12, 1e-7 * want.a12) << RepresentationName(r);
      EXPECT_NEAR(run.a22[k], want.a22, 1e-7) << RepresentationName(r);
    }
  }
}

// A0 = exp(Psi0), Psi0 smooth and periodic.
SymTensor Initial(double x, double y) {
  const double s = 0.8 * std::sin(2.0 * kPi * x) * std::cos(2.0 * kPi * y);
  const double c = 0.6 * std::cos(2.0 * kPi * (x + y));
  return MatrixExp(SymTensor{s + 0.3, c, 0.3 - s});
}

// Max error of A after t = 0.25 with u = (1, 0.5), lambda = 1 on an n x n periodic grid; exact:
// A = I + (A0(x - u t) - I) e^{-t} (L = 0: the pointwise update is exact relaxation).
double AdvectionError(int n, ConformationRepresentation r) {
  const Params p = Channel(n, r);
  const Grid grid = p.domain.VelocityGrid();
  ConformationStep step(p, grid);
  const std::size_t count = grid.NodeCount();
  std::vector<double> u(count, 1.0), v(count, 0.5), a11(count), a12(count), a22(count);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const SymTensor a = Initial(grid.X(i), grid.Y(j));
      const std::size_t k = grid.Index(i, j);
      a11[k] = a.a11;
      a12[k] = a.a12;
      a22[k] = a.a22;
    }
  }
  const double dt = 0.25 / n, t_end = 0.25;  // Courant (|u| + |v|) dt / h = 0.375
  StepReport report;
  for (int s = 0; s < n; ++s)
    step.Advance(s * dt, dt, u.data(), v.data(), nullptr, a11.data(), a12.data(), a22.data(),
                 report);
  const double decay = std::exp(-t_end);
  double error = 0.0;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const SymTensor a0 = Initial(grid.X(i) - t_end, grid.Y(j) - 0.5 * t_end);
      const std::size_t k = grid.Index(i, j);
      error = std::max({error, std::abs(a11[k] - 1.0 - (a0.a11 - 1.0) * decay),
                        std::abs(a12[k] - a0.a12 * decay),
                        std::abs(a22[k] - 1.0 - (a0.a22 - 1.0) * decay)});
    }
  }
  return error;
}

TEST(ConformationRepresentation, AdvectionIsThirdOrderInEachRepresentation) {
  for (ConformationRepresentation r :
       {ConformationRepresentation::kStandard, ConformationRepresentation::kLog,
        ConformationRepresentation::kSqrt}) {
    // Measured (n = 16 -> 32 -> 64 -> 128): standard 2.78, 2.95, 3.00; log 2.96, 2.99, 3.00; sqrt
    // 2.87, 2.97, 3.00. The test runs 16, 32, 64 and asks for an order above 2.85 at 32 -> 64.
    std::vector<double> e;
    for (int n : {16, 32, 64}) e.push_back(AdvectionError(n, r));
    EXPECT_GT(std::log2(e[1] / e[2]), 2.85) << RepresentationName(r);
    EXPECT_GT(std::log2(e[0] / e[1]), 2.5) << RepresentationName(r);
  }
}

// Step (35) of an Oldroyd-B liquid in the log or sqrt representation written as its pieces
// compose, one pass over the grid each: A -> X at every node, the advection of X without the blend
// in the step's sub-steps, X -> A at every node, the pointwise update (the one-panel row kernel,
// the general rule where it does not apply). Walls only: no inflow node.
void ComposedStep(const Params& p, const Grid& g, double dt, const std::vector<double>& u,
                  const std::vector<double>& v, std::vector<double>& a11, std::vector<double>& a12,
                  std::vector<double>& a22) {
  const ConformationRepresentation r = p.fluid.conformation;
  const std::size_t n = g.NodeCount();
  std::vector<double> l11(n), l12(n), l21(n), l22(n);
  NodeVelocityGradient(g, false, false, u.data(), v.data(), l11.data(), l12.data(), l21.data(),
                       l22.data());
  double max_speed = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    max_speed = std::max(max_speed, std::abs(u[k]) + std::abs(v[k]));
  const double courant_ratio = dt * max_speed / (g.h * p.conformation.max_courant);
  const int substeps = std::max(1, static_cast<int>(std::ceil(courant_ratio * (1.0 - 1e-12))));
  EXPECT_GE(substeps, 3);  // the case exercises sub-cycling
  ConformationAdvection advection(g, false, false, p.conformation.blend_kappa);
  advection.SetSpdBlend(false);
  std::vector<double> x11(n), x12(n), x22(n);
  for (std::size_t k = 0; k < n; ++k) {
    const SymTensor x = ToRepresentation(r, SymTensor{a11[k], a12[k], a22[k]});
    x11[k] = x.a11;
    x12[k] = x.a12;
    x22[k] = x.a22;
  }
  advection.Load(x11.data(), x12.data(), x22.data());
  for (int s = 0; s < substeps; ++s) advection.SubStep(dt / substeps, u.data(), v.data());
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const SymTensor a = FromRepresentation(r, advection.At(i, j));
      const std::size_t k = g.Index(i, j);
      x11[k] = a.a11;
      x12[k] = a.a12;
      x22[k] = a.a22;
    }
  }
  const ExponentialIntegrator integrator(dt, p.fluid.relaxation_time);
  const OnePanelConstants constants = integrator.Constants();
  for (int j = 0; j <= g.ny; ++j) {
    const std::size_t row = g.Index(0, j);
    OnePanelRow(g.nx + 1, constants, x11.data() + row, x12.data() + row, x22.data() + row,
                l11.data() + row, l12.data() + row, l21.data() + row, l22.data() + row,
                a11.data() + row, a12.data() + row, a22.data() + row);
    for (int i = 0; i <= g.nx; ++i) {
      const std::size_t k = row + i;
      const Mat2 l{l11[k], l12[k], l21[k], l22[k]};
      if (OnePanelApplies(constants, l)) continue;
      const SymTensor a = integrator.Apply(SymTensor{x11[k], x12[k], x22[k]}, l);
      a11[k] = a.a11;
      a12[k] = a.a12;
      a22[k] = a.a22;
    }
  }
}

TEST(ConformationRepresentation, StepIsTheCompositionOfItsPiecesBitForBit) {
  const int n = 24;
  for (ConformationRepresentation r :
       {ConformationRepresentation::kLog, ConformationRepresentation::kSqrt}) {
    Params p = Channel(n, r);
    for (Side s : {Side::kLeft, Side::kRight, Side::kBottom, Side::kTop})
      p.domain.sides[int(s)].type = SideType::kWall;
    const Grid g = p.domain.VelocityGrid();
    const std::size_t count = g.NodeCount();
    // A swirl vanishing on the walls (strong gradients: lambda |L| dt up to about 2) and a smooth
    // SPD field.
    std::vector<double> u(count), v(count), a11(count), a12(count), a22(count);
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const double x = g.X(i), y = g.Y(j);
        const std::size_t k = g.Index(i, j);
        u[k] = 6.0 * std::sin(kPi * x) * std::sin(kPi * x) * std::sin(2.0 * kPi * y);
        v[k] = -6.0 * std::sin(2.0 * kPi * x) * std::sin(kPi * y) * std::sin(kPi * y);
        const SymTensor a = Initial(x, y);
        a11[k] = a.a11;
        a12[k] = a.a12;
        a22[k] = a.a22;
      }
    }
    std::vector<double> b11 = a11, b12 = a12, b22 = a22;
    ConformationStep step(p, g);
    StepReport report;
    const double dt = 0.05;
    for (int s = 0; s < 3; ++s) {
      step.Advance(s * dt, dt, u.data(), v.data(), nullptr, a11.data(), a12.data(), a22.data(),
                   report);
      ComposedStep(p, g, dt, u, v, b11, b12, b22);
    }
    EXPECT_EQ(a11, b11) << RepresentationName(r);
    EXPECT_EQ(a12, b12) << RepresentationName(r);
    EXPECT_EQ(a22, b22) << RepresentationName(r);
  }
}

}  // namespace
}  // namespace dlmfd
