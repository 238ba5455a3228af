// The limit lambda -> 0 of the discrete Oldroyd-B step against the Newtonian step (issue 13 point
// 1). Under the paper's explicit polymer stress (fluid.stress_splitting = explicit) the two are
// different discretisations of the same liquid at a fixed grid. With lambda << dt the pointwise
// update of (35) gives A - I = 2 lambda D(u) + O(lambda^2), so the polymer force is eta_p div(2
// D(u)) taken explicitly, through the node-averaged P1 gradient and with A = I at the nodes inside
// particles, while the Newtonian step carries the same eta_p in the implicit 5-point Laplacian.
// Away from particles both are second-order consistent; next to a particle the polymer's stress is
// cut off over a band of one cell. So the gap between the lambda -> 0 limit and the lambda = 0
// answer is O(h^2) without particles and O(h) with them, and vanishes as h -> 0: the limit is
// continuous in the continuum, not bit for bit on a grid. The default devss carries the share
// w = 1 / (1 + El_h) of eta_p implicitly (El_h = lambda eta_p / (rho h^2)) and subtracts it from
// the explicit stress, so its gap is the explicit one times El_h / (1 + El_h): O(lambda) on every
// grid (tests/unit/viscosity_rule_test.cc follows it down to lambda = 1e-6).
// On the disk's channel lambda = 1e-4 stands for the limit of the explicit scheme: there its drag
// at lambda = 1e-4 and 1e-5 agree to 2e-7 relative, against gaps of 4 % and more.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "../support/viscous_channel.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/core/simulation.h"

namespace dlmfd {
namespace {

constexpr double kLimitLambda = 1e-4;
constexpr double kSolventRatio = 0.59;

void SetLiquid(Params& p, double lambda, StressSplitting splitting) {
  p.fluid.relaxation_time = lambda;
  p.fluid.solvent_ratio = lambda > 0.0 ? kSolventRatio : 1.0;
  p.fluid.stress_splitting = splitting;
}

// The channel and fixed disk of tests/unit/viscosity_rule_test.cc: the drag at t = 0.5.
double ChannelDrag(int cells, double dt, double lambda,
                   StressSplitting splitting = StressSplitting::kExplicit) {
  Params p = testing::ChannelWithFixedDisk(cells, dt, 0.0, 1.0);
  SetLiquid(p, lambda, splitting);
  Simulation sim(p);
  sim.Run();
  return sim.state().particles[0].force.x();
}

double MaxDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

// Taylor-Green vortex u = (sin 2 pi x cos 2 pi y, -cos 2 pi x sin 2 pi y) in the periodic unit box
// (A = I at t = 0), to t = 0.02 (it decays by e^{-8 pi^2 0.02} = 0.21): the velocity field under
// the paper's explicit polymer stress.
std::vector<double> TaylorGreenVelocity(int cells, double dt, double lambda) {
  Params p = testing::ViscousBase(1.0, 1.0, cells, dt);
  for (auto& side : p.domain.sides) side.type = SideType::kPeriodic;
  p.time.end = 0.02;
  SetLiquid(p, lambda, StressSplitting::kExplicit);
  Simulation sim(p);
  FlowState start = sim.state();
  const Grid& g = sim.grid();
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const double x = 2.0 * kPi * g.X(i), y = 2.0 * kPi * g.Y(j);
      start.u[g.Index(i, j)] = std::sin(x) * std::cos(y);
      start.v[g.Index(i, j)] = -std::cos(x) * std::sin(y);
    }
  }
  sim.Restore(start);
  sim.Run();
  std::vector<double> uv = sim.state().u;
  uv.insert(uv.end(), sim.state().v.begin(), sim.state().v.end());
  return uv;
}

// lambda = dt / 100 stands for the limit here (dt / lambda fixed as dt falls with h^2). Measured
// max gap 0.04809 / 0.01226 / 0.00305 at h = 1/8, 1/16, 1/32 (orders 1.97, 2.01; 2.00 on to 1/64,
// 0.00076, left out for its 30 s): second order, as both discretisations of eta_p div 2D(u) are
// on a smooth periodic flow, the explicit lag of the polymer force being O(dt) = O(h^2) here.
// Test: every observed order >= 1.8. (On the lid-driven cavity the max gap does not converge:
// D(u) is unbounded at the lid's corners, where the two discretisations differ at O(1); its L2 gap
// is first order.)
TEST(ViscosityLimit, TaylorGreenGapOfTheLambdaToZeroLimitIsSecondOrder) {
  const int cells[3] = {8, 16, 32};
  double gap[3];
  for (int k = 0; k < 3; ++k) {
    const double dt = 5e-4 * std::pow(16.0 / cells[k], 2);  // nu dt / h^2 fixed at 0.128
    gap[k] = MaxDifference(TaylorGreenVelocity(cells[k], dt, dt / 100.0),
                           TaylorGreenVelocity(cells[k], dt, 0.0));
    std::printf("Taylor-Green h = 1/%d: max |u(lambda -> 0) - u(0)| = %.4g\n", cells[k], gap[k]);
  }
  for (int k = 0; k + 1 < 3; ++k) {
    const double order = std::log2(gap[k] / gap[k + 1]);
    std::printf("order %.3f\n", order);
    EXPECT_GE(order, 1.8) << "h = 1/" << cells[k] << " to 1/" << cells[k + 1];
  }
}

// Measured relative drag gap of the explicit scheme 0.1106 / 0.0536 at h = 1/16, 1/32 (dt = 5e-4
// on both: eta_p dt / (rho h^2) = 0.21 and 0.84 for the explicit polymer force, the finest stable
// here), order 1.04: first order, the band of one cell at the disk where A = I cuts the polymer
// stress off. Test: observed order >= 0.8. The default devss at the same lambda: gap 1.06e-3 and
// 1.92e-3 (El_h = 0.0105 and 0.042), 0.92 and 0.89 of the model El_h / (1 + El_h) times the
// explicit gap. Test: within 1.2 times the model at both h.
TEST(ViscosityLimit, DiskGapOfTheLambdaToZeroLimitIsFirstOrder) {
  const int cells[2] = {16, 32};
  double gap[2];
  for (int k = 0; k < 2; ++k) {
    const double newtonian = ChannelDrag(cells[k], 5e-4, 0.0);
    gap[k] = std::abs(ChannelDrag(cells[k], 5e-4, kLimitLambda) - newtonian) / newtonian;
    const double devss =
        std::abs(ChannelDrag(cells[k], 5e-4, kLimitLambda, StressSplitting::kDevss) - newtonian) /
        newtonian;
    const double h = 1.0 / cells[k];
    const double elasticity = kLimitLambda * (1.0 - kSolventRatio) / (h * h);  // rho = eta = 1
    const double model = elasticity / (1.0 + elasticity) * gap[k];
    std::printf("disk h = 1/%d: drag gap %.4g relative (explicit), %.4g (devss; model %.4g)\n",
                cells[k], gap[k], devss, model);
    EXPECT_LE(devss, 1.2 * model) << "h = 1/" << cells[k];
  }
  const double order = std::log2(gap[0] / gap[1]);
  std::printf("order %.3f\n", order);
  EXPECT_GE(order, 0.8);
}

// With cut cells (particle_mesh.kind = "cut_cell", particles/cut_cell_step.h) and the default
// devss the polymer's force acts on the fluid part only, and the nodes inside the disk next to the
// fluid take the fluid's A and D_h (CutCellStep::ExtendIntoBodies), so the explicit rest
// G (A - I) - w eta_p 2 D_h is O(lambda) at every node the fluid polygons read: the gap to the
// Newtonian cut-cell drag falls at first order in lambda or faster, with no O(h) band left.
// The velocity's ghost penalty follows the polymer's elastic share 1 - w (particles/
// cut_cell_step.h), O(lambda) too. Measured (h = 1/16, dt = 2e-3): gaps 5.06e-3, 5.28e-4,
// 5.31e-5 of 51.0469 at lambda = 1e-3, 1e-4, 1e-5, orders 0.98 and 1.00 (with the Newtonian
// penalty throughout: 7.62e-3, 8.24e-4, 8.31e-5). Rerun 2026-12-06, the Params leaving
// conformation.velocity to "auto" as the scene does (the Stokes step's velocity around cut cells):
// 4.978e-3, 5.195e-4, 5.217e-5 of 51.2788, orders 0.98 and 1.00 (the paper's velocity named:
// 4.976e-3, 5.192e-4, 5.214e-5). With D_h left at 0 inside the disk the gap grew
// as lambda fell (to 1.6 % at lambda = 1e-5, the case file's numerics: the band carried the whole
// polymer stress beside the implicit w eta_p). Test: observed order >= 0.9 over each decade.
TEST(ViscosityLimit, WithCutCellsTheDevssGapIsFirstOrderInLambda) {
  auto drag = [](double lambda) {
    Params p = testing::ChannelWithFixedDisk(16, 2e-3, 0.0, 1.0);
    p.particle_mesh.kind = ParticleMeshKind::kCutCell;
    SetLiquid(p, lambda, StressSplitting::kDevss);
    Simulation sim(p);
    sim.Run();
    return sim.state().particles[0].force.x();
  };
  const double newtonian = drag(0.0);
  const double lambdas[3] = {1e-3, 1e-4, 1e-5};
  double gap[3];
  for (int k = 0; k < 3; ++k) {
    gap[k] = std::abs(drag(lambdas[k]) - newtonian) / newtonian;
    std::printf("cut cells, lambda = %g: drag gap %.4g relative (Newtonian %.10g)\n", lambdas[k],
                gap[k], newtonian);
  }
  for (int k = 0; k < 2; ++k) {
    const double order = std::log10(gap[k] / gap[k + 1]);
    std::printf("order from lambda = %g: %.3f\n", lambdas[k], order);
    EXPECT_GE(order, 0.9) << "lambda = " << lambdas[k];
  }
}

}  // namespace
}  // namespace dlmfd
