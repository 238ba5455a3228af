// The polymer force of (33), f_i = -int grad phi_i : tau_p with tau_p = G (A - I), G =
// eta_p/lambda: against an independently assembled matrix (on the SW-NE triangles, and with
// domain.diagonals = "both" the mean of the SW-NE and the NW-SE matrices), against h^2 div tau for
// a linear tau at interior nodes, and zero for a uniform A away from the boundary.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <array>
#include <cmath>
#include <vector>

#include "dlmfd/conformation/polymer_force.h"
#include "dlmfd/core/constants.h"

namespace dlmfd {
namespace {

DomainParams Domain(const Grid& g, SideType x_sides, SideType y_sides,
                    MeshDiagonals diagonals = MeshDiagonals::kSwNe) {
  DomainParams d;
  d.diagonals = diagonals;
  d.size = Vec2(g.Width(), g.Height());
  d.h = g.h;
  d.sides[int(Side::kLeft)].type = d.sides[int(Side::kRight)].type = x_sides;
  d.sides[int(Side::kBottom)].type = d.sides[int(Side::kTop)].type = y_sides;
  return d;
}

// D_x, D_y with (D_x)_{ik} = int d_x phi_i phi_k, assembled triangle by triangle from the vertex
// coordinates (barycentric gradients by inverting the edge matrix), rows of periodic duplicates
// folded into the first node; on the SW-NE triangles, or half on each triangulation ("both").
struct AssembledDerivative {
  Eigen::SparseMatrix<double> dx, dy;
};

AssembledDerivative Assemble(const Grid& g, bool px, bool py, MeshDiagonals diagonals) {
  std::vector<Eigen::Triplet<double>> tx, ty;
  auto row_of = [&](int i, int j) {
    if (px && i == g.nx) i = 0;
    if (py && j == g.ny) j = 0;
    return int(g.Index(i, j));
  };
  for (int sj = 0; sj < g.ny; ++sj) {
    for (int si = 0; si < g.nx; ++si) {
      using Triangle = std::array<std::array<int, 2>, 3>;
      const Triangle sw_ne[2] = {{{{si, sj}, {si + 1, sj}, {si + 1, sj + 1}}},
                                 {{{si, sj}, {si + 1, sj + 1}, {si, sj + 1}}}};
      const Triangle nw_se[2] = {{{{si, sj}, {si + 1, sj}, {si, sj + 1}}},
                                 {{{si + 1, sj}, {si + 1, sj + 1}, {si, sj + 1}}}};
      std::vector<Triangle> triangles(sw_ne, sw_ne + 2);
      if (diagonals == MeshDiagonals::kBoth) triangles.insert(triangles.end(), nw_se, nw_se + 2);
      const double weight = diagonals == MeshDiagonals::kBoth ? 0.5 : 1.0;
      for (const Triangle& tri : triangles) {
        Eigen::Vector2d p[3];
        for (int a = 0; a < 3; ++a) p[a] = Eigen::Vector2d(g.X(tri[a][0]), g.Y(tri[a][1]));
        Eigen::Matrix2d edges;
        edges.col(0) = p[1] - p[0];
        edges.col(1) = p[2] - p[0];
        const double area = weight * 0.5 * std::abs(edges.determinant());
        const Eigen::Matrix2d inv_t = edges.inverse().transpose();
        // grad phi_1 = inv_t e1, grad phi_2 = inv_t e2, grad phi_0 = -(sum).
        Eigen::Vector2d grad[3];
        grad[1] = inv_t.col(0);
        grad[2] = inv_t.col(1);
        grad[0] = -grad[1] - grad[2];
        for (int a = 0; a < 3; ++a) {
          for (int b = 0; b < 3; ++b) {
            const int row = row_of(tri[a][0], tri[a][1]);
            const int col = int(g.Index(tri[b][0], tri[b][1]));
            tx.emplace_back(row, col, grad[a].x() * area / 3.0);
            ty.emplace_back(row, col, grad[a].y() * area / 3.0);
          }
        }
      }
    }
  }
  const int n = int(g.NodeCount());
  AssembledDerivative d{Eigen::SparseMatrix<double>(n, n), Eigen::SparseMatrix<double>(n, n)};
  d.dx.setFromTriplets(tx.begin(), tx.end());
  d.dy.setFromTriplets(ty.begin(), ty.end());
  return d;
}

struct Field {
  Eigen::VectorXd a11, a12, a22;
};

// A smooth SPD field (periodic when asked: a function of sin/cos of the box angles).
Field SmoothField(const Grid& g) {
  const int n = int(g.NodeCount());
  Field f{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const double x = 2 * kPi * (g.X(i) - g.x0) / g.Width(),
                   y = 2 * kPi * (g.Y(j) - g.y0) / g.Height();
      const int k = int(g.Index(i, j));
      f.a11[k] = 3.0 + std::sin(x) * std::cos(2 * y);
      f.a12[k] = 0.7 * std::cos(x + y);
      f.a22[k] = 2.5 + std::sin(2 * x - y);
    }
  }
  return f;
}

void ExpectEqualsAssembled(const Grid& g, bool px, bool py,
                           MeshDiagonals diagonals = MeshDiagonals::kSwNe) {
  const double modulus = 0.37;
  const Field a = SmoothField(g);
  const int n = int(g.NodeCount());
  std::vector<double> fx(n, 0.25), fy(n, -0.5);  // AddPolymerForce adds into what is there
  AddPolymerForce(g,
                  Domain(g, px ? SideType::kPeriodic : SideType::kWall,
                         py ? SideType::kPeriodic : SideType::kOutflow, diagonals),
                  modulus, a.a11.data(), a.a12.data(), a.a22.data(), fx.data(), fy.data());
  const AssembledDerivative d = Assemble(g, px, py, diagonals);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(n);
  const Eigen::VectorXd t11 = modulus * (a.a11 - ones), t12 = modulus * a.a12,
                        t22 = modulus * (a.a22 - ones);
  const Eigen::VectorXd ex = -(d.dx * t11 + d.dy * t12), ey = -(d.dx * t12 + d.dy * t22);
  const double scale = g.h * modulus * 4.0;  // f ~ h tau
  for (int k = 0; k < n; ++k) {
    EXPECT_NEAR(fx[k] - 0.25, ex[k], 1e-14 * scale) << "node " << k;
    EXPECT_NEAR(fy[k] + 0.5, ey[k], 1e-14 * scale) << "node " << k;
  }
}

TEST(AddPolymerForce, EqualsAssembledIntegralWithWallsAndOutflow) {
  ExpectEqualsAssembled(Grid{6, 5, 0.2, -0.4, 0.3}, false, false);
}

TEST(AddPolymerForce, EqualsAssembledIntegralWithPeriodicSides) {
  ExpectEqualsAssembled(Grid{6, 4, 0.25, 0.0, 0.0}, true, false);
  ExpectEqualsAssembled(Grid{6, 4, 0.25, 0.0, 0.0}, true, true);
}

TEST(AddPolymerForce, BothDiagonalsEqualTheMeanOfTheTwoAssembledIntegrals) {
  ExpectEqualsAssembled(Grid{6, 5, 0.2, -0.4, 0.3}, false, false, MeshDiagonals::kBoth);
  ExpectEqualsAssembled(Grid{6, 4, 0.25, 0.0, 0.0}, true, false, MeshDiagonals::kBoth);
  ExpectEqualsAssembled(Grid{6, 4, 0.25, 0.0, 0.0}, false, true, MeshDiagonals::kBoth);
  ExpectEqualsAssembled(Grid{6, 4, 0.25, 0.0, 0.0}, true, true, MeshDiagonals::kBoth);
}

TEST(AddPolymerForce, LinearStressGivesHSquaredDivergenceAtInteriorNodes) {
  // tau = G (A - I) linear in x and y: -int grad phi_i : tau = int phi_i div tau = h^2 div tau
  // at interior nodes (int phi_i = h^2), exactly.
  const Grid g{7, 6, 0.1, 0.2, -0.1};
  const double modulus = 2.0;
  const int n = int(g.NodeCount());
  std::vector<double> a11(n), a12(n), a22(n), fx(n, 0.0), fy(n, 0.0);
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const double x = g.X(i), y = g.Y(j);
      const std::size_t k = g.Index(i, j);
      a11[k] = 1.0 + (0.5 + 1.2 * x - 0.3 * y) / modulus;   // tau11 = 0.5 + 1.2 x - 0.3 y
      a12[k] = (0.1 - 0.8 * x + 2.0 * y) / modulus;         // tau12 = 0.1 - 0.8 x + 2.0 y
      a22[k] = 1.0 + (-0.2 + 0.4 * x + 0.9 * y) / modulus;  // tau22 = -0.2 + 0.4 x + 0.9 y
    }
  }
  AddPolymerForce(g, Domain(g, SideType::kWall, SideType::kWall), modulus, a11.data(), a12.data(),
                  a22.data(), fx.data(), fy.data());
  const double div_x = 1.2 + 2.0, div_y = -0.8 + 0.9;
  for (int j = 1; j < g.ny; ++j) {
    for (int i = 1; i < g.nx; ++i) {
      EXPECT_NEAR(fx[g.Index(i, j)], g.h * g.h * div_x, 1e-15);
      EXPECT_NEAR(fy[g.Index(i, j)], g.h * g.h * div_y, 1e-15);
    }
  }
}

TEST(AddPolymerForce, UniformConformationGivesNoInteriorForce) {
  const Grid g{8, 8, 0.125, 0.0, 0.0};
  const int n = int(g.NodeCount());
  std::vector<double> a11(n, 4.0), a12(n, 1.5), a22(n, 2.0), fx(n, 0.0), fy(n, 0.0);
  AddPolymerForce(g, Domain(g, SideType::kWall, SideType::kWall), 3.0, a11.data(), a12.data(),
                  a22.data(), fx.data(), fy.data());
  for (int j = 1; j < g.ny; ++j) {
    for (int i = 1; i < g.nx; ++i) {
      EXPECT_NEAR(fx[g.Index(i, j)], 0.0, 1e-15);
      EXPECT_NEAR(fy[g.Index(i, j)], 0.0, 1e-15);
    }
  }
  // On the left wall the traction -tau n integrates to h tau n: (h G 3, h G 1.5) at an edge node.
  EXPECT_NEAR(fx[g.Index(0, 4)], g.h * 3.0 * 3.0, 1e-14);
  EXPECT_NEAR(fy[g.Index(0, 4)], g.h * 3.0 * 1.5, 1e-14);
}

}  // namespace
}  // namespace dlmfd
