// The derived quantities of a scene have one function each (core/params.h, core/time_stepping.h):
// the polymer modulus G = eta_p / lambda, the cell elasticity number El_h = lambda eta_p / (rho
// h^2) and the DEVSS weight w = 1 / (1 + El_h) built on it, the elastic wave speed c = sqrt(G /
// rho), the Deborah number lambda U / L, when an output of a period is due and how many snapshots
// a run writes.
#include <gtest/gtest.h>

#include <cmath>

#include "dlmfd/core/params.h"
#include "dlmfd/core/time_stepping.h"

namespace dlmfd {
namespace {

// The paper's 5.2 liquid (eta = 0.12, beta = 0.5, lambda = 1.4, rho = 1) on its h = 1/96:
// eta_p = 0.06, G = 0.06 / 1.4, El_h = 1.4 * 0.06 * 96^2 = 774.144.
TEST(DerivedQuantities, ModulusAndCellElasticityOfThePapersLiquid) {
  FluidParams f;
  f.viscosity = 0.12;
  f.solvent_ratio = 0.5;
  f.relaxation_time = 1.4;
  const double h = 1.0 / 96;
  EXPECT_DOUBLE_EQ(f.PolymerModulus(), 0.06 / 1.4);
  EXPECT_NEAR(f.CellElasticity(h), 774.144, 1e-12 * 774.144);
  EXPECT_NEAR(f.DevssWeight(h), 1.0 / (1.0 + 774.144), 1e-15);
  f.stress_splitting = StressSplitting::kExplicit;
  EXPECT_EQ(f.DevssWeight(h), 0.0);
  // c = sqrt(G / rho) = sqrt(0.06 / 1.4); De of the paper's fall speed scale U = 1 on D = 0.2: 7.
  EXPECT_DOUBLE_EQ(f.ElasticWaveSpeed(), std::sqrt(0.06 / 1.4));
  EXPECT_DOUBLE_EQ(f.Deborah(1.0, 0.2), 7.0);
  // A Newtonian liquid carries no polymer: El_h = 0, De = 0.
  EXPECT_EQ(FluidParams{}.CellElasticity(h), 0.0);
  EXPECT_EQ(FluidParams{}.Deborah(1.0, 0.2), 0.0);
}

// Every 0.1 with dt = 0.01: due at steps 10, 20, ...; a period of 0 is never due.
TEST(DerivedQuantities, AnOutputIsDueWhenItsPeriodEnds) {
  int due = 0;
  for (long n = 1; n <= 100; ++n) due += OutputDue(n, 0.01, 0.1) ? 1 : 0;
  EXPECT_EQ(due, 10);
  EXPECT_TRUE(OutputDue(10, 0.01, 0.1));
  EXPECT_FALSE(OutputDue(11, 0.01, 0.1));
  EXPECT_FALSE(OutputDue(10, 0.01, 0.0));
}

// A run writes the initial snapshot and one at each step where one is due: SnapshotCount is that
// count (the daemon's max_snapshots compares it), for periods that end on a step and that do not.
TEST(DerivedQuantities, TheSnapshotCountIsWhatTheRunWrites) {
  for (const double every : {0.1, 0.25, 0.033, 1.0, 2.0}) {
    TimeParams time;
    time.dt = 0.01;
    time.end = 1.0;
    long written = 1;
    for (long n = 1; n <= StepCount(time); ++n) written += OutputDue(n, time.dt, every) ? 1 : 0;
    EXPECT_EQ(SnapshotCount(time, every), written) << every;
  }
  EXPECT_EQ(SnapshotCount(TimeParams{}, 0.1), 11);
  EXPECT_EQ(SnapshotCount(TimeParams{}, 0.0), 0);
}

}  // namespace
}  // namespace dlmfd
