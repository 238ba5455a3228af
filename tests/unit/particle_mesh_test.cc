// The ring mesh of a disk (method notes 2, 1.1) and its H1 Gram matrix G = M + R^2 K (paper (24)).
#include "dlmfd/particles/particle_mesh.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

TEST(ParticleMesh, PaperMeshHasSevenRingsAnd177Nodes) {
  const ParticleMesh mesh(0.1, 1.0 / 70);  // D = 0.2, h_p = 1/70 (notes 1.1)
  EXPECT_EQ(mesh.RingCount(), 7);
  EXPECT_EQ(mesh.NodeCount(), 177);
  // Ring k holds round(2 pi k) nodes: 6 13 19 25 31 38 44; the outer 44 lie on the circle.
  int on_circle = 0;
  for (const Vec2& x : mesh.nodes()) {
    if (std::abs(x.norm() - 0.1) < 1e-15) ++on_circle;
  }
  EXPECT_EQ(on_circle, 44);
  // Euler: a triangulated disk with n nodes and b boundary nodes has 2n - b - 2 triangles.
  EXPECT_EQ(static_cast<int>(mesh.triangles().size()), 2 * 177 - 44 - 2);
}

TEST(ParticleMesh, TrianglesArePositiveAndTileTheInscribedPolygon) {
  for (double hp : {1.0 / 20, 1.0 / 35, 1.0 / 70, 1.0 / 140}) {
    const ParticleMesh mesh(0.1, hp);
    for (const auto& t : mesh.triangles()) {
      const Vec2 a = mesh.nodes()[t[1]] - mesh.nodes()[t[0]];
      const Vec2 b = mesh.nodes()[t[2]] - mesh.nodes()[t[0]];
      ASSERT_GT(a.x() * b.y() - a.y() * b.x(), 0.0);
    }
    // The outer ring is a regular polygon with n nodes: area n/2 R^2 sin(2 pi/n). Equal to
    // round-off only if the triangles neither overlap nor leave holes.
    const int n = static_cast<int>(std::lround(2 * kPi * 0.1 / hp));
    const double polygon = 0.5 * n * 0.01 * std::sin(2 * kPi / n);
    EXPECT_NEAR(mesh.Area(), polygon, 1e-15);
  }
}

TEST(ParticleMesh, AreaConvergesToTheDiskAtSecondOrder) {
  // pi R^2 - polygon area = pi R^2 (2 pi / n)^2 / 6 + O(n^-4) with n ~ 2 pi R / h_p: order 2 up to
  // the rounding of n (which moves the observed order by less than 0.1 on these meshes).
  double previous = 0.0;
  for (int level = 0; level < 4; ++level) {
    const double hp = 1.0 / (35 << level);
    const double error = kPi * 0.01 - ParticleMesh(0.1, hp).Area();
    if (level > 0) {
      const double order = std::log2(previous / error);
      std::printf("h_p = 1/%d: area error %.3e, observed order %.3f\n", 35 << level, error, order);
      EXPECT_NEAR(order, 2.0, 0.1);
    }
    previous = error;
  }
}

TEST(ParticleMesh, GramMatrixIsSymmetricPositiveDefiniteAndExactOnLinears) {
  const double radius = 0.1;
  const ParticleMesh mesh(radius, 1.0 / 35);
  const Eigen::MatrixXd g = Eigen::MatrixXd(mesh.Gram());
  EXPECT_EQ((g - g.transpose()).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(g);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
  // Consistent P1 mass and stiffness are exact for products of linear functions:
  // 1^T M 1 = area, K 1 = 0, x^T K x = int |grad x|^2 = area, x^T M x = int x^2.
  const int n = mesh.NodeCount();
  Eigen::VectorXd one = Eigen::VectorXd::Ones(n), x(n);
  for (int k = 0; k < n; ++k) x[k] = mesh.nodes()[k].x();
  const double area = mesh.Area();
  EXPECT_NEAR(one.dot(mesh.Mass() * one), area, 1e-15);
  EXPECT_LT((mesh.Stiffness() * one).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_NEAR(x.dot(mesh.Stiffness() * x), area, 1e-14);
  EXPECT_NEAR(one.dot(mesh.Gram() * one), area, 1e-15);
  // ApplyGram2 equals the assembled G per component.
  Eigen::VectorXd y(n);
  for (int k = 0; k < n; ++k) y[k] = std::sin(7 * mesh.nodes()[k].y());
  std::vector<double> in(2 * n), out(2 * n);
  for (int k = 0; k < n; ++k) {
    in[2 * k] = x[k];
    in[2 * k + 1] = y[k];
  }
  mesh.ApplyGram2(in.data(), out.data());
  const Eigen::VectorXd gx = mesh.Gram() * x, gy = mesh.Gram() * y;
  for (int k = 0; k < n; ++k) {
    EXPECT_NEAR(out[2 * k], gx[k], 1e-15);
    EXPECT_NEAR(out[2 * k + 1], gy[k], 1e-15);
  }
}

TEST(ParticleMesh, RejectsNonPositiveSizes) {
  EXPECT_THROW(ParticleMesh(0.0, 0.01), InvalidParameter);
  EXPECT_THROW(ParticleMesh(0.1, -1.0), InvalidParameter);
}

}  // namespace
}  // namespace dlmfd
