// The cut-cell step's Uzawa start from the earlier steps' pressure corrections
// (particles/pressure_correction_basis.h):
// - on a known symmetric positive definite S: the start is the Galerkin one (its residual
//   orthogonal to the corrections kept; exact once they span the space), the velocity moves with
//   it, a correction already in the span is not kept, a full basis starts over;
// - in CutCellStokes: a solve repeated from the same start needs no iteration (the first solve's
//   correction is the answer) and is the direct solve; the basis is forgotten when the operators
//   are built anew.
#include "dlmfd/particles/pressure_correction_basis.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "../support/cut_cell_creeping.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/particles/cut_cell_stokes.h"

namespace dlmfd {
namespace {

constexpr int kBasisSize = PressureCorrectionBasis::kCapacity + 2;

// A symmetric positive definite S (diagonally dominant) and a "velocity response" W (kBasisSize + 3
// rows).
Eigen::MatrixXd BasisOperator() {
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(kBasisSize, kBasisSize);
  for (int i = 0; i < kBasisSize; ++i) {
    s(i, i) = 4.0 + 0.5 * i;
    if (i + 1 < kBasisSize) s(i, i + 1) = s(i + 1, i) = 1.0;
    if (i + 3 < kBasisSize) s(i, i + 3) = s(i + 3, i) = 0.3;
  }
  return s;
}

Eigen::MatrixXd BasisResponse() {
  Eigen::MatrixXd w(kBasisSize + 3, kBasisSize);
  for (int i = 0; i < w.rows(); ++i)
    for (int j = 0; j < kBasisSize; ++j) w(i, j) = std::sin(1.0 + i + 2.0 * j);
  return w;
}

void AddBasisCorrection(PressureCorrectionBasis& basis, const Eigen::VectorXd& dp) {
  basis.Add(dp, BasisOperator() * dp, BasisResponse() * dp);
}

Eigen::VectorXd BasisUnit(int i) { return Eigen::VectorXd::Unit(kBasisSize, i); }

TEST(PressureCorrectionBasis, StartIsTheGalerkinOneInTheSpan) {
  const Eigen::MatrixXd s = BasisOperator(), w = BasisResponse();
  Eigen::VectorXd c(kBasisSize);
  for (int i = 0; i < kBasisSize; ++i) c[i] = std::cos(0.7 * i) + 0.1 * i;
  const Eigen::VectorXd p0 = Eigen::VectorXd::LinSpaced(kBasisSize, -1.0, 2.0);
  const Eigen::VectorXd u0 = Eigen::VectorXd::Constant(kBasisSize + 3, 0.5);
  const std::vector<Eigen::VectorXd> corrections = {BasisUnit(0) + BasisUnit(1),
                                                    BasisUnit(2) - 0.5 * BasisUnit(5),
                                                    BasisUnit(3) + BasisUnit(4) + BasisUnit(7)};
  PressureCorrectionBasis basis;
  for (const Eigen::VectorXd& d : corrections) AddBasisCorrection(basis, d);
  ASSERT_EQ(basis.Count(), 3);
  Eigen::VectorXd p = p0, u = u0, r = c - s * p0;
  basis.Project(p, u, r);
  EXPECT_LT((r - (c - s * p)).norm(), 1e-12 * c.norm());           // the residual moves with p
  EXPECT_LT((u - (u0 - w * (p - p0))).norm(), 1e-12 * u0.norm());  // so does the velocity
  for (const Eigen::VectorXd& d : corrections) EXPECT_LT(std::abs(d.dot(r)), 1e-12 * c.norm());
  // The start is better than p0 in the S-norm of the error.
  const Eigen::VectorXd exact = s.ldlt().solve(c);
  EXPECT_LT((p - exact).dot(s * (p - exact)), (p0 - exact).dot(s * (p0 - exact)));
}

TEST(PressureCorrectionBasis, SpanningCorrectionsGiveTheSolution) {
  const Eigen::MatrixXd s = BasisOperator();
  const Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(kBasisSize, 1.0, -3.0);
  PressureCorrectionBasis basis;
  for (int i = 0; i < PressureCorrectionBasis::kCapacity; ++i)
    AddBasisCorrection(basis, BasisUnit(i));
  ASSERT_EQ(basis.Count(), PressureCorrectionBasis::kCapacity);
  // c's solution lies in the span of the first kCapacity unit vectors when S x = c has x there.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(kBasisSize);
  x.head(PressureCorrectionBasis::kCapacity) = c.head(PressureCorrectionBasis::kCapacity);
  const Eigen::VectorXd rhs = s * x;
  Eigen::VectorXd p = Eigen::VectorXd::Zero(kBasisSize), u = Eigen::VectorXd::Zero(kBasisSize + 3),
                  r = rhs;
  basis.Project(p, u, r);
  EXPECT_LT((p - x).norm(), 1e-12 * x.norm());
  EXPECT_LT(r.norm(), 1e-12 * rhs.norm());
}

TEST(PressureCorrectionBasis, KeepsNewDirectionsOnlyAndStartsOverWhenFull) {
  PressureCorrectionBasis basis;
  AddBasisCorrection(basis, BasisUnit(0) + BasisUnit(1));
  AddBasisCorrection(basis, 3.0 * (BasisUnit(0) + BasisUnit(1)));  // in the span
  AddBasisCorrection(basis, Eigen::VectorXd::Zero(kBasisSize));
  EXPECT_EQ(basis.Count(), 1);
  for (int i = 1; i < PressureCorrectionBasis::kCapacity; ++i)
    AddBasisCorrection(basis, BasisUnit(i + 1));
  EXPECT_EQ(basis.Count(), PressureCorrectionBasis::kCapacity);
  AddBasisCorrection(basis, BasisUnit(kBasisSize - 1));
  EXPECT_EQ(basis.Count(), 1);
  basis.Clear();
  EXPECT_EQ(basis.Count(), 0);
}

// The time loop's Stokes solve (nu dt / h^2 = 1e-3) of the creeping channel's disk at D/h = 10.
TEST(PressureCorrectionBasis, RepeatedCutCellSolveNeedsNoIteration) {
  const DomainParams d = CutCreepingChannel(10.0);
  const Grid g = d.VelocityGrid();
  std::vector<FixedBody> bodies(1);
  bodies[0].shape = Shape::Disk(0.05);
  bodies[0].centre = Vec2(0.2 + 0.3 * d.h, 0.2 + 0.1 * d.h);
  const CutCellGeometry geo(g, bodies);
  const BoundaryData data(g, d);
  CutCellStokes flow(geo, d, 1.0, 1.0, 1e3 / (d.h * d.h));
  const std::size_t n = g.NodeCount(), np = g.Coarse().NodeCount();
  std::vector<double> ud(n), vd(n), pd(np);
  flow.SolveDirect(data, nullptr, nullptr, ud.data(), vd.data(), pd.data());
  auto solve_from_rest = [&](std::vector<double>& u, std::vector<double>& v,
                             std::vector<double>& p) {
    u.assign(n, 0.0);
    v.assign(n, 0.0);
    p.assign(np, 0.0);
    return flow.Solve(data, nullptr, nullptr, u.data(), v.data(), p.data(), 1e-11, 2000).iterations;
  };
  std::vector<double> u, v, p;
  const int first = solve_from_rest(u, v, p);
  EXPECT_GT(first, 3);
  EXPECT_EQ(solve_from_rest(u, v, p), 0);
  double du = 0.0, dp = 0.0, umax = 0.0, pmax = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    du = std::max({du, std::abs(u[k] - ud[k]), std::abs(v[k] - vd[k])});
    umax = std::max(umax, std::abs(ud[k]));
  }
  for (std::size_t k = 0; k < np; ++k) {
    dp = std::max(dp, std::abs(p[k] - pd[k]));
    pmax = std::max(pmax, std::abs(pd[k]));
  }
  // The bounds of CutCellStokes.IterativeSolveIsTheDirectSolve (the same tolerance).
  EXPECT_LT(du, 1e-8 * umax);
  EXPECT_LT(dp, 1e-7 * pmax);
  flow.SetExactVelocityPreconditioner(false);  // the operators built anew: the basis forgotten
  EXPECT_EQ(solve_from_rest(u, v, p), first);
}

}  // namespace
}  // namespace dlmfd
