// Sangani & Acrivos's square array of fixed disks in Stokes flow (issue 32 point 4;
// cases/verification/sangani_acrivos_square_array.toml): the drag K = F / (mu U) of one disk in a
// unit periodic box driven by a body force, F the disk's force and U the flux through the box's
// edge x = 0 over its height, against Sangani & Acrivos (1982), Table 1
// (cases/verification/sangani_acrivos_reference.csv).
//
// Study (2026-12-04, bench/sangani_acrivos.sh, collocation points on both diagonals, wave
// advection; docs/evidence/validation_particles.md, "Sangani and Acrivos's square array"): at h =
// 1/64 the error over four sub-grid positions of the disk (shifts 0, 1/4, 1/2, 3/4 h along x) is
// +0.83 / +0.67 / -0.40 / +0.77 % at Phi = 0.1 and +0.37 / +0.96 / +2.16 / +2.27 % at Phi = 0.3.
// The node-centred disk must stay within the largest error of its area fraction over those
// positions (0.83 % and 2.27 %): a change that moves it outside has moved the boundary's error, not
// its position's.
//
// With cut cells (particle_mesh.kind = "cut_cell", periodic sides; docs/evidence/
// cut_cell_boundary.md, "Periodic boxes: the square array"): at Phi = 0.3 over the four positions
// +1.15 to +1.19 % at h = 1/32, +0.29 % at 1/64 (spread 0.04 % and 0.001 %), order 2.00 on the
// node-centred disk (1.86-2.0 over Phi = 0.1-0.4). The node-centred disk must meet the 1 %
// at h = 1/64 and converge at order 1.8 at least from h = 1/32 to 1/64 (issue 33's bound): a
// first-order boundary, or a periodic side treated wrong (an O(1) error that does not converge),
// fails it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

// K of the square array at area fraction `phi`, the disk node-centred, with the particle mesh
// `kind` on `cells` cells a side.
double SquareArrayDrag(double phi, const char* kind = "collocation", int cells = 64) {
  const double diameter = 2.0 * std::sqrt(phi / M_PI);
  Params params = LoadSceneFile(
      std::string(DLMFD_SOURCE_DIR) + "/cases/verification/sangani_acrivos_square_array.toml",
      {{"particles.0.diameter", std::to_string(diameter)},
       {"domain.h", std::to_string(1.0 / cells)},
       {"particle_mesh.kind", std::string("\"") + kind + "\""},
       {"domain.diagonals", "\"both\""},
       {"splitting.advection", "\"wave\""},
       {"output.fields_every", "0"},
       {"output.particles_every", "0"},
       {"output.checkpoint_every", "0"}});
  params.threads = 1;
  Simulation sim(params);
  sim.Run();
  const FlowState& s = sim.state();
  const Grid& g = sim.grid();
  double flux = 0.0;  // through x = 0; the periodic duplicate row j = ny left out
  for (int j = 0; j < g.ny; ++j) flux += s.u[g.Index(0, j)] * g.h;
  const double mean_velocity = flux / g.Height();
  return s.particles[0].force.x() / (params.fluid.viscosity * mean_velocity);
}

TEST(SanganiAcrivos, SquareArrayDragAtPhiPointOne) {
  const double k = SquareArrayDrag(0.1);
  std::printf("Phi = 0.1: K = %.4f (Sangani & Acrivos 24.83, %+.3f %%)\n", k,
              100.0 * (k / 24.83 - 1.0));
  EXPECT_NEAR(k / 24.83 - 1.0, 0.0, 0.0083);
}

TEST(SanganiAcrivos, SquareArrayDragAtPhiPointThree) {
  const double k = SquareArrayDrag(0.3);
  std::printf("Phi = 0.3: K = %.4f (Sangani & Acrivos 102.90, %+.3f %%)\n", k,
              100.0 * (k / 102.90 - 1.0));
  EXPECT_NEAR(k / 102.90 - 1.0, 0.0, 0.0227);
}

TEST(SanganiAcrivos, CutCellsAreSecondOrderAndWithinOnePercent) {
  const double coarse = SquareArrayDrag(0.3, "cut_cell", 32) / 102.90 - 1.0;
  const double fine = SquareArrayDrag(0.3, "cut_cell", 64) / 102.90 - 1.0;
  const double order = std::log2(coarse / fine);
  std::printf("Phi = 0.3, cut cells: %+.3f %% (h = 1/32), %+.3f %% (1/64), order %.2f\n",
              100.0 * coarse, 100.0 * fine, order);
  EXPECT_LT(std::abs(fine), 0.01);
  EXPECT_GT(order, 1.8);
}

}  // namespace
}  // namespace dlmfd
