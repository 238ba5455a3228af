// Schaefer-Turek 2D-1 at the defaults (issue 32 point 4, issue 33 point 1):
// cases/verification/schaefer_turek_2d1.toml as shipped, D/h = 20, with no numerics key but the
// advection it names (the default since issue 32 too): `auto` picks cut cells for its fixed disk
// in a Newtonian liquid over 1,600 steps (scene/auto_particle_mesh.h), both diagonals, the coupling
// "auto" chose (unused by cut cells), the tendency steady correction. Reference (the scene's
// title): Cd = 5.57953523384, Cl = 0.010618948146 (John & Matthies 2001). The targets: Cd within
// 0.3 % at D/h = 20 (issue 33; issue 32 asks 1 %), Cl within 10 % (issue 32 asks it at D/h = 40)
// and of the right sign. Measured +0.022 % and +4.2 % at t = 12 (docs/accuracy.md, with the
// command). Cd is steady to 1e-4 by t = 5; the lift's wake mode decays by t = 8
// (docs/evidence/particle_boundary.md (e), "The lift's steady state"), so the run goes to t = 8.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

constexpr double kReferenceDrag = 5.57953523384;
constexpr double kReferenceLift = 0.010618948146;

TEST(SchaeferTurekAtTheDefaults, DragWithinAThirdOfAPercentAndLiftWithinTenAtDOverHTwenty) {
  Params params =
      LoadSceneFile(std::string(DLMFD_SOURCE_DIR) + "/cases/verification/schaefer_turek_2d1.toml",
                    {{"time.end", "8"},
                     {"output.fields_every", "0"},
                     {"output.particles_every", "0"},
                     {"output.checkpoint_every", "0"}});
  params.threads = 1;
  EXPECT_EQ(params.particle_mesh.kind, ParticleMeshKind::kCutCell);
  EXPECT_EQ(params.domain.diagonals, MeshDiagonals::kBoth);
  EXPECT_EQ(params.splitting.advection, AdvectionScheme::kWave);
  ASSERT_EQ(params.numerics.resolved.size(), 2u);  // the coupling's and the mesh's "auto"
  Simulation sim(params);
  sim.Run();
  const Vec2 force = sim.state().particles.at(0).force;
  const double scale = 0.5 * 1.0 * 0.2 * 0.2 * 0.1;  // rho U_mean^2 D / 2
  const double cd = force.x() / scale;
  const double cl = force.y() / scale;
  std::printf("Schaefer-Turek at the defaults, D/h = 20, t = 8: Cd = %.5f (%+.3f %%), Cl = %.5f\n",
              cd, 100.0 * (cd / kReferenceDrag - 1.0), cl);
  EXPECT_NEAR(cd, kReferenceDrag, 0.003 * kReferenceDrag);
  EXPECT_NEAR(cl, kReferenceLift, 0.1 * kReferenceLift);
  EXPECT_GT(cl * kReferenceLift, 0.0) << "the lift's sign";
}

// The work-precision ladder's coarsest point (bench/work_precision_defaults.sh, problem dfg: the
// channel 2.255 long, t = 5; here dt = h, the ladder's 2 h moves C_D by 4.9e-5 relative), D/h =
// 9.76, at two sub-grid positions of the disk: within
// issue 32's 1 %. Measured over eight positions +0.71 % to +0.85 % (the pressure ghost penalty
// scaled by eta + rho H^2 / dt; by eta alone +1.16 % to +1.33 %; docs/evidence/
// cut_cell_boundary.md, "The pressure ghost penalty's scale").
TEST(SchaeferTurekAtTheDefaults, DragWithinOnePercentAtDOverHTen) {
  const double h = 0.01025;
  for (const double shift : {0.0, 0.75}) {
    char centre[64];
    std::snprintf(centre, sizeof centre, "[%.17g, 0.2]", 0.2 + shift * h);
    Params params = LoadSceneFile(
        std::string(DLMFD_SOURCE_DIR) + "/cases/verification/schaefer_turek_2d1.toml",
        {{"domain.h", "0.01025"},
         {"domain.size", "[2.255, 0.41]"},
         {"particle_mesh.h", "0.014057142857"},  // h 96 / 70, as the ladder (unused by cut cells)
         {"particles.0.center", centre},
         {"time.dt", "0.01025"},
         {"time.end", "5"},
         {"output.fields_every", "0"},
         {"output.particles_every", "0"},
         {"output.checkpoint_every", "0"}});
    params.threads = 1;
    EXPECT_EQ(params.particle_mesh.kind, ParticleMeshKind::kCutCell);
    Simulation sim(params);
    sim.Run();
    const Vec2 force = sim.state().particles.at(0).force;
    const double scale = 0.5 * 1.0 * 0.2 * 0.2 * 0.1;  // rho U_mean^2 D / 2
    // The drag moved back to x = 0.2 with the slope of the study (-0.0496 a cell at D/h = 9.76).
    const double cd = force.x() / scale + 0.0496 * shift;
    const double cl = force.y() / scale;
    std::printf("Schaefer-Turek at the defaults, D/h = 9.76, shift %.2f h: Cd = %.5f (%+.3f %%)\n",
                shift, cd, 100.0 * (cd / kReferenceDrag - 1.0));
    EXPECT_NEAR(cd, kReferenceDrag, 0.01 * kReferenceDrag);
    EXPECT_GT(cl * kReferenceLift, 0.0) << "the lift's sign";
  }
}

}  // namespace
}  // namespace dlmfd
