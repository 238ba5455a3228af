// Ellipses as particles (issue 37, point 1): the scene keys and their errors, the multiplier points
// turned with the particle's angle (the DLM step (37) holds the fluid rigid at the turned points),
// the angle integrated with the rotation by the corrector's trapezoidal rule, and particles.h5
// carrying the shape, the semi-axes and the angle.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "../support/scratch_path.h"
#include "../support/walled_box_scene.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/simulation.h"
#include "dlmfd/io/particle_history.h"
#include "dlmfd/particles/particle_step.h"
#include "dlmfd/particles/rigid_body_constraint.h"
#include "dlmfd/particles/shape.h"
#include "dlmfd/scene/scene_file.h"
#include "dlmfd/viz/colour_map.h"
#include "dlmfd/viz/field_picture.h"

namespace dlmfd {
namespace {

using ::testing::HasSubstr;

// A 1 x 1 box of walls, h = 1/32, a Newtonian liquid, collocation points, one particle whose
// table is `particle` (its keys after center).
std::string EllipseScene(const std::string& particle, const std::string& mesh = "collocation") {
  return "\n" + testing::WalledBoxDomain("1.0, 1.0", "0.03125") + R"TOML([fluid]
density = 1.0
viscosity = 1.0
relaxation_time = 0.0
gravity = [0.0, -1.0]
[time]
dt = 0.005
end = 1.0
[particle_mesh]
kind = ")TOML" +
         mesh + R"TOML("
[[particles]]
center = [0.5, 0.5]
)TOML" + particle +
         "\n";
}

// The InvalidParameter message of parsing this scene ("" when it parses).
std::string ErrorOf(const std::string& scene) {
  try {
    ParseScene(scene);
  } catch (const InvalidParameter& e) {
    return e.what();
  }
  return "";
}

TEST(EllipseScene, KeysGiveTheShapeAndRoundTrip) {
  const Params p = ParseScene(
      EllipseScene("shape = \"ellipse\"\nsemi_axes = [0.2, 0.1]\nangle = 0.5\ndensity = 1.5\n"));
  ASSERT_EQ(p.particles.size(), 1u);
  const ParticleParams& q = p.particles[0];
  EXPECT_EQ(q.shape, ShapeKind::kEllipse);
  EXPECT_EQ(q.semi_axes, Vec2(0.2, 0.1));
  EXPECT_EQ(q.angle, 0.5);
  EXPECT_DOUBLE_EQ(q.Radius(), 0.2);                         // the bounding radius
  EXPECT_DOUBLE_EQ(q.diameter, 2.0 * std::sqrt(0.2 * 0.1));  // the equal-area diameter
  EXPECT_EQ(Shape::Of(q), Shape::Ellipse(0.2, 0.1));
  EXPECT_EQ(WriteScene(ParseScene(WriteScene(p))), WriteScene(p));
  EXPECT_THAT(WriteScene(p), HasSubstr("shape = \"ellipse\"\nsemi_axes = [0.2, 0.1]\nangle = 0.5"));
  // A disk's scene text has none of the new keys.
  const Params disk = ParseScene(EllipseScene("diameter = 0.2\n"));
  EXPECT_EQ(disk.particles[0].shape, ShapeKind::kDisk);
  EXPECT_EQ(WriteScene(disk).find("shape"), std::string::npos);
  EXPECT_EQ(WriteScene(disk).find("angle ="), std::string::npos);
}

TEST(EllipseScene, BadShapesAreRefusedNamingTheKeyAndTheAllowedValues) {
  EXPECT_THAT(ErrorOf(EllipseScene("shape = \"square\"\n")),
              AllOf(HasSubstr("particles.0.shape"), HasSubstr("disk"), HasSubstr("ellipse")));
  EXPECT_THAT(ErrorOf(EllipseScene("shape = \"ellipse\"\n")), HasSubstr("particles.0.semi_axes"));
  EXPECT_THAT(ErrorOf(EllipseScene("shape = \"ellipse\"\ndiameter = 0.2\nsemi_axes = [0.2, 0.1]")),
              AllOf(HasSubstr("particles.0.diameter"), HasSubstr("semi_axes")));
  EXPECT_THAT(ErrorOf(EllipseScene("diameter = 0.2\nsemi_axes = [0.2, 0.1]")),
              AllOf(HasSubstr("particles.0.semi_axes"), HasSubstr("ellipse")));
  EXPECT_THAT(ErrorOf(EllipseScene("shape = \"ellipse\"\nsemi_axes = [0.2, -0.1]")),
              AllOf(HasSubstr("particles.0.semi_axes"), HasSubstr("> 0")));
  EXPECT_THAT(ErrorOf(EllipseScene("shape = \"ellipse\"\nsemi_axes = [0.2, 0.02]")),
              AllOf(HasSubstr("particles.0.semi_axes"), HasSubstr("max / min <= 8")));
  EXPECT_THAT(ErrorOf(EllipseScene("shape = \"ellipse\"\nsemi_axes = [0.2, 0.025]")), "");
  EXPECT_THAT(ErrorOf(EllipseScene("shape = \"ellipse\"\nsemi_axes = [0.2, 0.1]", "ring")),
              AllOf(HasSubstr("particle_mesh.kind"), HasSubstr("collocation")));
  EXPECT_THAT(ErrorOf(EllipseScene("angle = nan")), HasSubstr("particles.0.angle"));
  // The bounding circle must lie in the box (a conservative rule for an ellipse).
  EXPECT_THAT(ErrorOf(EllipseScene("shape = \"ellipse\"\nsemi_axes = [0.6, 0.1]")),
              HasSubstr("particles.0.center"));
}

TEST(EllipseParticle, TheDlmStepHoldsTheFluidRigidAtTheTurnedPoints) {
  Params p = ParseScene(
      EllipseScene("shape = \"ellipse\"\nsemi_axes = [0.2, 0.1]\nmotion = \"prescribed\"\n"
                   "angular_velocity = 2.0\nvelocity = [0.1, 0.0]"));
  const Grid grid = p.domain.VelocityGrid();
  RigidBodyConstraint constraint(p, grid);
  std::vector<ParticleState> particles = ParticleStep::InitialStates(p);
  const double theta = 0.7;
  particles[0].angle = theta;
  std::vector<double> u(grid.NodeCount(), 0.0), v(grid.NodeCount(), 0.0);
  const RigidBodyConstraint::Outcome outcome =
      constraint.Enforce(0.005, 0.005, particles, u.data(), v.data());
  const MultiplierPoints& points = constraint.points();
  const Shape ellipse = Shape::Ellipse(0.2, 0.1);
  const int boundary = ellipse.BoundaryPointCount(p.particle_mesh.spacing * p.domain.h);
  const std::vector<BoundaryPoint> body = ellipse.BoundaryPoints(boundary);
  ASSERT_GT(points.Count(0), boundary);
  for (int k = 0; k < boundary; ++k) {
    EXPECT_NEAR((points.Points(0)[k] - Rotate(theta, body[k].position)).norm(), 0.0, 1e-15);
  }
  // E u = U + omega r_perp at the turned points, to the CG's tolerance of the cold mismatch
  // (the rigid speed is at most 0.1 + 2 * 0.2 = 0.5).
  EXPECT_GT(outcome.cold_residual, 0.1);
  EXPECT_LT(outcome.residual, 1e-3 * outcome.cold_residual);
  for (int k = 0; k < points.Count(0); ++k) {
    double eu, ev;
    constraint.coupling().Interpolate(points.Begin(0) + k, u.data(), v.data(), eu, ev);
    const Vec2 r = points.Points(0)[k];
    const Vec2 rigid = Vec2(0.1, 0.0) + 2.0 * Vec2(-r.y(), r.x());
    EXPECT_NEAR((Vec2(eu, ev) - rigid).norm(), 0.0, outcome.residual + 1e-15);
  }
  // Turning back to 0 moves them back.
  particles[0].angle = 0.0;
  constraint.Enforce(0.01, 0.005, particles, u.data(), v.data());
  EXPECT_NEAR((points.Points(0)[0] - Vec2(0.2, 0.0)).norm(), 0.0, 1e-15);
}

TEST(EllipseParticle, TheAngleIsTheTrapezoidalIntegralOfTheRotation) {
  // A prescribed rotation: theta = theta_0 + omega t exactly (to round-off).
  {
    Params p = ParseScene(EllipseScene(
        "shape = \"ellipse\"\nsemi_axes = [0.2, 0.1]\nangle = 0.25\nmotion = \"prescribed\"\n"
        "angular_velocity = 1.5"));
    Simulation sim(p);
    for (int n = 0; n < 8; ++n) sim.Step();
    EXPECT_NEAR(sim.state().particles[0].angle, 0.25 + 1.5 * 8 * 0.005, 1e-14);
  }
  // A heavy free ellipse tilted by 45 degrees, settling: it turns, and each step's increment is
  // dt (omega^n + omega^{n+1}) / 2.
  Params p = ParseScene(EllipseScene(
      "shape = \"ellipse\"\nsemi_axes = [0.2, 0.1]\nangle = 0.7853981633974483\ndensity = 2.0"));
  Simulation sim(p);
  double angle = sim.state().particles[0].angle, omega = sim.state().particles[0].angular_velocity;
  for (int n = 0; n < 6; ++n) {
    sim.Step();
    const ParticleState& q = sim.state().particles[0];
    EXPECT_NEAR(q.angle - angle, 0.5 * 0.005 * (omega + q.angular_velocity), 1e-16);
    angle = q.angle;
    omega = q.angular_velocity;
  }
  // It turns: omega is 1e-5 to 1e-4 after six steps (3.8e-5 on both diagonals with the wave
  // advection, 1e-4 on the SW-NE mesh), ten orders above the increments' round-off checked above.
  EXPECT_GT(std::abs(omega), 1e-6);
  EXPECT_EQ(sim.state().particles[0].shape, ShapeKind::kEllipse);
}

TEST(EllipseParticle, ParticlesH5CarriesTheShapeTheSemiAxesAndTheAngle) {
  const Params p = ParseScene(
      EllipseScene("shape = \"ellipse\"\nsemi_axes = [0.1, 0.2]\nangle = 0.3\ndensity = 2.0\n") +
      "[[particles]]\ncenter = [0.2, 0.8]\ndiameter = 0.1\ndensity = 2.0\n");
  Simulation sim(p);
  const std::string dir = dlmfd::testing::ScratchPath("ellipse_particles_h5");
  std::filesystem::create_directories(dir);
  {
    auto w = ParticleHistoryWriter::Create(dir + "/particles.h5", sim.state());
    w->Append(sim.state(), {0.3, 0.0});
  }
  const ParticleHistory h = ReadParticleHistory(dir + "/particles.h5");
  EXPECT_EQ(h.shape, (std::vector<std::int64_t>{1, 0}));
  EXPECT_EQ(h.semi_axes, (std::vector<double>{0.1, 0.2, 0.05, 0.05}));
  EXPECT_EQ(h.radius, (std::vector<double>{0.2, 0.05}));
  EXPECT_EQ(h.angle, (std::vector<double>{0.3, 0.0}));
  EXPECT_EQ(sim.state().particles[0].angle, 0.3);
}

TEST(EllipseParticle, PicturesDrawAnEllipseTurnedByItsAngle) {
  NodeField field;
  field.grid = Grid{8, 8, 0.125, 0.0, 0.0};
  field.values.assign(field.grid.NodeCount(), 1.0);
  field.values[0] = 0.0;  // a colour range
  PictureOptions options;
  options.max_width = 400;
  options.max_height = 400;
  // Upright (turned by pi/2): white along y inside it, the field's colour along x beside it.
  DiskOutline ellipse{0.5, 0.5, 0.3, kPi / 2, true, 0.3, 0.1};
  const FieldPicture picture = DrawFieldPicture(field, {ellipse}, options);
  const RgbImage image = picture.image.Rasterise();
  const auto at = [&](double x, double y) {
    return image.At(static_cast<int>(picture.PixelX(x)), static_cast<int>(picture.PixelY(y)));
  };
  EXPECT_EQ(at(0.52, 0.72), kWhite);
  EXPECT_EQ(at(0.48, 0.28), kWhite);
  EXPECT_NE(at(0.72, 0.52), kWhite);  // inside the bounding circle, outside the ellipse
  EXPECT_NE(at(0.28, 0.48), kWhite);
  // The same outline without semi-axes is the disk of the bounding radius.
  ellipse.semi_a = ellipse.semi_b = 0.0;
  const FieldPicture disk = DrawFieldPicture(field, {ellipse}, options);
  const RgbImage disk_image = disk.image.Rasterise();
  EXPECT_EQ(disk_image.At(static_cast<int>(disk.PixelX(0.72)), static_cast<int>(disk.PixelY(0.52))),
            kWhite);
}

}  // namespace
}  // namespace dlmfd
