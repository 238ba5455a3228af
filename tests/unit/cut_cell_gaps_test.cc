// The surface gaps a cut-cell step reports (particles/cut_cell_step.h; the collocation path's
// columns, particles/particle_step.h): after every step of a heavy free disk falling beside a
// fixed one in a closed box, particle_pair_gap is |X_1 - X_2| - R_1 - R_2 and particle_wall_gap
// the smallest distance of a surface to a side, both at the positions the step gives the particles
// (X^{n+1}), and particle_min_gap the smaller of the two. The free disk falls towards the bottom
// wall, away from the fixed one, so both gaps change from step to step (checked): a gap of
// another step's positions is off by far more than the checks' 1e-12, one of the centres or of
// other radii by 0.1-0.25. Without the columns (before session 24) Get reads 0 and fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "dlmfd/core/state.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/particles/cut_cell_step.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

TEST(CutCellGaps, ReportedGapsAreThoseOfTheStepsPositions) {
  const Params params = ParseScene(
      "[domain]\nsize = [1.0, 1.0]\nh = 0.0625\n"
      "[fluid]\ndensity = 1.0\nviscosity = 0.5\ngravity = [0.0, -9.81]\n"
      "[time]\ndt = 0.02\nend = 0.1\n"
      "[particle_mesh]\nkind = \"cut_cell\"\n"
      "[[particles]]\ndiameter = 0.3\ncenter = [0.33, 0.3]\ndensity = 3.0\n"
      "[[particles]]\ndiameter = 0.2\ncenter = [0.7, 0.45]\nmotion = \"fixed\"\n");
  const Grid g = params.domain.VelocityGrid();
  CutCellStep step(params, g);
  const BoundaryData data(g, params.domain);
  std::vector<double> u(g.NodeCount(), 0.0), v(g.NodeCount(), 0.0);
  std::vector<double> p(g.Coarse().NodeCount(), 0.0);
  std::vector<ParticleState> particles(2);
  const double r0 = 0.15, r1 = 0.1;
  double first_pair = NAN, first_wall = NAN, last_pair = NAN, last_wall = NAN;
  for (int n = 0; n < 6; ++n) {
    StepReport report;
    step.MoveBeforeStep(params.time.dt, u.data(), v.data());
    step.Solve(params.time.dt, data, particles, u.data(), v.data(), p.data(), report);
    const Vec2 a = particles[0].position, b = particles[1].position;
    const double pair = (a - b).norm() - r0 - r1;
    const double wall = std::min({a.x() - r0, 1.0 - a.x() - r0, a.y() - r0, 1.0 - a.y() - r0,
                                  b.x() - r1, 1.0 - b.x() - r1, b.y() - r1, 1.0 - b.y() - r1});
    EXPECT_NEAR(report.Get("particle_pair_gap"), pair, 1e-12) << "step " << n;
    EXPECT_NEAR(report.Get("particle_wall_gap"), wall, 1e-12) << "step " << n;
    EXPECT_NEAR(report.Get("particle_min_gap"), std::min(pair, wall), 1e-12) << "step " << n;
    if (n == 0) {
      first_pair = pair;
      first_wall = wall;
    }
    last_pair = pair;
    last_wall = wall;
  }
  std::printf("pair gap %.6f -> %.6f, wall gap %.6f -> %.6f over the steps\n", first_pair,
              last_pair, first_wall, last_wall);
  // The free disk falls: both gaps move by more than the 1e-12 of the checks above, many times.
  EXPECT_GT(std::abs(last_pair - first_pair), 1e-4);
  EXPECT_GT(std::abs(last_wall - first_wall), 1e-4);
}

}  // namespace
}  // namespace dlmfd
