#include "dlmfd/conformation/conformation_advection.h"

#include <algorithm>
#include <cmath>

#include "dlmfd/core/target_clones.h"

namespace dlmfd {

ConformationAdvection::ConformationAdvection(const Grid& grid, bool periodic_x, bool periodic_y,
                                             double blend_kappa)
    : grid_(grid),
      periodic_x_(periodic_x),
      periodic_y_(periodic_y),
      kappa_(blend_kappa),
      padded_nx_(grid.nx + 1 + 2 * kGhost),
      padded_ny_(grid.ny + 1 + 2 * kGhost) {
  const std::size_t n = std::size_t(padded_nx_) * std::size_t(padded_ny_);
  storage_.assign(9 * n, 0.0);
  for (int c = 0; c < 3; ++c) {
    a_[c] = storage_.data() + c * n;
    s1_[c] = storage_.data() + (3 + c) * n;
    s2_[c] = storage_.data() + (6 + c) * n;
  }
  const std::size_t boundary_nodes = 2 * std::size_t(grid.nx + 1) + 2 * std::size_t(grid.ny + 1);
  fixed_index_.reserve(boundary_nodes);
  fixed_value_.reserve(boundary_nodes);
}

void ConformationAdvection::ClearFixed() {
  fixed_index_.clear();
  fixed_value_.clear();
}

void ConformationAdvection::AddFixed(int i, int j, const SymTensor& value) {
  fixed_index_.push_back(Padded(i, j));
  fixed_value_.push_back(value);
}

void ConformationAdvection::FillGhosts(double* f) const {
  const int nx = grid_.nx, ny = grid_.ny;
  for (int j = 0; j <= ny; ++j) {
    double* row = f + Padded(0, j);  // row[i] is node (i, j)
    if (periodic_x_) {
      row[nx] = row[0];
      row[-1] = row[nx - 1];
      row[-2] = row[nx - 2];
      row[nx + 1] = row[1];
      row[nx + 2] = row[2];
    } else {
      row[-1] = row[-2] = row[0];
      row[nx + 1] = row[nx + 2] = row[nx];
    }
  }
  const std::size_t stride = std::size_t(padded_nx_);
  auto copy_row = [&](int to, int from) {
    std::copy_n(f + Padded(-kGhost, from), stride, f + Padded(-kGhost, to));
  };
  if (periodic_y_) {
    copy_row(ny, 0);
    copy_row(-1, ny - 1);
    copy_row(-2, ny - 2);
    copy_row(ny + 1, 1);
    copy_row(ny + 2, 2);
  } else {
    copy_row(-1, 0);
    copy_row(-2, 0);
    copy_row(ny + 1, ny);
    copy_row(ny + 2, ny);
  }
}

void ConformationAdvection::RestoreFixedAndGhosts(double* const f[3]) const {
  for (std::size_t n = 0; n < fixed_index_.size(); ++n) {
    f[0][fixed_index_[n]] = fixed_value_[n].a11;
    f[1][fixed_index_[n]] = fixed_value_[n].a12;
    f[2][fixed_index_[n]] = fixed_value_[n].a22;
  }
  for (int c = 0; c < 3; ++c) FillGhosts(f[c]);
}

void ConformationAdvection::Load(const double* a11, const double* a12, const double* a22) {
  const double* src[3] = {a11, a12, a22};
#pragma omp parallel for schedule(static)  // the rows of Stage's static split
  for (int j = 0; j <= grid_.ny; ++j) {
    for (int c = 0; c < 3; ++c) {
      std::copy_n(src[c] + grid_.Index(0, j), grid_.nx + 1, a_[c] + Padded(0, j));
    }
  }
  RestoreFixedAndGhosts(a_);
}

namespace {

// One row of a stage: out = w_base base + w_in (a - tau (u dA/dx + v dA/dy)), third-order
// upwind-biased differences written without a branch, so that the loop vectorises:
// u D_upwind = u C + |u| Q with C = (A_{i-2} - 8 A_{i-1} + 8 A_{i+1} - A_{i+2}) / 12 (the mean of
// the two biased stencils) and Q = (A_{i-2} - 4 A_{i-1} + 6 A_i - 4 A_{i+1} + A_{i+2}) / 12 (half
// their difference); for u > 0 this is (A_{i-2} - 6 A_{i-1} + 3 A_i + 2 A_{i+1}) / 6, for u < 0 its
// mirror. Compiled for AVX2 and for the baseline, chosen at load time (GCC function
// multi-versioning).
DLMFD_AVX2_CLONES void AdvectRow(int count, const double* __restrict u, const double* __restrict v,
                                 const double* __restrict a, std::ptrdiff_t sy,
                                 const double* __restrict base, double w_base, double w_in,
                                 double tau_over_12h, double* __restrict out) {
  for (int i = 0; i < count; ++i) {
    const double* p = a + i;
    const double cx = p[-2] - 8.0 * (p[-1] - p[1]) - p[2];
    const double qx = p[-2] + p[2] - 4.0 * (p[-1] + p[1]) + 6.0 * p[0];
    const double cy = p[-2 * sy] - 8.0 * (p[-sy] - p[sy]) - p[2 * sy];
    const double qy = p[-2 * sy] + p[2 * sy] - 4.0 * (p[-sy] + p[sy]) + 6.0 * p[0];
    const double flux = u[i] * cx + std::abs(u[i]) * qx + v[i] * cy + std::abs(v[i]) * qy;
    out[i] = w_base * base[i] + w_in * (p[0] - tau_over_12h * flux);
  }
}

}  // namespace

void ConformationAdvection::Stage(double tau, const double* u, const double* v, double w_base,
                                  double* const base[3], double w_in, double* const in[3],
                                  double* const out[3]) const {
  const int nx = grid_.nx, ny = grid_.ny;
  const std::ptrdiff_t sy = padded_nx_;
  const double tau_over_12h = tau / (12.0 * grid_.h);
#pragma omp parallel for schedule(static)
  for (int j = 0; j <= ny; ++j) {
    const std::size_t k = grid_.Index(0, j);
    const std::size_t p = Padded(0, j);
    for (int c = 0; c < 3; ++c) {
      AdvectRow(nx + 1, u + k, v + k, in[c] + p, sy, base[c] + p, w_base, w_in, tau_over_12h,
                out[c] + p);
    }
  }
}

long ConformationAdvection::SubStep(double tau, const double* u, const double* v) {
  // SSP-RK3: s1 = A + tau R(A); s2 = 3/4 A + 1/4 (s1 + tau R(s1)); s1 = 1/3 A + 2/3 (s2 + tau
  // R(s2)).
  Stage(tau, u, v, 0.0, a_, 1.0, a_, s1_);  // base = in: 0 * base adds nothing
  RestoreFixedAndGhosts(s1_);
  Stage(tau, u, v, 0.75, a_, 0.25, s1_, s2_);
  RestoreFixedAndGhosts(s2_);
  Stage(tau, u, v, 1.0 / 3.0, a_, 2.0 / 3.0, s2_, s1_);

  // Blend A_H = s1 against the first-order upwind update of A, into s2.
  const int nx = grid_.nx, ny = grid_.ny;
  const std::ptrdiff_t sy = padded_nx_;
  const double tau_over_h = tau / grid_.h;
  const double kappa = kappa_;
  const bool blend = blend_enabled_;
  long blended = 0;
#pragma omp parallel for schedule(static) reduction(+ : blended)
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const std::size_t k = grid_.Index(i, j);
      const std::size_t p = Padded(i, j);
      const SymTensor high{s1_[0][p], s1_[1][p], s1_[2][p]};
      SymTensor result = high;
      if (blend) {
        const double cx = u[k] * tau_over_h, cy = v[k] * tau_over_h;
        const std::ptrdiff_t ox = cx >= 0.0 ? -1 : 1;
        const std::ptrdiff_t oy = cy >= 0.0 ? -sy : sy;
        const double ax = std::abs(cx), ay = std::abs(cy), centre = 1.0 - ax - ay;
        double low_c[3];
        for (int c = 0; c < 3; ++c) {
          const double* a = a_[c] + p;
          low_c[c] = centre * a[0] + ax * a[ox] + ay * a[oy];
        }
        const SymTensor low{low_c[0], low_c[1], low_c[2]};
        // Screen: lambda_min(A_H) >= Gershgorin bound >= kappa min diag(A_L) >= kappa
        // lambda_min(A_L) keeps A_H without the eigenvalues (the common case).
        if (GershgorinLowerBound(high) >= kappa * std::min(low.a11, low.a22)) {
          s2_[0][p] = high.a11;
          s2_[1][p] = high.a12;
          s2_[2][p] = high.a22;
          continue;
        }
        const double m_low = MinEigenvalue(low);
        if (!IsFinite(high)) {
          result = low;
          ++blended;
        } else {
          const double m_high = MinEigenvalue(high);
          if (m_high < kappa * m_low) {
            const double theta = (1.0 - kappa) * m_low / (m_low - m_high);
            result = Mix(theta, high, low);
            ++blended;
          }
        }
      }
      s2_[0][p] = result.a11;
      s2_[1][p] = result.a12;
      s2_[2][p] = result.a22;
    }
  }
  for (int c = 0; c < 3; ++c) std::swap(a_[c], s2_[c]);
  RestoreFixedAndGhosts(a_);
  return blended;
}

}  // namespace dlmfd
