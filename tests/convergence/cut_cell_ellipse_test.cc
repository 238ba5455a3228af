// A fixed ellipse cut out of the mesh (particles/cut_cell_stokes.h; issue 37 point 4, issue 33):
// the creeping channel of the cut-cell disk (tests/support/cut_cell_creeping.h) with the disk
// replaced by the ellipse of its area, a / b = 2 (a = 0.0707107, b = 0.0353553), its long axis at
// 30 degrees, centred at (0.2 + s h, 0.2), s = 0, h/4, ..., 7h/4, and 2h. Each force and torque is
// moved back to s = 0 with the slope of the 2h shift (the same discrete geometry: the slope is the
// physical effect of the inflow's distance); what is left over the shifts is the grid's. F = the
// force, T = the torque about the centre, eta = 1. The spreads over the eight shifts, of Fx and Fy
// relative to their means, of T relative to |F| a (the torque is small here: 0.0026 against
// |F| a = 0.46).
// Measured (this test's output, 2026-12-08; docs/evidence/cut_cell_boundary.md, "A fixed ellipse"):
//   D/h   Fx (mean)           Fy (mean)            T
//   10    0.161 % (6.44463)   0.445 % (-1.30080)   2.4e-4 (0.002689)
//   20    0.037 % (6.40470)   0.143 % (-1.26941)   1.2e-4 (0.002617)
// Asserted: each spread at D/h = 20 at most 2.5 times the measured one (as the disk's test;
// the collocation points' spreads of the Navier-Stokes case at D/h = 20, 1.0-3.0 % moved back,
// are what they must stay below), and each falling from D/h = 10 to 20 by more than 1.5 (measured
// 4.4, 3.1 and 2.0).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "../support/cut_cell_creeping.h"
#include "dlmfd/core/constants.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/particles/cut_cell_stokes.h"

namespace dlmfd {
namespace {

constexpr double kSemiMajor = 0.07071067811865475, kSemiMinor = 0.035355339059327376;

// Fx, Fy, T of the steady creeping flow with the ellipse's centre shifted by `shift` cells.
std::array<double, 3> EllipseLoad(double d_over_h, double shift) {
  const DomainParams d = CutCreepingChannel(d_over_h);
  const Grid g = d.VelocityGrid();
  std::vector<FixedBody> body(1);
  body[0].shape = Shape::Ellipse(kSemiMajor, kSemiMinor);
  body[0].centre = Vec2(0.2 + shift * d.h, 0.2);
  body[0].angle = kPi / 6.0;
  const CutCellGeometry geo(g, body);
  CutCellStokes flow(geo, d, 1.0, 1.0, 0.0);
  const BoundaryData data(g, d);
  std::vector<double> u(g.NodeCount()), v(g.NodeCount()), p(g.Coarse().NodeCount());
  flow.Solve(data, nullptr, nullptr, u.data(), v.data(), p.data(), 1e-10, 3000);
  const CutCellStokes::BodyLoad load =
      flow.Load(0, body[0].centre, u.data(), v.data(), p.data(), nullptr, nullptr);
  return {load.force.x(), load.force.y(), load.torque};
}

// The spread over the shifts of each of Fx, Fy, T moved back to s = 0: of Fx and Fy relative to
// their means, of T relative to |F| a.
std::array<double, 3> SpreadsOverShifts(double d_over_h) {
  const std::vector<double> shifts = {0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75};
  std::vector<std::array<double, 3>> loads;
  for (double s : shifts) loads.push_back(EllipseLoad(d_over_h, s));
  const std::array<double, 3> two_cells = EllipseLoad(d_over_h, 2.0);
  std::array<double, 3> spreads{};
  const char* names[3] = {"Fx", "Fy", "T"};
  const double lever = std::hypot(loads[0][0], loads[0][1]) * kSemiMajor;  // |F| a
  for (int c = 0; c < 3; ++c) {
    const double slope = (two_cells[c] - loads[0][c]) / 2.0;
    std::vector<double> moved;
    double mean = 0.0;
    for (std::size_t k = 0; k < shifts.size(); ++k) {
      moved.push_back(loads[k][c] - slope * shifts[k]);
      mean += moved.back() / static_cast<double>(shifts.size());
    }
    const auto [lo, hi] = std::minmax_element(moved.begin(), moved.end());
    spreads[c] = (*hi - *lo) / (c < 2 ? std::abs(mean) : lever);
    std::printf("D/h %g %s: moved back", d_over_h, names[c]);
    for (double f : moved) std::printf(" %.6f", f);
    std::printf("; mean %.6f, slope %+.6f a cell, spread %.3f %%\n", mean, slope,
                100.0 * spreads[c]);
  }
  return spreads;
}

TEST(CutCellCreepingEllipse, ForcesAndTorqueDoNotDependOnTheSubGridPosition) {
  const std::array<double, 3> coarse = SpreadsOverShifts(10.0);
  const std::array<double, 3> fine = SpreadsOverShifts(20.0);
  const double measured20[3] = {0.00037, 0.00143, 0.00012};
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(fine[c], 2.5 * measured20[c]) << c;
    EXPECT_GT(coarse[c] / fine[c], 1.5) << c;
  }
}

}  // namespace
}  // namespace dlmfd
