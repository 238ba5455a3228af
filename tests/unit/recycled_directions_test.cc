// The viscous coupling's recycled PCG directions (particles/recycled_directions.h): the Galerkin
// start on a known symmetric positive definite operator, the store's capacity, and which scenes
// keep directions.
#include "dlmfd/particles/recycled_directions.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

namespace dlmfd {
namespace {

// S = the 4 x 4 matrix below (symmetric, positive definite); stores the directions d with S d.
void StoreDirections(RecycledDirections& store, const Eigen::Matrix4d& s,
                     const std::vector<Eigen::Vector4d>& directions) {
  for (const Eigen::Vector4d& d : directions) {
    const Eigen::Vector4d sd = s * d;
    store.Add({d.data(), d.data() + 4}, {sd.data(), sd.data() + 4}, {}, {}, {}, {}, {});
  }
}

Eigen::Matrix4d Spd() {
  Eigen::Matrix4d a;
  a << 4, 1, 0, 0.5, 1, 3, 0.2, 0, 0, 0.2, 2, 0.1, 0.5, 0, 0.1, 1;
  return a;
}

// When the stored directions span the space, the Galerkin start solves S nu = -g exactly; with
// fewer, its error is S-orthogonal to their span (the energy norm's best in it).
TEST(RecycledDirections, GalerkinStartIsTheBestInTheStoredSpan) {
  const Eigen::Matrix4d s = Spd();
  const Eigen::Vector4d g(1.0, -2.0, 0.5, 3.0);
  const std::vector<double> gv(g.data(), g.data() + 4);
  const std::vector<Eigen::Vector4d> all = {{1, 0, 0, 0}, {1, 1, 0, 0}, {0, 1, 1, 0}, {0, 0, 1, 1}};

  RecycledDirections full;
  StoreDirections(full, s, all);
  RecycledDirections::Coefficient a = full.Coefficients(gv);
  Eigen::Vector4d nu = Eigen::Vector4d::Zero();
  for (int i = 0; i < 4; ++i) nu += a(i) * all[static_cast<std::size_t>(i)];
  EXPECT_LT((s * nu + g).norm(), 1e-12);
  for (int i = 4; i < RecycledDirections::kCapacity; ++i) EXPECT_EQ(a(i), 0.0);

  RecycledDirections two;
  StoreDirections(two, s, {all[0], all[2]});
  a = two.Coefficients(gv);
  nu = a(0) * all[0] + a(1) * all[2];
  const Eigen::Vector4d residual = s * nu + g;
  EXPECT_LT(std::abs(all[0].dot(residual)), 1e-12);
  EXPECT_LT(std::abs(all[2].dot(residual)), 1e-12);
}

// A repeated (dependent) direction does not break the start: the decomposition takes the
// minimum-norm solution.
TEST(RecycledDirections, DependentDirectionsStillGiveTheStart) {
  const Eigen::Matrix4d s = Spd();
  const Eigen::Vector4d g(0.0, 1.0, 0.0, 0.0);
  const std::vector<double> gv(g.data(), g.data() + 4);
  const Eigen::Vector4d d(0.0, 1.0, 0.0, 0.0);
  RecycledDirections store;
  StoreDirections(store, s, {d, d});
  const RecycledDirections::Coefficient a = store.Coefficients(gv);
  const Eigen::Vector4d nu = (a(0) + a(1)) * d;
  EXPECT_NEAR(d.dot(s * nu + g), 0.0, 1e-12);
}

// The store holds the last kCapacity directions.
TEST(RecycledDirections, KeepsTheLastCapacityDirections) {
  RecycledDirections store;
  for (int i = 0; i < RecycledDirections::kCapacity + 5; ++i) {
    store.Add({static_cast<double>(i)}, {1.0}, {}, {}, {}, {}, {});
  }
  ASSERT_EQ(store.Count(), RecycledDirections::kCapacity);
  std::vector<double> kept;
  for (int i = 0; i < store.Count(); ++i) kept.push_back(store.At(i).d[0]);
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(kept.front(), 5.0);
  EXPECT_EQ(kept.back(), RecycledDirections::kCapacity + 4.0);
}

// Only the viscous coupling with every particle fixed keeps directions (S is then the same
// operator at every step).
TEST(RecycledDirections, UsedWhenEveryParticleIsFixedUnderTheViscousCoupling) {
  Params params;
  params.splitting.constraint = ConstraintCoupling::kViscous;
  EXPECT_FALSE(RecycledDirections::Used(params));  // no particle
  ParticleParams disk;
  disk.motion = Motion::kFixed;
  params.particles = {disk, disk};
  EXPECT_TRUE(RecycledDirections::Used(params));
  params.particles[1].motion = Motion::kPrescribed;
  EXPECT_FALSE(RecycledDirections::Used(params));
  params.particles[1].motion = Motion::kFixed;
  params.splitting.constraint = ConstraintCoupling::kIncremental;
  EXPECT_FALSE(RecycledDirections::Used(params));
}

}  // namespace
}  // namespace dlmfd
