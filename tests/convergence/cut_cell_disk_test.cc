// The cut-cell boundary (particles/cut_cell_stokes.h) on the creeping fixed disk of
// docs/evidence/particle_boundary.md ("The circle's sub-grid position"; "A second-order boundary:
// the engine's cut cells"): D = 0.1 at (0.2 + s h, 0.2) in a 0.8 x 0.4 channel, Poiseuille inflow
// of maximum 0.3, eta = 1, steady Stokes, at D/h = 10, 20, 40 and shifts s = 0, h/4, ..., 7h/4 (D/h
// = 40: 0, h/2, h, 3h/2), each drag moved back to s = 0 with the slope of the 2h shift (the same
// discrete geometry, so the slope is the physical effect of the inflow's distance). The
// reference 6.487 is the Richardson limit of the position means (prototype, D/h = 20-40-80).
// Measured (this test's output, 2026-12-04; bench/cut_cell_drag gives all eight shifts at 40):
//   D/h   mean error   spread    worst error   (moved back, against 6.487)
//   10    +0.882 %     0.155 %   0.926 %
//   20    +0.223 %     0.020 %   0.231 %
//   40    +0.042 %     0.006 %   0.046 %       (eight shifts: +0.045 %, 0.013 %, 0.053 %)
//   order of the means on their own differences 10-20-40: 1.86; of the worst error 20-40: 2.33.
// Asserted: the targets where they are stated (worst error <= 0.3 % and spread <= 0.2 % at
// D/h = 20, orders >= 1.8), and the spreads at most about 2.5 times the measured ones (the
// collocation points' spreads, 3.1 / 1.3 / 0.36 %, and the cut prototype's before the boundary
// pieces on mesh edges were kept, 1.1 % at D/h = 10, are what they must stay below).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "../support/cut_cell_creeping.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/particles/cut_cell_stokes.h"

namespace dlmfd {
namespace {

double CutCreepingDrag(double d_over_h, double shift) {
  const DomainParams d = CutCreepingChannel(d_over_h);
  const Grid g = d.VelocityGrid();
  std::vector<FixedBody> body(1);
  body[0].shape = Shape::Disk(0.05);
  body[0].centre = Vec2(0.2 + shift * d.h, 0.2);
  const CutCellGeometry geo(g, body);
  CutCellStokes flow(geo, d, 1.0, 1.0, 0.0);
  const BoundaryData data(g, d);
  std::vector<double> u(g.NodeCount()), v(g.NodeCount()), p(g.Coarse().NodeCount());
  flow.Solve(data, nullptr, nullptr, u.data(), v.data(), p.data(), 1e-10, 3000);
  return flow.Force(0, u.data(), v.data(), p.data()).x();
}

struct CutPositions {
  double mean = 0.0, spread = 0.0, worst = 0.0;  // spread and worst relative
};

CutPositions CutOverShifts(double d_over_h, const std::vector<double>& shifts) {
  const double f0 = CutCreepingDrag(d_over_h, 0.0);
  const double slope = (CutCreepingDrag(d_over_h, 2.0) - f0) / 2.0;
  std::vector<double> moved;
  for (double s : shifts)
    moved.push_back((s == 0.0 ? f0 : CutCreepingDrag(d_over_h, s)) - slope * s);
  CutPositions r;
  for (double f : moved) {
    r.mean += f / static_cast<double>(moved.size());
    r.worst = std::max(r.worst, std::abs(f / kCutCreepingReference - 1.0));
  }
  const auto [lo, hi] = std::minmax_element(moved.begin(), moved.end());
  r.spread = (*hi - *lo) / r.mean;
  std::printf("D/h %g: moved back", d_over_h);
  for (double f : moved) std::printf(" %.5f", f);
  std::printf("; mean %.5f (%+.3f %%), spread %.3f %%, worst %.3f %%\n", r.mean,
              100.0 * (r.mean / kCutCreepingReference - 1.0), 100.0 * r.spread, 100.0 * r.worst);
  return r;
}

TEST(CutCellCreepingDisk, SecondOrderAndPositionIndependent) {
  const std::vector<double> eight = {0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75};
  const CutPositions c10 = CutOverShifts(10.0, eight);
  const CutPositions c20 = CutOverShifts(20.0, eight);
  const CutPositions c40 = CutOverShifts(40.0, {0.0, 0.5, 1.0, 1.5});
  const double order = std::log2((c10.mean - c20.mean) / (c20.mean - c40.mean));
  const double worst_order = std::log2(c20.worst / c40.worst);
  std::printf("order of the means (own differences) %.2f, of the worst error 20-40 %.2f\n", order,
              worst_order);
  EXPECT_LT(c20.worst, 0.003);
  EXPECT_LT(c20.spread, 0.0005);
  EXPECT_LT(c40.worst, 0.001);
  EXPECT_LT(c40.spread, 0.0002);
  EXPECT_LT(c10.spread, 0.004);
  EXPECT_GE(order, 1.8);
  EXPECT_GE(worst_order, 1.8);
}

}  // namespace
}  // namespace dlmfd
