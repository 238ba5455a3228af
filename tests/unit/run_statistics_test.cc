// The statistics of a whole run (io/run_statistics.h) from diagnostics and particle records.
#include "dlmfd/io/run_statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace dlmfd {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The paper's section 5.3 case of eleven disks: D = 0.2, rho_L = 1, eta = 0.13, lambda_r = 1.3.
Params ElevenDiskFluid(int disks) {
  Params p;
  p.domain.size = Vec2(2.0, 8.0);
  p.fluid.density = 1.0;
  p.fluid.viscosity = 0.13;
  p.fluid.relaxation_time = 1.3;
  p.fluid.solvent_ratio = 0.5;
  p.gravity = Vec2(0.0, -981.0);
  for (int k = 0; k < disks; ++k) {
    ParticleParams d;
    d.diameter = 0.2;
    d.density = 1.01;
    p.particles.push_back(d);
  }
  return p;
}

// Records of particles moving at constant velocities from (x0, y0).
ParticleHistory Moving(const std::vector<Vec2>& start, const std::vector<Vec2>& velocity,
                       int records, double every) {
  ParticleHistory h;
  h.records = records;
  h.particles = start.size();
  for (int k = 0; k < records; ++k) {
    const double t = k * every;
    h.time.push_back(t);
    h.step.push_back(k);
    for (std::size_t p = 0; p < start.size(); ++p) {
      const Vec2 x = start[p] + t * velocity[p];
      h.position.push_back(x.x());
      h.position.push_back(x.y());
    }
  }
  return h;
}

TEST(RunStatistics, ExtremesOverEveryStepSkipNaN) {
  DiagnosticsTable t;
  t.header = {"step",    "time",     "wall_seconds", "particle_pair_gap", "particle_wall_gap",
              "max_trA", "min_eig_A"};
  t.rows = {{1, 0.1, 0, 0.231, kNaN, 2.0, 1.0},
            {2, 0.2, 0, 0.202, 0.5, 7.5, 0.25},
            {3, 0.3, 0, 0.210, 0.4, 3.0, 0.5}};
  const RunStatistics s = ComputeRunStatistics(ElevenDiskFluid(2), t, ParticleHistory{});
  EXPECT_EQ(s.min_gap, 0.202);
  EXPECT_EQ(s.min_wall_gap, 0.4);
  EXPECT_EQ(s.max_trA, 7.5);
  EXPECT_EQ(s.min_eig_A, 0.25);
  // No records: no fall speed, and so no dimensionless numbers.
  EXPECT_TRUE(std::isnan(s.mean_fall_speed));
  EXPECT_TRUE(std::isnan(s.reynolds));
}

TEST(RunStatistics, AbsentColumnsAreNaN) {
  DiagnosticsTable t;
  t.header = {"step", "time", "wall_seconds", "stokes_iterations"};
  t.rows = {{1, 0.1, 0, 10}};
  const RunStatistics s = ComputeRunStatistics(ElevenDiskFluid(0), t, ParticleHistory{});
  EXPECT_TRUE(std::isnan(s.min_gap));
  EXPECT_TRUE(std::isnan(s.min_wall_gap));
  EXPECT_TRUE(std::isnan(s.max_trA));
  EXPECT_TRUE(std::isnan(s.min_eig_A));
}

// U over the last half of the records, from the displacement: exact for a constant velocity,
// including across a periodic side, where the positions are wrapped into the domain.
TEST(RunStatistics, FallSpeedOverTheLastHalfAcrossAPeriodicSide) {
  Params p = ElevenDiskFluid(2);
  p.domain.sides[static_cast<int>(Side::kBottom)].type = SideType::kPeriodic;
  p.domain.sides[static_cast<int>(Side::kTop)].type = SideType::kPeriodic;
  // Records every 0.25 up to t = 10; particle 0 falls at 0.2 from y = 1 and crosses the periodic
  // bottom at t = 5, particle 1 falls at 0.1 and drifts in x.
  ParticleHistory h =
      Moving({Vec2(1.0, 1.0), Vec2(0.5, 7.0)}, {Vec2(0, -0.2), Vec2(0.01, -0.1)}, 41, 0.25);
  for (std::size_t k = 0; k < h.position.size(); k += 2) {
    double& y = h.position[k + 1];
    y -= 8.0 * std::floor(y / 8.0);  // the engine wraps positions into [0, 8)
  }
  const RunStatistics s = ComputeRunStatistics(p, DiagnosticsTable{}, h);
  EXPECT_DOUBLE_EQ(s.fall_window_start, 5.0);
  EXPECT_DOUBLE_EQ(s.fall_window_end, 10.0);
  ASSERT_EQ(s.fall_speed.size(), 2u);
  EXPECT_NEAR(s.fall_speed[0], 0.2, 1e-12);
  EXPECT_NEAR(s.fall_speed[1], 0.1, 1e-12);
  EXPECT_NEAR(s.mean_fall_speed, 0.15, 1e-12);
  EXPECT_DOUBLE_EQ(s.diameter, 0.2);
}

// Re, De, M and E as the paper defines them (section 1), against its section 5.3 numbers for the
// eleven disks: U = 0.2 gives "De = 1.3, Re = 0.31, M = 0.63, E = 4.19". The paper rounds Re to
// 0.31 before E = De / Re (1.3 / 0.31 = 4.19; unrounded 1.3 / 0.3077 = 4.225): hence 1 % on E, and
// half a unit of the paper's last digit on the others.
TEST(RunStatistics, DimensionlessNumbersOfThePaper) {
  const ParticleHistory h =
      Moving({Vec2(0.9, 7.0), Vec2(1.1, 7.0)}, {Vec2(0, -0.2), Vec2(0, -0.2)}, 11, 0.5);
  const RunStatistics s = ComputeRunStatistics(ElevenDiskFluid(2), DiagnosticsTable{}, h);
  EXPECT_NEAR(s.mean_fall_speed, 0.2, 1e-12);
  EXPECT_NEAR(s.reynolds, 1.0 * 0.2 * 0.2 / 0.13, 1e-12);
  EXPECT_NEAR(s.reynolds, 0.31, 0.005);
  EXPECT_NEAR(s.deborah, 1.3, 1e-12);
  EXPECT_NEAR(s.mach, 0.63, 0.005);
  EXPECT_NEAR(s.elasticity, 4.19, 0.01 * 4.19);
  EXPECT_NEAR(s.elasticity, s.deborah / s.reynolds, 1e-12);
  // A Newtonian liquid: no elasticity.
  Params newtonian = ElevenDiskFluid(2);
  newtonian.fluid.relaxation_time = 0.0;
  const RunStatistics n = ComputeRunStatistics(newtonian, DiagnosticsTable{}, h);
  EXPECT_EQ(n.deborah, 0.0);
  EXPECT_EQ(n.mach, 0.0);
  EXPECT_EQ(n.elasticity, 0.0);
}

// Fixed particles do not count in U and D; without gravity there is no fall speed.
TEST(RunStatistics, FixedParticlesAndNoGravity) {
  Params p = ElevenDiskFluid(2);
  p.particles[1].motion = Motion::kFixed;
  p.particles[1].diameter = 0.5;
  const ParticleHistory h =
      Moving({Vec2(0.9, 7.0), Vec2(1.5, 4.0)}, {Vec2(0, -0.3), Vec2(0, 0)}, 5, 1.0);
  const RunStatistics s = ComputeRunStatistics(p, DiagnosticsTable{}, h);
  EXPECT_NEAR(s.mean_fall_speed, 0.3, 1e-12);
  EXPECT_EQ(s.diameter, 0.2);
  EXPECT_EQ(s.fall_speed[1], 0.0);
  p.gravity = Vec2::Zero();
  const RunStatistics g = ComputeRunStatistics(p, DiagnosticsTable{}, h);
  EXPECT_TRUE(std::isnan(g.fall_speed[0]));
  EXPECT_TRUE(std::isnan(g.mean_fall_speed));
}

}  // namespace
}  // namespace dlmfd
