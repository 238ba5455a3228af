// The block preconditioner of the multiplier CG (particles/multiplier_preconditioner.h): an
// isolated particle's block is the whole Schur complement of (37), so the CG converges in one
// iteration (two with round-off) wherever the particle's centre sits in its cell, for fixed, heavy
// and neutrally buoyant particles, with either point set; particles that share nodes take a few
// more, not more as they grow in number; the answer is the unpreconditioned CG's (the same linear
// system) to the tight tolerance's round-off. docs/evidence/validation_particles.md, "A multiplier
// solve whose cost does not depend on sub-grid position".
#include "dlmfd/particles/multiplier_preconditioner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>
#include <vector>

#include "../support/constraint_disk_scene.h"
#include "dlmfd/particles/rigid_body_constraint.h"

namespace dlmfd {
namespace {

using Scene = testing::ConstraintDiskScene;

// The disk of Scene centred at (f h, f h) off the node (24, 24), under the given preconditioner
// and tolerance, on the given points; returns the CG's iterations and leaves the answer in s.
int Solve(Scene& s, double f, MultiplierPreconditioning preconditioner, double tolerance,
          ParticleMeshKind kind = ParticleMeshKind::kCollocation) {
  const Vec2 centre = Vec2(0.5, 0.5) + f * s.grid.h * Vec2(1.0, 1.0);
  s.params.particles[0].center = centre;
  s.particles[0].position = centre;
  s.params.particle_mesh.kind = kind;
  // The paper's ring mesh ratio h_p / h = 96 / 70 (a finer ring has more points than nodes: B_p is
  // singular and the block falls back to G).
  if (kind == ParticleMeshKind::kRing) s.params.particle_mesh.h = 96.0 / 70.0 * s.grid.h;
  s.params.solvers.multiplier_tolerance = tolerance;
  s.params.solvers.multiplier_preconditioner = preconditioner;
  s.Vortical();
  RigidBodyConstraint dlm(s.params, s.grid);
  return dlm.Enforce(0.0, 4e-4, s.particles, s.u.data(), s.v.data()).iterations;
}

double MaxDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) worst = std::max(worst, std::abs(a[k] - b[k]));
  return worst;
}

struct Body {
  const char* name;
  double density;
  Motion motion;
};
constexpr Body kBodies[] = {
    {"fixed", 1.5, Motion::kFixed}, {"heavy", 1.5, Motion::kFree}, {"neutral", 1.0, Motion::kFree}};

TEST(MultiplierPreconditioner, OneParticleConvergesInOneIterationAtEverySubGridPosition) {
  for (const Body& body : kBodies) {
    for (const ParticleMeshKind kind : {ParticleMeshKind::kCollocation, ParticleMeshKind::kRing}) {
      for (const double f : {0.0, 0.25, 0.5}) {
        Scene blocks(body.density, body.motion), gram(body.density, body.motion);
        const int its = Solve(blocks, f, MultiplierPreconditioning::kBlocks, 1e-4, kind);
        const int its_gram = Solve(gram, f, MultiplierPreconditioning::kGram, 1e-4, kind);
        std::printf("%s %s f = %.2f: %d iterations (unpreconditioned %d)\n", body.name,
                    kind == ParticleMeshKind::kRing ? "ring" : "collocation", f, its, its_gram);
        EXPECT_GE(its, 1);
        EXPECT_LE(its, 2);  // one in exact arithmetic
      }
    }
  }
}

TEST(MultiplierPreconditioner, GivesTheUnpreconditionedAnswer) {
  // The same linear system: at a tight tolerance both CGs reach its solution.
  for (const Body& body : kBodies) {
    for (const double f : {0.0, 0.5}) {
      Scene blocks(body.density, body.motion), gram(body.density, body.motion);
      Solve(blocks, f, MultiplierPreconditioning::kBlocks, 1e-11);
      Solve(gram, f, MultiplierPreconditioning::kGram, 1e-11);
      const double du = std::max(MaxDifference(blocks.u, gram.u), MaxDifference(blocks.v, gram.v));
      const double dU = (blocks.particles[0].velocity - gram.particles[0].velocity).norm();
      const double domega =
          std::abs(blocks.particles[0].angular_velocity - gram.particles[0].angular_velocity);
      std::printf("%s f = %.1f: |du| %.2e, |dU| %.2e, |domega| %.2e\n", body.name, f, du, dU,
                  domega);
      // The fields and the motion are O(1) and each CG stops at 1e-11 of the cold residual; the
      // two answers differ by at most 6.5e-11 (measured, these six cases): 1e-9 is the stopping
      // rule's 1e-11 times a condition factor of 100.
      EXPECT_LT(du, 1e-9);
      EXPECT_LT(dU, 1e-9);
      EXPECT_LT(domega, 1e-9);
    }
  }
}

TEST(MultiplierPreconditioner, KeepsWhatTheStencilsDidNotChange) {
  // A block depends only on its particle's stencils, dt and points: a second Build at the same
  // position keeps it, a move within the stencils' cells refactors it on the kept analysis (unless
  // a weight of exactly 0, a point on a grid line, became nonzero: E^T then reaches another node),
  // and either way the answer is bit for bit that of a preconditioner built afresh. Off the grid
  // lines (Scene's centre) and on a node (every interior point on grid lines).
  struct Start {
    Vec2 centre;
    std::uint64_t analyses_after_move;
  };
  for (const Start& start : {Start{Vec2(0.5137, 0.4871), 1}, Start{Vec2(0.5, 0.5), 2}}) {
    Scene s(1.5, Motion::kFixed);
    s.params.solvers.multiplier_preconditioner = MultiplierPreconditioning::kBlocks;
    s.params.particles[0].center = start.centre;
    s.particles[0].position = start.centre;
    RigidBodyConstraint dlm(s.params, s.grid);
    const MultiplierPreconditioner& blocks = dlm.cg().Preconditioner();
    const auto solve = [&s](RigidBodyConstraint& constraint) {
      s.Vortical();
      constraint.Enforce(0.0, 4e-4, s.particles, s.u.data(), s.v.data());
      return std::make_pair(s.u, s.v);
    };
    solve(dlm);
    EXPECT_EQ(blocks.Factorisations(), 1u);
    EXPECT_EQ(blocks.Analyses(), 1u);
    solve(dlm);  // the same position: kept
    EXPECT_EQ(blocks.Factorisations(), 1u);
    // A millionth of a cell: every point keeps its stencil's nodes, the weights change.
    s.particles[0].position += Vec2(1e-6, -1e-6) * s.grid.h;
    const std::vector<ParticleState> before = s.particles;  // the same warm start for both
    const auto kept = solve(dlm);
    EXPECT_EQ(blocks.Factorisations(), 2u);
    EXPECT_EQ(blocks.Analyses(), start.analyses_after_move);
    s.params.particles[0].center = s.particles[0].position;
    RigidBodyConstraint fresh(s.params, s.grid);
    s.particles = before;
    EXPECT_TRUE(solve(fresh) == kept);
    // Half a cell: other nodes, a new analysis.
    s.particles[0].position += Vec2(0.5, 0.5) * s.grid.h;
    solve(dlm);
    EXPECT_EQ(blocks.Factorisations(), 3u);
    EXPECT_EQ(blocks.Analyses(), start.analyses_after_move + 1);
  }
}

// k x k disks of Scene's diameter, heavy, neutral or fixed by turns, a gap of h / 2 apart (their
// stencils share fluid nodes, which the blocks leave out), each at another sub-grid position.
int SolveLattice(int k, MultiplierPreconditioning preconditioner) {
  Scene s(1.5);
  const double spacing = 0.2 + 0.5 * s.grid.h;
  s.params.particles.clear();
  s.particles.clear();
  for (int n = 0; n < k * k; ++n) {
    const Body& body = kBodies[n % 3];
    ParticleParams pp;
    pp.center = Vec2(0.17 + (n % k) * spacing, 0.13 + (n / k) * spacing);
    pp.diameter = 0.2;
    pp.density = body.density;
    pp.motion = body.motion;
    s.params.particles.push_back(pp);
    ParticleState state;
    state.id = n;
    state.position = pp.center;
    state.radius = 0.1;
    state.density = body.density;
    state.motion = body.motion;
    state.velocity = Vec2(0.1, -0.2);
    state.angular_velocity = 0.5;
    s.particles.push_back(state);
  }
  s.params.solvers.multiplier_preconditioner = preconditioner;
  s.Vortical();
  RigidBodyConstraint dlm(s.params, s.grid);
  return dlm.Enforce(0.0, 4e-4, s.particles, s.u.data(), s.v.data()).iterations;
}

TEST(MultiplierPreconditioner, IterationsDoNotGrowWithTheNumberOfParticles) {
  // What is left to the CG is the coupling of neighbours through shared nodes, whose spectrum does
  // not widen with the count (each disk has at most four neighbours). Measured: 1, 8, 9, 11
  // iterations for 1, 4, 9, 16 disks (unpreconditioned 7, 12, 20, 27); the bound is 1.5 times the
  // 2 x 2 lattice's count, for the few more distinct eigenvalues of a larger lattice.
  int its_four = 0;
  for (int k = 1; k <= 4; ++k) {
    const int its = SolveLattice(k, MultiplierPreconditioning::kBlocks);
    const int its_gram = SolveLattice(k, MultiplierPreconditioning::kGram);
    std::printf("%d disks: %d iterations (unpreconditioned %d)\n", k * k, its, its_gram);
    if (k == 2) its_four = its;
    if (k > 2) {
      EXPECT_LE(its, 1.5 * its_four);
    }
    EXPECT_LT(its, its_gram);
  }
}

}  // namespace
}  // namespace dlmfd
