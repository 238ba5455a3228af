// A body in prescribed motion with cut cells (particles/cut_cell_step.h, cut_cell_stokes.h
// SetBodyMotion; docs/evidence/cut_cell_boundary.md, "A body in prescribed motion"):
// - a disk translating with the liquid: in a fully periodic box whose liquid moves at U, a disk
//   prescribed to move at U is an exact discrete solution, u = U everywhere and p constant (the
//   constant is in the kernel of every form; Nitsche's load of g = U is what the forms give u = U
//   on the chords), so after steps that move the disk across cells (the cut set, the nodes it
//   uncovers and the ones it covers change) u = U to round-off and the force is 0; the disk is
//   where dt U puts it. A wrong sign or weight of the load, a node uncovered with a wrong value or
//   a geometry not moved gives O(1) errors.
// - the rules: free particles stay refused with cut cells, prescribed ones are taken.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/state.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/particles/cut_cell_step.h"
#include "dlmfd/particles/particle_rules.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

std::string TranslatingScene(const std::string& motion) {
  return "[domain]\nsize = [1.0, 1.0]\nh = 0.0625\n"
         "[domain.boundary]\nleft = { type = \"periodic\" }\nright = { type = \"periodic\" }\n"
         "bottom = { type = \"periodic\" }\ntop = { type = \"periodic\" }\n"
         "[fluid]\ndensity = 1.0\nviscosity = 0.5\n"
         "[time]\ndt = 0.02\nend = 0.1\n"
         "[particle_mesh]\nkind = \"cut_cell\"\n"
         "[[particles]]\ndiameter = 0.4\ncenter = [0.51, 0.47]\nvelocity = [1.3, -0.7]\n"
         "motion = \"" +
         motion + "\"\n";
}

TEST(CutCellMotion, DiskTranslatingWithTheLiquidKeepsItUniform) {
  const Params params = ParseScene(TranslatingScene("prescribed"));
  const Grid g = params.domain.VelocityGrid();
  const Vec2 velocity = params.particles[0].velocity;
  CutCellStep step(params, g);
  const BoundaryData data(g, params.domain);
  std::vector<double> u(g.NodeCount(), velocity.x()), v(g.NodeCount(), velocity.y());
  std::vector<double> p(g.Coarse().NodeCount(), 0.0);
  std::vector<ParticleState> particles(1);
  StepReport report;
  const int steps = 10;  // |U| dt / h = 0.47 a step: about five cells crossed
  double u_error = 0.0, p_range = 0.0, force = 0.0;
  for (int n = 0; n < steps; ++n) {
    step.Solve(params.time.dt, data, particles, u.data(), v.data(), p.data(), report);
    for (std::size_t k = 0; k < u.size(); ++k)
      u_error = std::max({u_error, std::abs(u[k] - velocity.x()), std::abs(v[k] - velocity.y())});
    const auto [lo, hi] = std::minmax_element(p.begin(), p.end());
    p_range = std::max(p_range, *hi - *lo);
    force = std::max(force, particles[0].force.norm() + std::abs(particles[0].torque));
  }
  EXPECT_LT(u_error, 1e-9);
  EXPECT_LT(p_range, 1e-8);
  EXPECT_LT(force, 1e-8);
  const Vec2 moved = params.particles[0].center + steps * params.time.dt * velocity;
  EXPECT_NEAR(particles[0].position.x(), moved.x(), 1e-12);
  EXPECT_NEAR(particles[0].position.y(), moved.y(), 1e-12);
  EXPECT_EQ(particles[0].velocity, velocity);
}

TEST(CutCellMotion, FreeParticlesAreRefusedPrescribedTaken) {
  EXPECT_NO_THROW(RequireCutCellScene(ParseScene(TranslatingScene("prescribed"))));
  EXPECT_THROW(RequireCutCellScene(ParseScene(TranslatingScene("free"))), InvalidParameter);
}

}  // namespace
}  // namespace dlmfd
