// Collision forces (14)-(15) and the cell-list neighbour search.
#include "dlmfd/particles/collision_forces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <utility>

namespace dlmfd {
namespace {

Params Box(double width, double height, double h, bool periodic_x, bool periodic_y) {
  Params params;
  params.domain.size = Vec2(width, height);
  params.domain.h = h;
  for (int s = 0; s < 4; ++s) {
    const bool periodic = s < 2 ? periodic_x : periodic_y;
    params.domain.sides[s].type = periodic ? SideType::kPeriodic : SideType::kWall;
  }
  return params;
}

// n disks of radii 0.02 to 0.1 at random centres in [0, width] x [0, height].
void RandomDisks(std::mt19937& rng, double width, double height, int n, std::vector<double>& radii,
                 std::vector<Vec2>& x) {
  std::uniform_real_distribution<double> ux(0.0, width), uy(0.0, height), ur(0.02, 0.1);
  radii.resize(n);
  x.resize(n);
  for (int i = 0; i < n; ++i) {
    radii[i] = ur(rng);
    x[i] = Vec2(ux(rng), uy(rng));
  }
}

// Cell lists must find exactly the pairs that all-pairs finds within the cell size.
void ExpectCellListEqualsAllPairs(bool periodic_x, bool periodic_y) {
  const Params params = Box(2.0, 3.0, 1.0 / 32, periodic_x, periodic_y);
  const Grid grid = params.domain.VelocityGrid();
  std::mt19937 rng(7);
  const int n = 400;
  std::vector<double> radii;
  std::vector<Vec2> x;
  RandomDisks(rng, 2.0, 3.0, n, radii, x);
  CollisionForces forces(params, grid, radii);
  const double cutoff = forces.CellSize();
  std::set<std::pair<int, int>> cell_pairs, all_pairs;
  forces.ForEachNearPair(x, [&](int i, int j, const Vec2& delta) {
    EXPECT_LT(i, j);
    if (delta.norm() < cutoff) {
      EXPECT_TRUE(cell_pairs.emplace(i, j).second) << "pair twice";
    }
  });
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (forces.MinimumImage(x[i] - x[j]).norm() < cutoff) all_pairs.emplace(i, j);
    }
  }
  EXPECT_GT(all_pairs.size(), 100u);
  EXPECT_EQ(cell_pairs, all_pairs);
}

TEST(CollisionForces, CellListFindsTheAllPairsNeighboursWithWalls) {
  ExpectCellListEqualsAllPairs(false, false);
}
TEST(CollisionForces, CellListFindsTheAllPairsNeighboursPeriodic) {
  ExpectCellListEqualsAllPairs(true, true);
}
TEST(CollisionForces, CellListFindsTheAllPairsNeighboursMixed) {
  ExpectCellListEqualsAllPairs(true, false);
}

TEST(CollisionForces, PairForceIsEquation14) {
  Params params = Box(2.0, 2.0, 1.0 / 96, false, false);
  const Grid grid = params.domain.VelocityGrid();
  CollisionForces forces(params, grid, {0.1, 0.1});
  const double rho = 1.5 / 96;
  const double d = 0.2 + 0.4 * rho;  // inside the range
  std::vector<Vec2> x = {Vec2(1.0, 1.0), Vec2(1.0 + 0.6 * d, 1.0 + 0.8 * d)}, f(2);
  EXPECT_EQ(forces.Compute(x, f), 1);
  const Vec2 expected = (x[0] - x[1]) * (0.2 + rho - d) * (0.2 + rho - d) / 2e-5;  // not normalised
  EXPECT_NEAR((f[0] - expected).norm(), 0.0, 1e-12 * expected.norm());
  EXPECT_NEAR((f[0] + f[1]).norm(), 0.0, 1e-15);
  // Out of range: no force.
  x[1] = Vec2(1.0, 1.0 + 0.2 + 1.01 * rho);
  EXPECT_EQ(forces.Compute(x, f), 0);
  EXPECT_EQ(f[0].norm(), 0.0);
}

TEST(CollisionForces, WallForceUsesTheMirrorImage) {
  Params params = Box(2.0, 2.0, 1.0 / 96, false, true);  // walls left and right only
  const Grid grid = params.domain.VelocityGrid();
  CollisionForces forces(params, grid, {0.1});
  const double rho = 1.5 / 96;
  const double distance = 0.1 + 0.3 * rho;             // centre to the left wall
  std::vector<Vec2> x = {Vec2(distance, 0.01)}, f(1);  // near the periodic bottom: no force from it
  EXPECT_EQ(forces.Compute(x, f), 1);
  const double d = 2 * distance;
  EXPECT_NEAR(f[0].x(), d * (0.2 + rho - d) * (0.2 + rho - d) / 1e-5, 1e-12);
  EXPECT_EQ(f[0].y(), 0.0);
  x[0] = Vec2(2.0 - distance, 1.0);  // right wall pushes to -x
  forces.Compute(x, f);
  EXPECT_LT(f[0].x(), 0.0);
}

TEST(CollisionForces, PeriodicPairInteractsAcrossTheSide) {
  Params params = Box(1.0, 1.0, 1.0 / 48, true, true);
  const Grid grid = params.domain.VelocityGrid();
  CollisionForces forces(params, grid, {0.1, 0.1});
  std::vector<Vec2> x = {Vec2(0.05, 0.5), Vec2(0.99 - 0.15, 0.5)}, f(2);
  // Image distance 0.05 + 0.01 + 0.15 = 0.21 < 0.2 + 1.5/48.
  EXPECT_EQ(forces.Compute(x, f), 1);
  EXPECT_GT(f[0].x(), 0.0);  // pushed to +x, away from the image at x = -0.16
  EXPECT_NEAR(forces.MinGap(x), 0.01, 1e-12);
}

// The gaps are true surface gaps, never capped at the cell size (issue 14: 0.231 reported where
// the gap was 0.202): every pair is examined when the cell lists find none near enough.
TEST(CollisionForces, GapsAreTrueSurfaceGapsBeyondTheCellSize) {
  const Params params = Box(2.0, 8.0, 1.0 / 96, false, false);
  const Grid grid = params.domain.VelocityGrid();
  CollisionForces forces(params, grid, {0.1, 0.1, 0.05});
  // Centres 0.6 apart in y: surface gap 0.4, beyond the cell size 0.2 + 1.5 h = 0.2156, where the
  // cell-list search alone stops.
  const std::vector<Vec2> x = {Vec2(1.0, 6.8), Vec2(1.0, 7.4), Vec2(0.3, 2.0)};
  ASSERT_GT(0.4, forces.CellSize());
  const CollisionForces::SurfaceGaps gaps = forces.Gaps(x);
  // Pairs: (0,1) 0.4; (0,2) and (1,2) about 4.8 apart.
  EXPECT_NEAR(gaps.pair, 0.4, 1e-12);
  EXPECT_EQ(gaps.first, 0);
  EXPECT_EQ(gaps.second, 1);
  // Walls: particle 2 is 0.3 - 0.05 = 0.25 from the left side; particles 0 and 1 are 0.9 from the
  // sides and particle 1 is 8 - 7.4 - 0.1 = 0.5 from the top.
  EXPECT_NEAR(gaps.wall, 0.25, 1e-12);
  EXPECT_EQ(gaps.wall_particle, 2);
  EXPECT_EQ(gaps.wall_side, static_cast<int>(Side::kLeft));
  EXPECT_NEAR(gaps.Min(), 0.25, 1e-12);
  int first = 0, second = 0;
  EXPECT_NEAR(forces.MinGap(x, &first, &second), 0.25, 1e-12);
  EXPECT_EQ(first, 2);
  EXPECT_EQ(second, -1 - static_cast<int>(Side::kLeft));
}

// The ring search past the neighbouring cells gives the smallest pair gap of every pair, to the
// bit (the same arithmetic per pair), for sparse particles whose nearest pair lies several cells
// apart, with walls, periodic sides, and a periodic ring that wraps onto itself.
void ExpectRingGapEqualsAllPairs(double width, double height, bool periodic_x, bool periodic_y) {
  const Params params = Box(width, height, 1.0 / 32, periodic_x, periodic_y);
  const Grid grid = params.domain.VelocityGrid();
  std::mt19937 rng(11);
  for (int n : {2, 3, 7, 20}) {
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<double> radii;
      std::vector<Vec2> x;
      RandomDisks(rng, width, height, n, radii, x);
      CollisionForces forces(params, grid, radii);
      double all_pairs = std::numeric_limits<double>::infinity();
      for (int i = 0; i < n; ++i) {
        for (int j = i + 1; j < n; ++j) {
          all_pairs =
              std::min(all_pairs, forces.MinimumImage(x[i] - x[j]).norm() - radii[i] - radii[j]);
        }
      }
      const CollisionForces::SurfaceGaps gaps = forces.Gaps(x);
      EXPECT_EQ(gaps.pair, all_pairs) << "n = " << n << ", trial " << trial;
      ASSERT_GE(gaps.first, 0);
      EXPECT_EQ(forces.MinimumImage(x[gaps.first] - x[gaps.second]).norm() - radii[gaps.first] -
                    radii[gaps.second],
                all_pairs);
    }
  }
}

TEST(CollisionForces, RingGapEqualsAllPairsWithWalls) {
  ExpectRingGapEqualsAllPairs(2.0, 7.0, false, false);
}
TEST(CollisionForces, RingGapEqualsAllPairsPeriodic) {
  ExpectRingGapEqualsAllPairs(3.0, 2.0, true, true);
}
TEST(CollisionForces, RingGapEqualsAllPairsMixed) {
  ExpectRingGapEqualsAllPairs(0.7, 6.0, true, false);  // 2 periodic cells: the ring wraps
}

TEST(CollisionForces, GapsWithNothingToMeasureAreNaN) {
  const Params params = Box(1.0, 1.0, 1.0 / 48, true, true);
  const Grid grid = params.domain.VelocityGrid();
  CollisionForces forces(params, grid, {0.1});
  const CollisionForces::SurfaceGaps gaps = forces.Gaps({Vec2(0.5, 0.5)});
  EXPECT_TRUE(std::isnan(gaps.pair));  // one particle: no pair
  EXPECT_TRUE(std::isnan(gaps.wall));  // periodic box: no wall
  EXPECT_TRUE(std::isnan(gaps.Min()));
}

}  // namespace
}  // namespace dlmfd
