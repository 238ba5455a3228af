// Failure reporting of step (35): a field that is indefinite or not finite ends the step with a
// typed error naming the time, the node and its position, and the quantity (design.md 5; issue 4
// point 5).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "../support/studied_numerics.h"
#include "dlmfd/conformation/conformation_step.h"
#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

using ::testing::HasSubstr;

constexpr int kFailureCells = 8;

Params WalledBox() {
  Params p;
  testing::UseStudiedNumerics(p);
  p.domain.size = Vec2(1.0, 1.0);
  p.domain.h = 1.0 / kFailureCells;
  p.fluid.relaxation_time = 0.5;
  p.fluid.solvent_ratio = 0.5;
  return p;  // four walls by default
}

struct Case {
  Grid grid{kFailureCells, kFailureCells, 1.0 / kFailureCells, 0.0, 0.0};
  std::vector<double> u, v, a11, a12, a22;
  Case() {
    const std::size_t n = grid.NodeCount();
    u.assign(n, 0.0);
    v.assign(n, 0.0);
    a11.assign(n, 1.0);
    a12.assign(n, 0.0);
    a22.assign(n, 1.0);
  }
};

// Runs one step and returns the message of the expected error type.
template <typename ErrorType>
std::string ErrorOfStep(Case& c, double time, double dt = 0.01) {
  ConformationStep step(WalledBox(), c.grid);
  StepReport report;
  try {
    step.Advance(time, dt, c.u.data(), c.v.data(), nullptr, c.a11.data(), c.a12.data(),
                 c.a22.data(), report);
  } catch (const ErrorType& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error thrown";
  return "";
}

TEST(ConformationFailure, IndefiniteFieldThrowsWithTimePlaceAndEigenvalue) {
  Case c;
  const std::size_t k = c.grid.Index(3, 5);  // (x, y) = (0.375, 0.625)
  c.a12[k] = 2.0;                            // [[1, 2], [2, 1]]: eigenvalues 3 and -1
  const std::string msg = ErrorOfStep<ConformationNotPositiveDefinite>(c, 1.25);
  EXPECT_THAT(msg, HasSubstr("not positive definite"));
  EXPECT_THAT(msg, HasSubstr("t = 1.25"));
  EXPECT_THAT(msg, HasSubstr("node (3, 5)"));
  EXPECT_THAT(msg, HasSubstr("(0.375, 0.625)"));
  EXPECT_THAT(msg, HasSubstr("lambda_min(A) = -1"));
  EXPECT_THAT(msg, HasSubstr("A12 = 2"));
}

TEST(ConformationFailure, NanInTheFieldThrowsNumericalBlowUp) {
  Case c;
  c.a22[c.grid.Index(7, 2)] = std::numeric_limits<double>::quiet_NaN();
  const std::string msg = ErrorOfStep<NumericalBlowUp>(c, 0.5);
  EXPECT_THAT(msg, HasSubstr("not finite"));
  EXPECT_THAT(msg, HasSubstr("t = 0.5"));
  EXPECT_THAT(msg, HasSubstr("node (7, 2)"));
  EXPECT_THAT(msg, HasSubstr("A22 = nan"));
  // The error type is also a RunFailure: the run ends FAILED with this reason.
  Case d;
  d.a11[0] = std::numeric_limits<double>::infinity();
  ConformationStep step(WalledBox(), d.grid);
  StepReport report;
  EXPECT_THROW(step.Advance(0.0, 0.01, d.u.data(), d.v.data(), nullptr, d.a11.data(), d.a12.data(),
                            d.a22.data(), report),
               RunFailure);
}

TEST(ConformationFailure, NanVelocityThrowsNumericalBlowUp) {
  Case c;
  c.u[c.grid.Index(4, 4)] = std::numeric_limits<double>::quiet_NaN();
  const std::string msg = ErrorOfStep<NumericalBlowUp>(c, 2.0);
  EXPECT_THAT(msg, HasSubstr("velocity"));
  EXPECT_THAT(msg, HasSubstr("t = 2"));
}

TEST(ConformationFailure, AVelocityBeyondAnyBoundThrowsInsteadOfSubCyclingForever) {
  // |u| = 1e4 with dt = 1 and h = 1/8: Courant 8e4, which would need 2e5 sub-steps.
  Case c;
  for (double& u : c.u) u = 1e4;
  const std::string msg = ErrorOfStep<NumericalBlowUp>(c, 3.0, 1.0);
  EXPECT_THAT(msg, HasSubstr("Courant number"));
  EXPECT_THAT(msg, HasSubstr("t = 3"));
}

}  // namespace
}  // namespace dlmfd
