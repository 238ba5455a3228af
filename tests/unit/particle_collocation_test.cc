// Collocation multiplier points (particles/collocation_points.h) and the quadratic coupling of the
// sharp-boundary DLM variant (particle_mesh.kind = "collocation"): the points lie where the method
// note puts them, the P2 macro-triangle stencil reproduces quadratics and the Q2 macro-square
// stencil biquadratics (so both rigid motions exactly) at every point, the constraint holds at the
// points after (37), and momentum is conserved.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "../../engine/src/mesh/macro_triangle_stencil.h"
#include "../support/constraint_disk_scene.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/particles/collocation_points.h"
#include "dlmfd/particles/rigid_body_constraint.h"

namespace dlmfd {
namespace {

TEST(CollocationPoints, BoundaryPointsOnTheCircleAndInteriorPointsClearOfThem) {
  const double radius = 0.1, h = 1.0 / 48;
  for (double spacing : {1.0, 1.5, 2.0}) {
    const CollocationPoints points(Shape::Disk(radius), h, spacing,
                                   BoundaryInterpolation::kQuadratic);
    const int nb = static_cast<int>(std::floor(2 * kPi * radius / (spacing * h)));
    ASSERT_EQ(points.BoundaryCount(), nb);
    ASSERT_GT(points.Count(), nb);
    for (int k = 0; k < points.Count(); ++k) {
      const Vec2 r = points.points()[k];
      if (k < nb) {
        EXPECT_NEAR(r.norm(), radius, 1e-15);
        EXPECT_TRUE(points.Quadratic(k));
        continue;
      }
      EXPECT_FALSE(points.Quadratic(k));
      EXPECT_LT(r.norm(), radius);
      // On the lattice of spacing h through the centre.
      EXPECT_NEAR(r.x() / h, std::round(r.x() / h), 1e-12);
      EXPECT_NEAR(r.y() / h, std::round(r.y() / h), 1e-12);
      for (int b = 0; b < nb; ++b) {
        EXPECT_GE((r - points.points()[b]).norm(), std::sqrt(2.0) * h * (1 - 1e-12));
      }
    }
  }
  const CollocationPoints linear(Shape::Disk(radius), h, 1.5, BoundaryInterpolation::kLinear);
  for (int k = 0; k < linear.Count(); ++k) EXPECT_FALSE(linear.Quadratic(k));
  EXPECT_THROW(CollocationPoints(Shape::Disk(radius), h, 0.0, BoundaryInterpolation::kQuadratic),
               InvalidParameter);
}

// The P2 stencil: weights sum to 1 and reproduce x, y, x^2, x y, y^2 at points anywhere, also in
// the last macro square of a periodic axis (whose third node line wraps to line 0).
TEST(MacroTriangleStencil, ReproducesQuadraticsExactly) {
  const Grid grid{16, 12, 0.125, -0.3, 0.2};
  for (const bool periodic : {false, true}) {
    for (int n = 0; n < 200; ++n) {
      const double x = grid.x0 + grid.Width() * std::fmod(0.6180339887 * n, 1.0);
      const double y = grid.y0 + grid.Height() * std::fmod(0.7548776662 * n + 0.1, 1.0);
      kernels::P2Stencil s;
      int side = -1;
      ASSERT_TRUE(kernels::LocatePointQuadratic(grid, periodic, periodic, x, y, &s, &side));
      double sum[6] = {};
      for (int q = 0; q < 6; ++q) {
        double xq = grid.X(s.i[q]), yq = grid.Y(s.j[q]);
        // A wrapped node stands for the node one period on.
        if (periodic && xq < x - 2.5 * grid.h) xq += grid.Width();
        if (periodic && yq < y - 2.5 * grid.h) yq += grid.Height();
        const double monomials[6] = {1.0, xq, yq, xq * xq, xq * yq, yq * yq};
        for (int m = 0; m < 6; ++m) sum[m] += s.weight[q] * monomials[m];
      }
      const double exact[6] = {1.0, x, y, x * x, x * y, y * y};
      for (int m = 0; m < 6; ++m) EXPECT_NEAR(sum[m], exact[m], 1e-14) << "monomial " << m;
    }
  }
  kernels::P2Stencil s;
  int side = -1;
  EXPECT_FALSE(kernels::LocatePointQuadratic(grid, false, false, grid.x0 - 1e-9, 0.5, &s, &side));
  EXPECT_EQ(side, 0);
}

// The Q2 stencil (particle_mesh.interpolation = biquadratic): weights sum to 1 and reproduce every
// monomial x^a y^b with a, b <= 2 at points anywhere, also across a periodic axis; and the weights
// at (x, y) and at its mirror image in the macro square's middle line y = const are the same node
// for node mirrored (the P2 stencil's are not: its macro-triangles have one diagonal).
TEST(MacroTriangleStencil, BiquadraticReproducesQ2AndIsMirrorSymmetric) {
  const Grid grid{16, 12, 0.125, -0.3, 0.2};
  for (const bool periodic : {false, true}) {
    for (int n = 0; n < 200; ++n) {
      const double x = grid.x0 + grid.Width() * std::fmod(0.6180339887 * n, 1.0);
      const double y = grid.y0 + grid.Height() * std::fmod(0.7548776662 * n + 0.1, 1.0);
      kernels::Q2Stencil s;
      int side = -1;
      ASSERT_TRUE(kernels::LocatePointBiquadratic(grid, periodic, periodic, x, y, &s, &side));
      double sum[9] = {};
      for (int q = 0; q < 9; ++q) {
        double xq = grid.X(s.i[q]), yq = grid.Y(s.j[q]);
        if (periodic && xq < x - 2.5 * grid.h) xq += grid.Width();
        if (periodic && yq < y - 2.5 * grid.h) yq += grid.Height();
        for (int b = 0; b < 3; ++b) {
          for (int a = 0; a < 3; ++a)
            sum[3 * b + a] += s.weight[q] * std::pow(xq, a) * std::pow(yq, b);
        }
      }
      for (int b = 0; b < 3; ++b) {
        for (int a = 0; a < 3; ++a) {
          EXPECT_NEAR(sum[3 * b + a], std::pow(x, a) * std::pow(y, b), 1e-13)
              << "x^" << a << " y^" << b;
        }
      }
    }
  }
  // Macro square (2, 1): its rows of nodes j = 2, 3, 4; a point at eta and its mirror at 1 - eta.
  for (const double xi : {0.1, 0.37, 0.8}) {
    for (const double eta : {0.05, 0.3, 0.45}) {
      const kernels::Q2Stencil a =
          kernels::Q2StencilInMacroSquare(grid, false, false, 2, 1, xi, eta);
      const kernels::Q2Stencil b =
          kernels::Q2StencilInMacroSquare(grid, false, false, 2, 1, xi, 1.0 - eta);
      for (int q = 0; q < 9; ++q) {
        const int mirrored = 3 * (2 - q / 3) + q % 3;
        EXPECT_EQ(a.i[q], b.i[mirrored]);
        EXPECT_EQ(a.j[q] - 2, 4 - b.j[mirrored]);
        EXPECT_NEAR(a.weight[q], b.weight[mirrored], 1e-15);
      }
    }
  }
}

// domain.diagonals = "both": the mean of the two macro-diagonals' P2 stencils reproduces every
// polynomial of degree <= 2, and the mean of the two diagonals' P1 stencils every linear, at points
// anywhere, also across a periodic axis; the P2 mean is mirror-symmetric in x and in y (a point and
// its mirror images in the macro square's middle lines get mirrored weights), which the
// one-diagonal P2 is not (tests/convergence/mirror_lift_test.cc).
TEST(MacroTriangleStencil, MeansOverBothDiagonalsReproducePolynomialsAndAreMirrorSymmetric) {
  const Grid grid{16, 12, 0.125, -0.3, 0.2};
  for (const bool periodic : {false, true}) {
    for (int n = 0; n < 200; ++n) {
      const double x = grid.x0 + grid.Width() * std::fmod(0.6180339887 * n, 1.0);
      const double y = grid.y0 + grid.Height() * std::fmod(0.7548776662 * n + 0.1, 1.0);
      kernels::Q2Stencil quadratic;
      kernels::MeanP1Stencil linear;
      int side = -1;
      ASSERT_TRUE(
          kernels::LocatePointMeanQuadratic(grid, periodic, periodic, x, y, &quadratic, &side));
      ASSERT_TRUE(kernels::LocatePointMean(grid, periodic, periodic, x, y, &linear, &side));
      double sum[6] = {}, lsum[3] = {};
      auto node = [&](int i, int j, double reach) {
        double xq = grid.X(i), yq = grid.Y(j);
        if (periodic && xq < x - reach) xq += grid.Width();
        if (periodic && yq < y - reach) yq += grid.Height();
        return Vec2(xq, yq);
      };
      for (int q = 0; q < 9; ++q) {
        const Vec2 r = node(quadratic.i[q], quadratic.j[q], 2.5 * grid.h);
        const double monomials[6] = {1.0,           r.x(),         r.y(),
                                     r.x() * r.x(), r.x() * r.y(), r.y() * r.y()};
        for (int m = 0; m < 6; ++m) sum[m] += quadratic.weight[q] * monomials[m];
      }
      for (int q = 0; q < 4; ++q) {
        const Vec2 r = node(linear.i[q], linear.j[q], 1.5 * grid.h);
        const double monomials[3] = {1.0, r.x(), r.y()};
        for (int m = 0; m < 3; ++m) lsum[m] += linear.weight[q] * monomials[m];
      }
      const double exact[6] = {1.0, x, y, x * x, x * y, y * y};
      for (int m = 0; m < 6; ++m) EXPECT_NEAR(sum[m], exact[m], 1e-13) << "monomial " << m;
      for (int m = 0; m < 3; ++m) EXPECT_NEAR(lsum[m], exact[m], 1e-14) << "monomial " << m;
    }
  }
  // Macro square (2, 1) (node lines i = 4..6, j = 2..4): a point at (xi, eta) and its mirror images
  // at (1 - xi, eta) and (xi, 1 - eta).
  for (const double xi : {0.1, 0.37, 0.8}) {
    for (const double eta : {0.05, 0.3, 0.45}) {
      const kernels::Q2Stencil a =
          kernels::MeanP2StencilInMacroSquare(grid, false, false, 2, 1, xi, eta);
      const kernels::Q2Stencil mx =
          kernels::MeanP2StencilInMacroSquare(grid, false, false, 2, 1, 1.0 - xi, eta);
      const kernels::Q2Stencil my =
          kernels::MeanP2StencilInMacroSquare(grid, false, false, 2, 1, xi, 1.0 - eta);
      for (int q = 0; q < 9; ++q) {
        const int a_x = q % 3, b_y = q / 3;
        EXPECT_NEAR(a.weight[q], mx.weight[3 * b_y + (2 - a_x)], 1e-15);
        EXPECT_NEAR(a.weight[q], my.weight[3 * (2 - b_y) + a_x], 1e-15);
      }
    }
  }
}

// The constraint tests' disk (support/constraint_disk_scene.h) on collocation points.
struct CollocationScene : testing::ConstraintDiskScene {
  CollocationScene(double density, BoundaryInterpolation interpolation,
                   MeshDiagonals diagonals = MeshDiagonals::kSwNe)
      : ConstraintDiskScene(density) {
    params.domain.diagonals = diagonals;
    params.particle_mesh.kind = ParticleMeshKind::kCollocation;
    params.particle_mesh.interpolation = interpolation;
  }
  // The fluid velocity at point k by the point's own stencil (quadratic or linear), written from
  // the stencil kernels.
  Vec2 AtPoint(const MultiplierPoints& points, int k) const {
    const Vec2 y = particles[0].position + points.Points(0)[k];
    Vec2 out = Vec2::Zero();
    int side = 0;
    const bool both = params.domain.diagonals == MeshDiagonals::kBoth;
    auto add = [&](const auto& s) {
      constexpr int kNodes = static_cast<int>(sizeof(s.weight) / sizeof(s.weight[0]));
      for (int q = 0; q < kNodes; ++q) {
        const std::size_t n = grid.Index(s.i[q], s.j[q]);
        out += s.weight[q] * Vec2(u[n], v[n]);
      }
    };
    if (points.Quadratic(0, k) &&
        params.particle_mesh.interpolation == BoundaryInterpolation::kBiquadratic) {
      kernels::Q2Stencil s;
      EXPECT_TRUE(kernels::LocatePointBiquadratic(grid, false, false, y.x(), y.y(), &s, &side));
      add(s);
    } else if (points.Quadratic(0, k) && both) {
      kernels::Q2Stencil s;
      EXPECT_TRUE(kernels::LocatePointMeanQuadratic(grid, false, false, y.x(), y.y(), &s, &side));
      add(s);
    } else if (points.Quadratic(0, k)) {
      kernels::P2Stencil s;
      EXPECT_TRUE(kernels::LocatePointQuadratic(grid, false, false, y.x(), y.y(), &s, &side));
      add(s);
    } else if (both) {
      kernels::MeanP1Stencil s;
      EXPECT_TRUE(kernels::LocatePointMean(grid, false, false, y.x(), y.y(), &s, &side));
      add(s);
    } else {
      kernels::P1Stencil s;
      EXPECT_TRUE(kernels::LocatePoint(grid, false, false, y.x(), y.y(), &s, &side));
      add(s);
    }
    return out;
  }
  double MaxMismatch(const MultiplierPoints& points) const {
    const ParticleState& p = particles[0];
    double worst = 0.0;
    for (int k = 0; k < points.Count(0); ++k) {
      const Vec2 r = points.Points(0)[k];
      const Vec2 rigid = p.velocity + p.angular_velocity * Vec2(-r.y(), r.x());
      worst = std::max(worst, (AtPoint(points, k) - rigid).norm());
    }
    return worst;
  }
};

// A fluid in rigid motion (translation + rotation) is interpolated exactly, to round-off, at every
// collocation point, so the constraint step has nothing to do and leaves it untouched.
// Also on both diagonals (domain.diagonals = "both": the mean P1 and P2 stencils).
TEST(CollocationConstraint, RigidMotionIsReproducedExactlyAtThePoints) {
  for (const auto interpolation :
       {BoundaryInterpolation::kQuadratic, BoundaryInterpolation::kLinear,
        BoundaryInterpolation::kBiquadratic}) {
    for (const MeshDiagonals diagonals : {MeshDiagonals::kSwNe, MeshDiagonals::kBoth}) {
      CollocationScene s(1.5, interpolation, diagonals);
      s.Rigid(s.particles[0].velocity, s.particles[0].angular_velocity);
      RigidBodyConstraint dlm(s.params, s.grid);
      EXPECT_LT(s.MaxMismatch(dlm.Points()), 1e-15);
      const std::vector<double> u0 = s.u, v0 = s.v;
      const RigidBodyConstraint::Outcome out =
          dlm.Enforce(0.0, 4e-4, s.particles, s.u.data(), s.v.data());
      EXPECT_LT(out.cold_residual, 1e-15);
      double change = 0.0;
      for (std::size_t n = 0; n < u0.size(); ++n) {
        change = std::max({change, std::abs(s.u[n] - u0[n]), std::abs(s.v[n] - v0[n])});
      }
      EXPECT_LT(change, 1e-14);
      EXPECT_NEAR(s.particles[0].velocity.x(), 0.1, 1e-14);
      EXPECT_NEAR(s.particles[0].angular_velocity, 0.5, 1e-13);
    }
  }
}

// After (37) the fluid velocity is rigid at every collocation point to the CG tolerance (the
// Euclidean product: |g|_2 <= tol |g0|_2), and the linear and angular momentum of fluid plus
// excess particle are those before (E reproduces constants and linears: a round-off identity).
TEST(CollocationConstraint, ConstraintHoldsAtThePointsAndMomentumIsConserved) {
  for (const auto interpolation :
       {BoundaryInterpolation::kQuadratic, BoundaryInterpolation::kLinear,
        BoundaryInterpolation::kBiquadratic}) {
    for (const MeshDiagonals diagonals : {MeshDiagonals::kSwNe, MeshDiagonals::kBoth}) {
      const double tol = 1e-10;
      CollocationScene s(1.01, interpolation, diagonals);
      s.params.solvers.multiplier_tolerance = tol;
      s.Vortical();
      RigidBodyConstraint dlm(s.params, s.grid);
      const MultiplierPoints& points = dlm.Points();
      double g0 = 0.0;
      {
        const ParticleState& p = s.particles[0];
        for (int k = 0; k < points.Count(0); ++k) {
          const Vec2 r = points.Points(0)[k];
          g0 += (s.AtPoint(points, k) - p.velocity - p.angular_velocity * Vec2(-r.y(), r.x()))
                    .squaredNorm();
        }
      }
      const double m = s.params.fluid.density * s.grid.h * s.grid.h;
      const double me = 0.01 * kPi * 0.01, je = me * 0.01 / 2;
      auto momentum = [&](Vec2* linear, double* angular) {
        const ParticleState& p = s.particles[0];
        *linear = me * p.velocity;
        *angular = je * p.angular_velocity;
        for (int j = 1; j < s.grid.ny; ++j) {
          for (int i = 1; i < s.grid.nx; ++i) {
            const std::size_t n = s.grid.Index(i, j);
            const Vec2 r = Vec2(s.grid.X(i), s.grid.Y(j)) - p.position;
            *linear += m * Vec2(s.u[n], s.v[n]);
            *angular += m * (r.x() * s.v[n] - r.y() * s.u[n]);
          }
        }
      };
      Vec2 l0, l1;
      double a0, a1;
      momentum(&l0, &a0);
      const double before = s.MaxMismatch(points);
      const RigidBodyConstraint::Outcome out =
          dlm.Enforce(0.0, 4e-4, s.particles, s.u.data(), s.v.data());
      const double after = s.MaxMismatch(points);
      momentum(&l1, &a1);
      std::printf("%s%s: %d points, %d iterations, mismatch %.3e -> %.3e\n",
                  interpolation == BoundaryInterpolation::kQuadratic     ? "quadratic"
                  : interpolation == BoundaryInterpolation::kBiquadratic ? "biquadratic"
                                                                         : "linear",
                  diagonals == MeshDiagonals::kBoth ? " (both diagonals)" : "", points.Count(0),
                  out.iterations, before, after);
      EXPECT_GT(before, 0.1);
      EXPECT_LE(after, tol * std::sqrt(g0) + 1e-13);
      EXPECT_NEAR(out.residual, after, 1e-12);
      EXPECT_NEAR((l1 - l0).norm(), 0.0, 1e-15);
      EXPECT_NEAR(a1 - a0, 0.0, 1e-15);
    }
  }
}

}  // namespace
}  // namespace dlmfd
