// The matrix-free operators of fem_operators.h against the assembled finite-element matrices (two
// independent codes: stencil gathers vs. a triangle loop with basis gradients from coordinates), on
// small meshes and every boundary topology, plus the properties and interior stencils of method
// notes 1, section 1. Tolerances: the two codes differ only by round-off in sums of O(10) terms of
// size O(h) or O(1), so 1e-13 relative to the largest output is a generous bound for double
// precision.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/mesh/boundary_topology.h"
#include "dlmfd/mesh/fem_operators.h"

namespace dlmfd {
namespace {

struct Case {
  std::string name;
  SideType left, right, bottom, top;
};

const std::vector<Case>& Cases() {
  static const std::vector<Case> cases = {
      {"all_walls", SideType::kWall, SideType::kWall, SideType::kWall, SideType::kWall},
      {"outflow_top", SideType::kWall, SideType::kWall, SideType::kVelocity, SideType::kOutflow},
      {"periodic_x", SideType::kPeriodic, SideType::kPeriodic, SideType::kWall, SideType::kWall},
      {"periodic_xy", SideType::kPeriodic, SideType::kPeriodic, SideType::kPeriodic,
       SideType::kPeriodic},
      {"outflow_right", SideType::kVelocity, SideType::kOutflow, SideType::kWall, SideType::kWall},
  };
  return cases;
}

DomainParams DomainOf(const Case& c, const Grid& grid) {
  DomainParams d;
  testing::UseStudiedNumerics(d);
  d.size = Vec2(grid.Width(), grid.Height());
  d.h = grid.h;
  d.sides[int(Side::kLeft)].type = c.left;
  d.sides[int(Side::kRight)].type = c.right;
  d.sides[int(Side::kBottom)].type = c.bottom;
  d.sides[int(Side::kTop)].type = c.top;
  return d;
}

std::vector<Grid> Meshes() { return {Grid{6, 4, 0.25, 0.3, -0.2}, Grid{8, 6, 0.125, -1.0, 0.5}}; }

std::vector<double> Random(std::size_t n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  std::vector<double> v(n);
  for (double& x : v) x = dist(gen);
  return v;
}

Eigen::VectorXd Map(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size()));
}

// max |a - b| / max |b|.
double RelativeDifference(const std::vector<double>& a, const Eigen::VectorXd& b) {
  double diff = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    diff = std::max(diff, std::abs(a[i] - b[Eigen::Index(i)]));
  return diff / std::max(b.cwiseAbs().maxCoeff(), 1e-300);
}

bool IsDuplicate(const Grid& g, const BoundaryTopology& t, int i, int j) {
  return (t.x.low == EndKind::kPeriodic && i == g.nx) ||
         (t.y.low == EndKind::kPeriodic && j == g.ny);
}

constexpr double kTolerance = 1e-13;

class OperatorsTest : public ::testing::TestWithParam<std::tuple<int, int>> {
 protected:
  void SetUp() override {
    grid_ = Meshes()[std::get<0>(GetParam())];
    kase_ = Cases()[std::get<1>(GetParam())];
    velocity_ = BoundaryTopology::ForVelocity(DomainOf(kase_, grid_));
    pressure_ = BoundaryTopology::ForPressure(DomainOf(kase_, grid_));
  }
  Grid grid_;
  Case kase_;
  BoundaryTopology velocity_, pressure_;
};

TEST_P(OperatorsTest, StiffnessEqualsAssembledOnBothGrids) {
  for (const auto& [g, t] : {std::pair{grid_, velocity_}, std::pair{grid_.Coarse(), pressure_}}) {
    const auto u = Random(g.NodeCount(), 1);
    std::vector<double> out(g.NodeCount());
    ApplyStiffness(g, t, u.data(), out.data());
    EXPECT_LT(RelativeDifference(out, AssembleStiffness(g, t) * Map(u)), kTolerance) << kase_.name;
  }
}

// On either diagonal set (domain.diagonals): the stencils, through the mirror image for the NW-SE
// triangles, against the triangle loop over each set's own triangles.
constexpr MeshDiagonals kBothChoices[] = {MeshDiagonals::kSwNe, MeshDiagonals::kBoth};

TEST_P(OperatorsTest, IntegratedGradientEqualsAssembled) {
  const auto f = Random(grid_.NodeCount(), 2);
  std::vector<double> gx(grid_.NodeCount()), gy(grid_.NodeCount());
  for (MeshDiagonals d : kBothChoices) {
    ApplyIntegratedGradient(grid_, velocity_, f.data(), gx.data(), gy.data(), d);
    EXPECT_LT(RelativeDifference(gx, AssembleGradientX(grid_, velocity_, d) * Map(f)), kTolerance)
        << kase_.name << int(d);
    EXPECT_LT(RelativeDifference(gy, AssembleGradientY(grid_, velocity_, d) * Map(f)), kTolerance)
        << kase_.name << int(d);
  }
}

// Random values on every node, boundary nodes included (non-zero Dirichlet data).
TEST_P(OperatorsTest, DivergenceEqualsAssembledWithBoundaryData) {
  const auto u = Random(grid_.NodeCount(), 3), v = Random(grid_.NodeCount(), 4);
  const Grid coarse = grid_.Coarse();
  std::vector<double> out(coarse.NodeCount());
  for (MeshDiagonals d : kBothChoices) {
    ApplyDivergence(grid_, pressure_, u.data(), v.data(), out.data(), d);
    const Eigen::VectorXd expected = AssembleDivergenceX(grid_, pressure_, d) * Map(u) +
                                     AssembleDivergenceY(grid_, pressure_, d) * Map(v);
    EXPECT_LT(RelativeDifference(out, expected), kTolerance) << kase_.name << int(d);
  }
}

TEST_P(OperatorsTest, DivergenceTransposeEqualsAssembled) {
  const Grid coarse = grid_.Coarse();
  const auto p = Random(coarse.NodeCount(), 5);
  std::vector<double> ou(grid_.NodeCount()), ov(grid_.NodeCount());
  for (MeshDiagonals d : kBothChoices) {
    ApplyDivergenceTranspose(grid_, pressure_, p.data(), ou.data(), ov.data(), d);
    const Eigen::SparseMatrix<double> bx_t = AssembleDivergenceX(grid_, pressure_, d).transpose();
    const Eigen::SparseMatrix<double> by_t = AssembleDivergenceY(grid_, pressure_, d).transpose();
    EXPECT_LT(RelativeDifference(ou, bx_t * Map(p)), kTolerance) << kase_.name << int(d);
    EXPECT_LT(RelativeDifference(ov, by_t * Map(p)), kTolerance) << kase_.name << int(d);
  }
}

// Lumped mass = row sums of the consistent mass (|T|/3 per vertex), except at non-periodic corners
// where the separable trapezoid value h^2/4 replaces h^2/3 or h^2/6 (header of fem_operators.h).
TEST_P(OperatorsTest, LumpedMassIsRowSumExceptAtCorners) {
  for (const auto& [g, t] : {std::pair{grid_, velocity_}, std::pair{grid_.Coarse(), pressure_}}) {
    const Eigen::VectorXd row_sum =
        AssembleConsistentMass(g, t) * Eigen::VectorXd::Ones(Eigen::Index(g.NodeCount()));
    std::vector<double> ones(g.NodeCount(), 1.0), applied(g.NodeCount()), diagonal(g.NodeCount());
    ApplyLumpedMass(g, t, ones.data(), applied.data());
    LumpedMassDiagonal(g, t, diagonal.data());
    const double h2 = g.h * g.h;
    for (int j = 0; j <= g.ny; ++j) {
      for (int i = 0; i <= g.nx; ++i) {
        const std::size_t n = g.Index(i, j);
        if (IsDuplicate(g, t, i, j)) {
          EXPECT_EQ(applied[n], 0.0);
          continue;
        }
        const bool corner = t.x.low != EndKind::kPeriodic && t.y.low != EndKind::kPeriodic &&
                            (i == 0 || i == g.nx) && (j == 0 || j == g.ny);
        const double expected = corner ? 0.25 * h2 : row_sum[Eigen::Index(n)];
        EXPECT_NEAR(applied[n], expected, 1e-15 * h2) << kase_.name << " node " << i << "," << j;
        EXPECT_EQ(diagonal[n], applied[n]);
      }
    }
  }
}

// Symmetric, positive semi-definite; positive definite on the unknowns when a Dirichlet side
// exists, else exactly one zero eigenvalue (the constants). 1e-12 separates round-off zeros from
// the smallest true eigenvalue, which is O(1/n^2) ~ 1e-2 on these meshes.
TEST_P(OperatorsTest, StiffnessIsSymmetricSemiDefinite) {
  for (const auto& [g, t] : {std::pair{grid_, velocity_}, std::pair{grid_.Coarse(), pressure_}}) {
    const Eigen::SparseMatrix<double> k = AssembleStiffness(g, t);
    EXPECT_EQ((k - Eigen::SparseMatrix<double>(k.transpose())).norm(), 0.0);
    std::vector<int> kept, unknown;
    for (int j = 0; j <= g.ny; ++j) {
      for (int i = 0; i <= g.nx; ++i) {
        if (IsDuplicate(g, t, i, j)) continue;
        kept.push_back(int(g.Index(i, j)));
        if (t.IsUnknown(g, i, j)) unknown.push_back(int(g.Index(i, j)));
      }
    }
    const Eigen::MatrixXd dense(k);
    const Eigen::VectorXd all =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense(kept, kept)).eigenvalues();
    EXPECT_GT(all.minCoeff(), -1e-12);
    const Eigen::VectorXd on_unknowns =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense(unknown, unknown)).eigenvalues();
    if (t.HasNullSpace()) {
      EXPECT_LT(std::abs(on_unknowns[0]), 1e-12) << kase_.name;
      EXPECT_GT(on_unknowns[1], 1e-3) << kase_.name;
    } else {
      EXPECT_GT(on_unknowns[0], 1e-3) << kase_.name;
    }
  }
}

// B^T 1 = 0 on every velocity row not on a non-periodic boundary line, exactly up to round-off.
TEST_P(OperatorsTest, DivergenceTransposeOfConstantVanishesInside) {
  const Grid coarse = grid_.Coarse();
  std::vector<double> ones(coarse.NodeCount(), 1.0), ou(grid_.NodeCount()), ov(grid_.NodeCount());
  ApplyDivergenceTranspose(grid_, pressure_, ones.data(), ou.data(), ov.data());
  const bool px = pressure_.x.low == EndKind::kPeriodic, py = pressure_.y.low == EndKind::kPeriodic;
  for (int j = 0; j <= grid_.ny; ++j) {
    for (int i = 0; i <= grid_.nx; ++i) {
      const bool inside = (px || (i > 0 && i < grid_.nx)) && (py || (j > 0 && j < grid_.ny));
      if (!inside) continue;
      EXPECT_NEAR(ou[grid_.Index(i, j)], 0.0, 1e-15) << i << "," << j;
      EXPECT_NEAR(ov[grid_.Index(i, j)], 0.0, 1e-15) << i << "," << j;
    }
  }
}

// G_x x = int phi_i (and G_y y) at every row, boundary rows included, where the axis is not
// periodic.
TEST_P(OperatorsTest, GradientOfCoordinateIsBasisIntegral) {
  const Eigen::VectorXd basis_integral = AssembleConsistentMass(grid_, velocity_) *
                                         Eigen::VectorXd::Ones(Eigen::Index(grid_.NodeCount()));
  std::vector<double> fx(grid_.NodeCount()), fy(grid_.NodeCount());
  for (int j = 0; j <= grid_.ny; ++j) {
    for (int i = 0; i <= grid_.nx; ++i) {
      fx[grid_.Index(i, j)] = grid_.X(i);
      fy[grid_.Index(i, j)] = grid_.Y(j);
    }
  }
  std::vector<double> gx(grid_.NodeCount()), gy(grid_.NodeCount()), unused(grid_.NodeCount());
  ApplyIntegratedGradient(grid_, velocity_, fx.data(), gx.data(), unused.data());
  ApplyIntegratedGradient(grid_, velocity_, fy.data(), unused.data(), gy.data());
  if (velocity_.x.low != EndKind::kPeriodic) {
    EXPECT_LT(RelativeDifference(gx, basis_integral), kTolerance);
  }
  if (velocity_.y.low != EndKind::kPeriodic) {
    EXPECT_LT(RelativeDifference(gy, basis_integral), kTolerance);
  }
}

std::string CaseName(const ::testing::TestParamInfo<std::tuple<int, int>>& param) {
  return "mesh" + std::to_string(std::get<0>(param.param)) + "_" +
         Cases()[std::get<1>(param.param)].name;
}

INSTANTIATE_TEST_SUITE_P(MeshesAndTopologies, OperatorsTest,
                         ::testing::Combine(::testing::Values(0, 1),
                                            ::testing::Values(0, 1, 2, 3, 4)),
                         CaseName);

using Stencil = std::map<std::pair<int, int>, double>;

// The non-zero entries of one row of m, keyed by column-node offset from (ci, cj), in units of
// scale.
Stencil RowStencil(const Eigen::SparseMatrix<double>& m, const Grid& columns, std::size_t row,
                   int ci, int cj, double scale) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows(m);
  Stencil out;
  for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, Eigen::Index(row)); it;
       ++it) {
    if (std::abs(it.value()) < 1e-14 * scale) continue;
    const int col = int(it.col());
    out[{col % columns.NodesX() - ci, col / columns.NodesX() - cj}] = it.value() / scale;
  }
  return out;
}

void ExpectStencil(const Stencil& actual, const Stencil& expected, const std::string& what) {
  EXPECT_EQ(actual.size(), expected.size()) << what;
  for (const auto& [offset, value] : expected) {
    const auto it = actual.find(offset);
    ASSERT_NE(it, actual.end()) << what << " missing offset " << offset.first << ","
                                << offset.second;
    EXPECT_NEAR(it->second, value, 1e-14) << what << " at " << offset.first << "," << offset.second;
  }
}

class InteriorStencilTest : public ::testing::Test {
 protected:
  Grid grid_{8, 6, 0.125, 0.0, 0.0};
  BoundaryTopology walls_;  // all Dirichlet
};

TEST_F(InteriorStencilTest, StiffnessIsFivePointLaplacian) {
  ExpectStencil(RowStencil(AssembleStiffness(grid_, walls_), grid_, grid_.Index(3, 3), 3, 3, 1.0),
                {{{0, 0}, 4.0}, {{1, 0}, -1.0}, {{-1, 0}, -1.0}, {{0, 1}, -1.0}, {{0, -1}, -1.0}},
                "K");
  // Bottom edge and SW corner rows of the Neumann stiffness (pressure notes: [2; -1/2, -1/2, -1]).
  ExpectStencil(RowStencil(AssembleStiffness(grid_, walls_), grid_, grid_.Index(3, 0), 3, 0, 1.0),
                {{{0, 0}, 2.0}, {{1, 0}, -0.5}, {{-1, 0}, -0.5}, {{0, 1}, -1.0}}, "K edge");
  ExpectStencil(RowStencil(AssembleStiffness(grid_, walls_), grid_, grid_.Index(0, 0), 0, 0, 1.0),
                {{{0, 0}, 1.0}, {{1, 0}, -0.5}, {{0, 1}, -0.5}}, "K corner");
}

TEST_F(InteriorStencilTest, ConsistentMass) {
  const double h2 = grid_.h * grid_.h;
  const double e = 1.0 / 12.0;
  ExpectStencil(
      RowStencil(AssembleConsistentMass(grid_, walls_), grid_, grid_.Index(3, 3), 3, 3, h2),
      {{{0, 0}, 0.5},
       {{1, 0}, e},
       {{-1, 0}, e},
       {{0, 1}, e},
       {{0, -1}, e},
       {{1, 1}, e},
       {{-1, -1}, e}},
      "M");
}

TEST_F(InteriorStencilTest, IntegratedGradientFormulas) {
  const double s = 1.0 / 6.0;
  ExpectStencil(
      RowStencil(AssembleGradientX(grid_, walls_), grid_, grid_.Index(3, 3), 3, 3, grid_.h),
      {{{1, 0}, 2 * s}, {{-1, 0}, -2 * s}, {{0, -1}, s}, {{-1, -1}, -s}, {{1, 1}, s}, {{0, 1}, -s}},
      "Gx");
  ExpectStencil(
      RowStencil(AssembleGradientY(grid_, walls_), grid_, grid_.Index(3, 3), 3, 3, grid_.h),
      {{{0, 1}, 2 * s}, {{0, -1}, -2 * s}, {{1, 1}, s}, {{1, 0}, -s}, {{-1, 0}, s}, {{-1, -1}, -s}},
      "Gy");
}

TEST_F(InteriorStencilTest, DivergenceSixteenPoints) {
  const Stencil bx = {
      {{-2, -2}, -1.0 / 12}, {{0, -2}, 1.0 / 12},                                      //
      {{-2, -1}, -0.25},     {{-1, -1}, -0.25},   {{0, -1}, 0.25}, {{1, -1}, 0.25},    //
      {{-2, 0}, -1.0 / 6},   {{-1, 0}, -0.5},     {{1, 0}, 0.5},   {{2, 0}, 1.0 / 6},  //
      {{-1, 1}, -0.25},      {{0, 1}, -0.25},     {{1, 1}, 0.25},  {{2, 1}, 0.25},     //
      {{0, 2}, -1.0 / 12},   {{2, 2}, 1.0 / 12}};
  Stencil by;
  for (const auto& [offset, value] : bx) by[{offset.second, offset.first}] = value;
  const Grid coarse = grid_.Coarse();
  const std::size_t row = coarse.Index(2, 1);  // fine node (4, 2)
  ExpectStencil(RowStencil(AssembleDivergenceX(grid_, walls_), grid_, row, 4, 2, grid_.h), bx,
                "Bx");
  ExpectStencil(RowStencil(AssembleDivergenceY(grid_, walls_), grid_, row, 4, 2, grid_.h), by,
                "By");
}

// The velocity topology of the scene sides, and the pressure one the other way round.
TEST(BoundaryTopologyTest, FromSides) {
  DomainParams d;
  d.sides[int(Side::kLeft)].type = SideType::kVelocity;
  d.sides[int(Side::kRight)].type = SideType::kOutflow;
  d.sides[int(Side::kBottom)].type = SideType::kPeriodic;
  d.sides[int(Side::kTop)].type = SideType::kPeriodic;
  const BoundaryTopology v = BoundaryTopology::ForVelocity(d), p = BoundaryTopology::ForPressure(d);
  EXPECT_EQ(v.x.low, EndKind::kDirichlet);
  EXPECT_EQ(v.x.high, EndKind::kNeumann);
  EXPECT_EQ(v.y.low, EndKind::kPeriodic);
  EXPECT_EQ(p.x.low, EndKind::kNeumann);
  EXPECT_EQ(p.x.high, EndKind::kDirichlet);
  EXPECT_EQ(p.y.high, EndKind::kPeriodic);
  EXPECT_FALSE(v.HasNullSpace());
  const Grid g{4, 4, 0.25};
  EXPECT_FALSE(v.IsUnknown(g, 0, 1));
  EXPECT_TRUE(v.IsUnknown(g, 4, 1));
  EXPECT_TRUE(v.IsUnknown(g, 2, 0));
  EXPECT_FALSE(v.IsUnknown(g, 2, 4));  // periodic duplicate row
  EXPECT_TRUE(p.IsUnknown(g, 0, 1));
  EXPECT_FALSE(p.IsUnknown(g, 4, 1));

  DomainParams walls;
  EXPECT_FALSE(BoundaryTopology::ForVelocity(walls).HasNullSpace());
  EXPECT_TRUE(BoundaryTopology::ForPressure(walls).HasNullSpace());
  EXPECT_FALSE(BoundaryTopology::ForVelocity(walls).IsUnknown(g, 0, 0));
  EXPECT_TRUE(BoundaryTopology::ForPressure(walls).IsUnknown(g, 4, 4));
}

}  // namespace
}  // namespace dlmfd
