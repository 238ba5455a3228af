// TypeOneTransform (engine/src/solvers/type_one_transform.cc) against FFTW's own RODFT00 / REDFT00
// on random rows: the extension identities of the header are exact, so the two agree to the
// round-off of a length-L FFT. Measured: at most 3e-16 of the largest output (0 up to length 7);
// 1e-13 is a bound of a few ulps times log2 L with a wide margin, far below any wrong sign, index
// or scale (those give differences of order 1).
#include "dlmfd/solvers/type_one_transform.h"

#include <fftw3.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace dlmfd {
namespace {

std::vector<double> RandomRows(int length, int rows, unsigned seed) {
  std::vector<double> x(std::size_t(length) * rows);
  for (double& v : x) {
    seed = seed * 1664525u + 1013904223u;
    v = static_cast<double>(seed >> 8) / 16777216.0 - 0.5;
  }
  return x;
}

// FFTW's r2r transform of every row (the definition TypeOneTransform must reproduce).
std::vector<double> Reference(TypeOneTransform::Kind kind, int length, int rows,
                              std::vector<double> x) {
  const fftw_r2r_kind k = kind == TypeOneTransform::Kind::kSine ? FFTW_RODFT00 : FFTW_REDFT00;
  fftw_plan plan = fftw_plan_many_r2r(1, &length, rows, x.data(), nullptr, 1, length, x.data(),
                                      nullptr, 1, length, &k, FFTW_ESTIMATE);
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  return x;
}

double MaxRelativeDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    diff = std::max(diff, std::abs(a[k] - b[k]));
    scale = std::max(scale, std::abs(b[k]));
  }
  return diff / scale;
}

TEST(TypeOneTransform, MatchesFftwSineAndCosineKinds) {
  for (const auto kind : {TypeOneTransform::Kind::kSine, TypeOneTransform::Kind::kCosine}) {
    // The shortest lengths, odd and even ones, and the paper grid's 191 and 97 columns.
    for (const int length : {2, 3, 4, 7, 16, 97, 191}) {
      // 5 rows: one short block; 37 rows: two blocks of 16 and a tail of 5.
      for (const int rows : {5, 37}) {
        const std::vector<double> x = RandomRows(length, rows, 7u + length + rows);
        const std::vector<double> expected = Reference(kind, length, rows, x);
        std::vector<double> y = x;
        TypeOneTransform transform(kind, length, rows, 2);
        transform.Apply(y.data(), 1);
        const double difference = MaxRelativeDifference(y, expected);
        std::printf("%s, length %3d, rows %2d: max difference / max value %.2e\n",
                    kind == TypeOneTransform::Kind::kSine ? "sine  " : "cosine", length, rows,
                    difference);
        EXPECT_LE(difference, 1e-13) << (kind == TypeOneTransform::Kind::kSine ? "sine" : "cosine")
                                     << ", length " << length << ", rows " << rows;
      }
    }
  }
}

// A single sine point: Y_0 = 2 X_0 sin(pi / 2) = 2 X_0.
TEST(TypeOneTransform, OnePointSine) {
  TypeOneTransform transform(TypeOneTransform::Kind::kSine, 1, 1, 1);
  double x = 0.75;
  transform.Apply(&x, 0);
  EXPECT_DOUBLE_EQ(x, 1.5);
}

TEST(TypeOneTransform, RejectsLengthsWithoutAnExtension) {
  EXPECT_THROW(TypeOneTransform(TypeOneTransform::Kind::kSine, 0, 3, 1), std::exception);
  EXPECT_THROW(TypeOneTransform(TypeOneTransform::Kind::kCosine, 1, 3, 1), std::exception);
  EXPECT_THROW(TypeOneTransform(TypeOneTransform::Kind::kCosine, 4, 0, 1), std::exception);
}

}  // namespace
}  // namespace dlmfd
