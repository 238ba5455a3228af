// A body in prescribed motion with cut cells (particles/cut_cell_step.h, cut_cell_stokes.h
// SetBodyMotion; docs/evidence/cut_cell_boundary.md, "A body in prescribed motion"):
// - a disk translating with the liquid: in a fully periodic box whose liquid moves at U, a disk
//   prescribed to move at U is an exact discrete solution, u = U everywhere and p constant (the
//   constant is in the kernel of every form; Nitsche's load of g = U is what the forms give u = U
//   on the chords), so after steps that move the disk across cells (the cut set, the nodes it
//   uncovers and the ones it covers change) u = U to round-off and the force is 0; the disk is
//   where dt U puts it. A wrong sign or weight of the load, a node uncovered with a wrong value or
//   a geometry not moved gives O(1) errors.
// - the rules: free and prescribed disks and ellipses are taken (a free one of any density), and
//   a polymer around a moving disk; around a moving ellipse it is refused;
// - a turned ellipse, prescribed or free, moving with the liquid: the same exact solution;
// - a free disk (particles/cut_cell_free_bodies.h) moving with the liquid keeps u = U and its
//   velocity; the first step of a heavy free disk is the solve at its new velocity, and Newton's
//   law holds with the force the step reports.
// - a moving body's saddle point recut in place (CutCellStokes::Recut: the uniform forms plus the
//   band's correction, the capacitance matrix's responses of the rows that stay in the band kept)
//   is the saddle point built anew on the moved geometry: the same solution to the solver's
//   tolerance, the same rank, and after a move of a fraction of a cell far fewer fast solves than
//   the rank (a wrong band correction or a response of another row gives O(1) differences); where
//   the responses decay within a few cells, its solves sum their held entries, as one built anew;
//   its forms, updated in place in the band's columns, are a fresh saddle point's first recut to
//   the bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../support/cut_cell_creeping.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/state.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/particles/cut_cell_step.h"
#include "dlmfd/particles/particle_rules.h"
#include "dlmfd/particles/shape.h"
#include "dlmfd/scene/scene_file.h"

namespace dlmfd {
namespace {

// The disk (D = 0.4), or an ellipse of the same long axis (a = 0.2, b = 0.15: its tip's radius of
// curvature b^2 / a is 1.8 h, above particles/particle_rules.h's kMovingEllipseTipCells) turned by
// 0.3.
const char kDiskShape[] = "diameter = 0.4\n";
const char kEllipseShape[] = "shape = \"ellipse\"\nsemi_axes = [0.2, 0.15]\nangle = 0.3\n";
std::string TranslatingScene(const std::string& motion, const char* shape = kDiskShape) {
  return "[domain]\nsize = [1.0, 1.0]\nh = 0.0625\n"
         "[domain.boundary]\nleft = { type = \"periodic\" }\nright = { type = \"periodic\" }\n"
         "bottom = { type = \"periodic\" }\ntop = { type = \"periodic\" }\n"
         "[fluid]\ndensity = 1.0\nviscosity = 0.5\n"
         "[time]\ndt = 0.02\nend = 0.1\n"
         "[particle_mesh]\nkind = \"cut_cell\"\n"
         "[[particles]]\n" +
         std::string(shape) + "center = [0.51, 0.47]\nvelocity = [1.3, -0.7]\nmotion = \"" +
         motion + "\"\n";
}

// The largest departures from the uniform state over `steps` steps of the translating scene
// with the disk's motion `motion` (|U| dt / h = 0.47 a step: ten steps cross about five cells).
struct TranslatingRun {
  Params params;
  double u_error = 0.0, p_range = 0.0, force = 0.0, velocity_error = 0.0;
  ParticleState last;
};
TranslatingRun RunWithTheLiquid(const std::string& motion, int steps,
                                const char* shape = kDiskShape) {
  TranslatingRun run;
  run.params = ParseScene(TranslatingScene(motion, shape));
  const Params& params = run.params;
  const Grid g = params.domain.VelocityGrid();
  const Vec2 velocity = params.particles[0].velocity;
  CutCellStep step(params, g);
  const BoundaryData data(g, params.domain);
  std::vector<double> u(g.NodeCount(), velocity.x()), v(g.NodeCount(), velocity.y());
  std::vector<double> p(g.Coarse().NodeCount(), 0.0);
  std::vector<ParticleState> particles(1);
  StepReport report;
  for (int n = 0; n < steps; ++n) {
    step.MoveBeforeStep(params.time.dt, u.data(), v.data());
    step.Solve(params.time.dt, data, particles, u.data(), v.data(), p.data(), report);
    for (std::size_t k = 0; k < u.size(); ++k) {
      run.u_error =
          std::max({run.u_error, std::abs(u[k] - velocity.x()), std::abs(v[k] - velocity.y())});
    }
    const auto [lo, hi] = std::minmax_element(p.begin(), p.end());
    run.p_range = std::max(run.p_range, *hi - *lo);
    run.force = std::max(run.force, particles[0].force.norm() + std::abs(particles[0].torque));
    run.velocity_error = std::max({run.velocity_error, (particles[0].velocity - velocity).norm(),
                                   std::abs(particles[0].angular_velocity)});
  }
  run.last = particles[0];
  return run;
}

TEST(CutCellMotion, DiskTranslatingWithTheLiquidKeepsItUniform) {
  const int steps = 10;
  const TranslatingRun run = RunWithTheLiquid("prescribed", steps);
  EXPECT_LT(run.u_error, 1e-9);
  EXPECT_LT(run.p_range, 1e-8);
  EXPECT_LT(run.force, 1e-8);
  const Params& params = run.params;
  const Vec2 velocity = params.particles[0].velocity;
  const Vec2 moved = params.particles[0].center + steps * params.time.dt * velocity;
  EXPECT_NEAR(run.last.position.x(), moved.x(), 1e-12);
  EXPECT_NEAR(run.last.position.y(), moved.y(), 1e-12);
  EXPECT_EQ(run.last.velocity, velocity);
}

// The same for a turned ellipse, prescribed and free (taken by cut cells since 2026-12-08; the
// scene refused them before): its cut moves with it, u = U to round-off, no force or torque, and
// a free one keeps its velocity and does not turn.
TEST(CutCellMotion, EllipseMovingWithTheLiquidKeepsItUniform) {
  const int steps = 10;
  for (const char* motion : {"prescribed", "free"}) {
    const TranslatingRun run = RunWithTheLiquid(motion, steps, kEllipseShape);
    EXPECT_LT(run.u_error, 1e-9) << motion;
    EXPECT_LT(run.force, 1e-8) << motion;
    EXPECT_LT(run.velocity_error, 1e-9) << motion;
    const Params& params = run.params;
    const Vec2 moved =
        params.particles[0].center + steps * params.time.dt * params.particles[0].velocity;
    EXPECT_NEAR(run.last.position.x(), moved.x() - std::floor(moved.x()), 1e-9) << motion;
    EXPECT_NEAR(run.last.position.y(), moved.y(), 1e-9) << motion;
    EXPECT_NEAR(run.last.angle, 0.3, 1e-9) << motion;
  }
}

// A step of (rho/dt) = 100 with the load M_l (1, 0.5) and the body moving at (1, 0.3), omega 2;
// u, v, p and the force, with the saddle point's rank and fast solves.
struct RecutStep {
  std::vector<double> u, v, p;
  Vec2 force = Vec2::Zero();
  int rank = 0, fast_solves = 0;
};
RecutStep StepOn(CutCellStokes& flow, const DomainParams& d, const FixedBody& body) {
  const Grid g = d.VelocityGrid();
  flow.SetBodyMotion({{body.centre, Vec2(1.0, 0.3), 2.0}});
  const Eigen::VectorXd& mass = flow.FluidMass();
  std::vector<double> fu(g.NodeCount()), fv(g.NodeCount());
  for (std::size_t k = 0; k < fu.size(); ++k) {
    fu[k] = mass[static_cast<Eigen::Index>(k)] * 1.0;
    fv[k] = mass[static_cast<Eigen::Index>(k)] * 0.5;
  }
  RecutStep s{std::vector<double>(g.NodeCount()), std::vector<double>(g.NodeCount()),
              std::vector<double>(g.Coarse().NodeCount())};
  const BoundaryData data(g, d);
  flow.Solve(data, fu.data(), fv.data(), s.u.data(), s.v.data(), s.p.data(), 1e-11, 2000);
  s.force =
      flow.Load(0, body.centre, s.u.data(), s.v.data(), s.p.data(), fu.data(), fv.data()).force;
  s.rank = flow.CapacitanceRank();
  s.fast_solves = flow.CapacitanceFastSolves();
  return s;
}

// A recut's step against the saddle point built anew at the same place: the largest differences
// of u, v and p against their largest values, and of the body's force, printed and held to the
// bounds of both solves' stopping rule (a relative residual of 1e-11; the pressure: see
// CutCellStokes's IterativeSolveIsTheDirectSolve, particle_cut_cell_test.cc).
void ExpectTheSaddlePointBuiltAnew(int move, const RecutStep& a, const RecutStep& b) {
  double du = 0.0, dp = 0.0, umax = 0.0, pmax = 0.0;
  for (std::size_t k = 0; k < a.u.size(); ++k) {
    du = std::max({du, std::abs(a.u[k] - b.u[k]), std::abs(a.v[k] - b.v[k])});
    umax = std::max({umax, std::abs(b.u[k]), std::abs(b.v[k])});
  }
  for (std::size_t k = 0; k < a.p.size(); ++k) {
    dp = std::max(dp, std::abs(a.p[k] - b.p[k]));
    pmax = std::max(pmax, std::abs(b.p[k]));
  }
  std::printf(
      "move %d: |du| / |u| %.2e, |dp| / |p| %.2e, |dF| / |F| %.2e, rank %d, fast solves %d\n", move,
      du / umax, dp / pmax, (a.force - b.force).norm() / b.force.norm(), a.rank, a.fast_solves);
  EXPECT_LT(du, 1e-8 * umax);
  EXPECT_LT(dp, 1e-7 * pmax);
  EXPECT_LT((a.force - b.force).norm(), 1e-8 * b.force.norm());
}

// A disk in the creeping channel (D/h = 20) that moves by 0.23 h and 0.07 h a move (more than a
// cell in five, the cut set changing on the way), cut in both triangulations, with Cahouet-
// Chabard's Laplacian of the whole grid, as a recut's (the fluid part's is for fixed bodies
// only): a recut and a saddle point built anew then differ by their forms only.
std::vector<FixedBody> OffNodeDisk(const DomainParams& d) {
  std::vector<FixedBody> body(1);
  body[0].shape = Shape::Disk(0.05);
  body[0].centre = Vec2(0.2 + 0.3 * d.h, 0.2 + 0.1 * d.h);
  return body;
}
CutCellConstants WholeGridLaplacian() {
  CutCellConstants c;
  c.fluid_pressure_laplacian = false;
  return c;
}
struct MovingDisk {
  void Move() {
    body[0].centre += Vec2(0.23 * d.h, 0.07 * d.h);
    sw_ne = CutCellGeometry(g, body);
    nw_se = CutCellGeometry(g, body, CutTriangulation::kNwSe);
  }
  const DomainParams d = CutCreepingChannel(20.0);
  const Grid g = d.VelocityGrid();
  std::vector<FixedBody> body = OffNodeDisk(d);
  CutCellGeometry sw_ne{g, body}, nw_se{g, body, CutTriangulation::kNwSe};
  const CutCellConstants constants = WholeGridLaplacian();
};

TEST(CutCellMotion, RecutIsTheSaddlePointBuiltAnew) {
  MovingDisk m;
  CutCellStokes recut(m.sw_ne, m.nw_se, m.d, 1.0, 1.0, 100.0, m.constants);
  StepOn(recut, m.d, m.body[0]);
  for (int move = 0; move < 5; ++move) {
    m.Move();
    recut.Recut();
    const RecutStep a = StepOn(recut, m.d, m.body[0]);
    CutCellStokes anew(m.sw_ne, m.nw_se, m.d, 1.0, 1.0, 100.0, m.constants);
    const RecutStep b = StepOn(anew, m.d, m.body[0]);
    ExpectTheSaddlePointBuiltAnew(move, a, b);
    EXPECT_EQ(a.rank, b.rank);
    EXPECT_EQ(b.fast_solves, b.rank);
    // The first recut solves for every row; then only the rows new to the band (measured 8-15 of
    // 224-228 for these moves of a quarter cell).
    if (move > 0) {
      EXPECT_LT(a.fast_solves, a.rank / 10);
    }
  }
}

// Where the responses decay within a few cells (rho/dt = 1e6, nu dt / h^2 = 0.04) a recut's
// velocity solves sum the held responses' entries for their second fast solve, as a saddle point
// built anew does (CutCellResponses keeps each response's entries; before, a moving body's solves
// always made the second fast solve), and the solutions are the same to the solver's tolerance.
TEST(CutCellMotion, RecutSumsTheHeldResponsesWhereTheyAreLocal) {
  MovingDisk m;
  CutCellStokes recut(m.sw_ne, m.nw_se, m.d, 1.0, 1.0, 1e6, m.constants);
  StepOn(recut, m.d, m.body[0]);
  for (int move = 0; move < 3; ++move) {
    m.Move();
    recut.Recut();
    const RecutStep a = StepOn(recut, m.d, m.body[0]);
    CutCellStokes anew(m.sw_ne, m.nw_se, m.d, 1.0, 1.0, 1e6, m.constants);
    const RecutStep b = StepOn(anew, m.d, m.body[0]);
    EXPECT_TRUE(recut.CapacitanceSumsResponses());
    EXPECT_TRUE(anew.CapacitanceSumsResponses());
    ExpectTheSaddlePointBuiltAnew(move, a, b);
  }
}

// A recut updates the forms in place, in the columns of the last band and of the new one only
// (CutCellStokes::Recut); after moves that change the cut set, the step is the one of a saddle
// point built at the last place and recut once (its forms the whole sums), to the bit: a column
// left with the last band's correction, or an entry summed in another order, would differ.
TEST(CutCellMotion, RecutInPlaceIsTheWholeSumToTheBit) {
  MovingDisk m;
  CutCellStokes moved(m.sw_ne, m.nw_se, m.d, 1.0, 1.0, 100.0, m.constants);
  StepOn(moved, m.d, m.body[0]);
  for (int move = 0; move < 4; ++move) {
    m.Move();
    moved.Recut();
  }
  const RecutStep a = StepOn(moved, m.d, m.body[0]);
  CutCellStokes fresh(m.sw_ne, m.nw_se, m.d, 1.0, 1.0, 100.0, m.constants);
  fresh.Recut();
  const RecutStep b = StepOn(fresh, m.d, m.body[0]);
  EXPECT_EQ(a.u, b.u);
  EXPECT_EQ(a.v, b.v);
  EXPECT_EQ(a.p, b.p);
  EXPECT_EQ(a.force, b.force);
}

TEST(CutCellMotion, FreeAndPrescribedTakenAlsoInAPolymer) {
  EXPECT_NO_THROW(RequireCutCellScene(ParseScene(TranslatingScene("prescribed"))));
  EXPECT_NO_THROW(RequireCutCellScene(ParseScene(TranslatingScene("free"))));
  // A free disk lighter than the liquid: taken by cut cells (no multiplier), refused by the
  // collocation points (the multiplier problem (37) would be indefinite).
  Params light = ParseScene(TranslatingScene("free"));
  light.particles[0].density = 0.5;
  const Grid g = light.domain.VelocityGrid();
  EXPECT_NO_THROW(ValidateParticles(light, g));
  light.particle_mesh.kind = ParticleMeshKind::kCollocation;
  EXPECT_THROW(ValidateParticles(light, g), InvalidParameter);
  // The polymer around a free body and around a prescribed one is taken (docs/evidence/
  // cut_cell_boundary.md, "The polymer around a free body" and "The polymer around a towed
  // body"); a moving ellipse is taken in a Newtonian liquid, refused in a polymer (not measured
  // there), with its shape named.
  for (const char* motion : {"free", "prescribed"}) {
    Params polymer = ParseScene(TranslatingScene(motion));
    polymer.fluid.relaxation_time = 0.1;
    polymer.fluid.solvent_ratio = 0.5;
    EXPECT_FALSE(polymer.fluid.IsNewtonian());
    EXPECT_NO_THROW(RequireCutCellScene(polymer)) << motion;
    EXPECT_NO_THROW(RequireCutCellScene(ParseScene(TranslatingScene(motion, kEllipseShape))));
    // A moving ellipse whose tip is thinner than kMovingEllipseTipCells h (b = 0.1: b^2 / a =
    // 0.8 h) is refused, naming the grid and the h that takes it.
    Params thin = ParseScene(TranslatingScene(motion, kEllipseShape));
    thin.particles[0].semi_axes = Vec2(0.2, 0.1);
    try {
      RequireCutCellScene(thin);
      ADD_FAILURE() << "a thin moving ellipse was taken by cut cells";
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.key(), "domain.h");
      EXPECT_NE(std::string(e.what()).find("at most 0.0312"), std::string::npos) << e.what();
    }
    thin.domain.h = 0.03125;
    EXPECT_NO_THROW(RequireCutCellScene(thin)) << motion;
    polymer = ParseScene(TranslatingScene(motion, kEllipseShape));
    polymer.fluid.relaxation_time = 0.1;
    polymer.fluid.solvent_ratio = 0.5;
    try {
      RequireCutCellScene(polymer);
      ADD_FAILURE() << "an ellipse was taken by cut cells";
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.key(), "particles.0.shape");
    }
  }
}

// A free disk moving with the liquid (neutrally buoyant, no gravity, at the liquid's velocity):
// the same exact discrete solution as the prescribed disk's above, now kept by Newton's law
// through the unit solves (particles/cut_cell_free_bodies.h): u = U, the disk's velocity U and
// its rotation 0 to round-off while it crosses cells.
TEST(CutCellMotion, FreeDiskMovingWithTheLiquidKeepsItsVelocity) {
  const int steps = 10;
  const TranslatingRun run = RunWithTheLiquid("free", steps);
  EXPECT_LT(run.u_error, 1e-9);
  EXPECT_LT(run.velocity_error, 1e-9);
  EXPECT_LT(run.force, 1e-8);
  const Params& params = run.params;
  const Vec2 moved =
      params.particles[0].center + steps * params.time.dt * params.particles[0].velocity;
  EXPECT_NEAR(run.last.position.x(), moved.x() - std::floor(moved.x()), 1e-9);
  EXPECT_NEAR(run.last.position.y(), moved.y(), 1e-9);
}

// The first step of a heavy free disk from rest under gravity in a closed box (walls; both
// triangulations): the step's solution, the first solve's plus the unit solves' times V - V*
// (V* = 0: all of it the unit solves'), is the solve with g = V^{n+1} on the step's geometry
// (X^{n+1} = X^n, at rest) to the unit solves' stopping rule (the direct solve is exact),
// and Newton's law holds with the force the step reports: M V^{n+1} / dt = F_h + M g, to round-
// off. A wrong column of K, a sign of the update or a superposition with the wrong weights gives
// O(1) differences.
TEST(CutCellMotion, FreeDiskStepIsTheSolveAtItsNewVelocity) {
  Params params = ParseScene(
      "[domain]\nsize = [1.0, 1.0]\nh = 0.0625\n"
      "[fluid]\ndensity = 1.0\nviscosity = 0.5\ngravity = [0.3, -9.81]\n"
      "[time]\ndt = 0.02\nend = 0.1\n"
      "[particle_mesh]\nkind = \"cut_cell\"\n"
      "[[particles]]\ndiameter = 0.4\ncenter = [0.47, 0.53]\ndensity = 1.5\n");
  const Grid g = params.domain.VelocityGrid();
  CutCellStep step(params, g);
  const BoundaryData data(g, params.domain);
  std::vector<double> u(g.NodeCount(), 0.0), v(g.NodeCount(), 0.0);
  std::vector<double> p(g.Coarse().NodeCount(), 0.0);
  std::vector<ParticleState> particles(1);
  StepReport report;
  const double dt = params.time.dt;
  step.MoveBeforeStep(dt, u.data(), v.data());
  step.Solve(dt, data, particles, u.data(), v.data(), p.data(), report);
  const ParticleState& s = particles[0];
  EXPECT_EQ(s.position, params.particles[0].center);  // X^1 = X^0 + dt V^0, V^0 = 0
  const Shape shape = Shape::Of(params.particles[0]);
  const double mass = shape.Mass(1.5), inertia = shape.MomentOfInertia(1.5);
  const Vec2 newton = mass * s.velocity / dt - s.force - mass * params.gravity;
  EXPECT_LT(newton.norm(), 1e-10 * s.force.norm());
  EXPECT_LT(std::abs(inertia * s.angular_velocity / dt - s.torque), 1e-10 * s.force.norm());
  EXPECT_GT(s.velocity.norm(), 0.01);  // it moves: the check above is not 0 = 0
  // The solve with g = V^1 on the same geometry: no load (u^0 = 0), the same forms.
  std::vector<FixedBody> body{{shape, s.position, 0.0}};
  const CutCellGeometry sw_ne(g, body), nw_se(g, body, CutTriangulation::kNwSe);
  CutCellStokes direct(sw_ne, nw_se, params.domain, params.fluid.viscosity, 1.0, 1.0 / dt);
  direct.SetBodyMotion({{s.position, s.velocity, s.angular_velocity}});
  std::vector<double> du(g.NodeCount(), 0.0), dv(g.NodeCount(), 0.0);
  std::vector<double> dp(g.Coarse().NodeCount(), 0.0);
  direct.SolveDirect(data, nullptr, nullptr, du.data(), dv.data(), dp.data());
  double diff = 0.0, umax = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    if (direct.FluidMass()[static_cast<Eigen::Index>(k)] == 0.0) continue;  // rigid: filled
    diff = std::max({diff, std::abs(u[k] - du[k]), std::abs(v[k] - dv[k])});
    umax = std::max({umax, std::abs(du[k]), std::abs(dv[k])});
  }
  const CutCellStokes::BodyLoad load =
      direct.Load(0, s.position, du.data(), dv.data(), dp.data(), nullptr, nullptr);
  const Vec2 f_direct = load.force + shape.Mass(1.0) * (-params.gravity);
  std::printf(
      "V^1 = (%.6f, %.6f), omega^1 = %.3e; |u - u(g = V^1)| / |u| = %.2e, |dF| / |F| = %.2e\n",
      s.velocity.x(), s.velocity.y(), s.angular_velocity, diff / umax,
      (f_direct - s.force).norm() / s.force.norm());
  // The unit solves stop at a relative residual of 1e-7 (CutCellConstants::step_tolerance), which
  // leaves the velocity 2.9e-6 and the force 2.2e-7 off (measured); what fails here is an O(1)
  // error, 1e5 times as large.
  EXPECT_LT(diff, 1e-5 * umax);
  EXPECT_LT((f_direct - s.force).norm(), 1e-5 * s.force.norm());
}

}  // namespace
}  // namespace dlmfd
