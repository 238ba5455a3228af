// Fast separable solver for (a M_l + b K) x = f (method notes 1, section 2).
//
// With V the generalized eigenvectors of (K1x, Dx) on the unknown columns, V^T Dx V = diag(c_k),
// the system splits into one tridiagonal system per mode k in y:
//   [(a h^2 + b lam_k) Dy + b K1y] xhat_k = (V^T f)_k / c_k,   x = V xhat.
// FFTW's r2r transforms compute V^T (f / w) and V (xhat / w') up to a factor 2 (w, w': 1/2 at the
// Neumann ends of the cosine kinds), and every case ends with one constant scale per mode:
//   DD  sin(pi k i / nx), k = 1..nx-1        RODFT00 / RODFT00   c_k = nx/2          -> 1/(2 nx)
//   NN  cos(pi k i / nx), k = 0..nx          REDFT00 / REDFT00   c_k = nx/2 (nx ends) -> 1/(2 nx)
//   DN  sin(pi (2k+1) i / (2 nx)), i = 1..nx RODFT01 / RODFT10   c_k = nx/2          -> 1/(2 nx)
//   ND  cos(pi (2k+1) i / (2 nx)), i = 0..nx-1 REDFT01 / REDFT10 c_k = nx/2          -> 1/(2 nx)
//   periodic: real DFT, halfcomplex R2HC / HC2R, lam_m = 2 - 2 cos(2 pi m / nx)      -> 1/nx
// The Thomas factors of every mode (and, for periodic y, the Sherman-Morrison vector of the cyclic
// system) are computed once here; Solve only sweeps. DD and NN use TypeOneTransform (a real DFT of
// the odd or even extension, faster than FFTW's own RODFT00/REDFT00), the other kinds FFTW r2r.
#include "dlmfd/solvers/separable_helmholtz.h"

#include <fftw3.h>
#include <omp.h>

#include <cmath>
#include <mutex>
#include <new>
#include <string>
#include <vector>

#include "dlmfd/core/errors.h"
#include "dlmfd/solvers/fft_planning.h"
#include "dlmfd/solvers/type_one_transform.h"

namespace dlmfd {
namespace {

// The FFTW planner is not thread-safe; executing plans is.
std::mutex& PlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

// The unknown lines of one axis: first index and count.
struct UnknownLines {
  int first = 0;
  int count = 0;
};

UnknownLines LinesOf(const AxisBoundary& ends, int cells) {
  if (ends.low == EndKind::kPeriodic) return {0, cells};
  const int first = ends.low == EndKind::kDirichlet ? 1 : 0;
  const int last = ends.high == EndKind::kDirichlet ? cells - 1 : cells;
  return {first, last - first + 1};
}

// Trapezoid weight of node line i on an axis (1/2 on a non-periodic end).
double LineWeight(const AxisBoundary& ends, int cells, int i) {
  if (ends.low == EndKind::kPeriodic) return 1.0;
  return (i == 0 || i == cells) ? 0.5 : 1.0;
}

struct Transform {
  fftw_r2r_kind forward, backward;
  double scale;  // per-mode factor of the forward-backward pair
};

Transform TransformFor(const AxisBoundary& x, int nx) {
  const double sine_cosine = 1.0 / (2.0 * nx);
  if (x.low == EndKind::kPeriodic) return {FFTW_R2HC, FFTW_HC2R, 1.0 / nx};
  if (x.low == EndKind::kDirichlet && x.high == EndKind::kDirichlet)
    return {FFTW_RODFT00, FFTW_RODFT00, sine_cosine};
  if (x.low == EndKind::kNeumann && x.high == EndKind::kNeumann)
    return {FFTW_REDFT00, FFTW_REDFT00, sine_cosine};
  if (x.low == EndKind::kDirichlet) return {FFTW_RODFT01, FFTW_RODFT10, sine_cosine};
  return {FFTW_REDFT01, FFTW_REDFT10, sine_cosine};
}

// Generalized eigenvalue of (K1x, Dx) at transform position p.
double ModeEigenvalue(const AxisBoundary& x, int nx, int p) {
  const double pi = std::acos(-1.0);
  double angle;
  if (x.low == EndKind::kPeriodic) {
    angle = 2.0 * pi * p / nx;
  } else if (x.low == EndKind::kDirichlet && x.high == EndKind::kDirichlet) {
    angle = pi * (p + 1) / nx;
  } else if (x.low == EndKind::kNeumann && x.high == EndKind::kNeumann) {
    angle = pi * p / nx;
  } else {
    angle = pi * (2 * p + 1) / (2.0 * nx);
  }
  return 2.0 - 2.0 * std::cos(angle);
}

void CheckAxis(const char* name, int cells, const AxisBoundary& ends) {
  const bool periodic_low = ends.low == EndKind::kPeriodic,
             periodic_high = ends.high == EndKind::kPeriodic;
  if (periodic_low != periodic_high) {
    throw InvalidParameter(std::string("domain.boundary (") + name + ")", "one periodic side",
                           "periodic sides in pairs");
  }
  if (cells < 2) {
    throw InvalidParameter(std::string("grid cells in ") + name, std::to_string(cells), ">= 2");
  }
}

}  // namespace

struct SeparableHelmholtz::Impl {
  Grid grid;
  BoundaryTopology topo;
  double a = 0.0, b = 0.0;
  UnknownLines ux, uy;
  int modes = 0;  // = ux.count, the transform length
  bool cyclic = false;
  bool singular = false;
  Transform transform{};
  std::vector<double> pre_scale;     // per unknown column: 1 / w (Neumann ends of cosine kinds: 2)
  std::vector<double> inv_pivot;     // uy.count x modes
  std::vector<double> upper_factor;  // uy.count x modes: c'_r = upper_r / pivot_r
  std::vector<double> cyclic_z;      // uy.count x modes: A'^-1 u of Sherman-Morrison
  std::vector<double> cyclic_coef;   // per mode: 1 / (1 + v.z), 0 for the pinned mode
  std::vector<double> cyclic_beta_over_gamma;  // per mode: beta / gamma
  std::vector<double*> buffers;                // rows x modes, plus one row of per-mode scratch
  // DD and NN in x: the type-I transforms (their own inverse up to the scale) through a real DFT of
  // the extension (type_one_transform.h); the other kinds: FFTW r2r plans.
  std::unique_ptr<TypeOneTransform> type_one;
  fftw_plan forward = nullptr, backward = nullptr;

  void ApplyTransform(fftw_plan plan, double* buf, int workspace) const;

  void Factorise();
  void Gather(const double* f, const double* x, double* buf) const;
  void SolveModes(double* buf) const;
  void Scatter(const double* buf, double* x) const;
};

void SeparableHelmholtz::Impl::Factorise() {
  const int n = uy.count;
  inv_pivot.assign(std::size_t(n) * modes, 0.0);
  upper_factor.assign(std::size_t(n) * modes, 0.0);
  cyclic_z.assign(cyclic ? std::size_t(n) * modes : 0, 0.0);
  cyclic_coef.assign(cyclic ? modes : 0, 0.0);
  cyclic_beta_over_gamma.assign(cyclic ? modes : 0, 0.0);
  const double h2 = grid.h * grid.h;
  std::vector<double> diag(n), z(n);
  const double off = -b;  // off-diagonal of b K1y, and the corner entries alpha = beta when cyclic
  for (int k = 0; k < modes; ++k) {
    const double shift = a * h2 + b * ModeEigenvalue(topo.x, grid.nx, k);
    for (int r = 0; r < n; ++r) {
      const int j = uy.first + r;
      const bool neumann_end = !cyclic && ((j == 0 && topo.y.low == EndKind::kNeumann) ||
                                           (j == grid.ny && topo.y.high == EndKind::kNeumann));
      diag[r] = neumann_end ? 0.5 * shift + b : shift + 2.0 * b;
    }
    const bool pinned = singular && k == 0;
    const bool sherman_morrison = cyclic && !pinned;
    const double gamma = -diag[0];
    if (sherman_morrison) {
      diag[0] -= gamma;
      diag[n - 1] -= off * off / gamma;
    }
    double previous_upper_factor = 0.0;
    for (int r = 0; r < n; ++r) {
      const double lower = (r > 0 && !(pinned && r == 1)) ? off : 0.0;
      const double upper = (r + 1 < n && !(pinned && r == 0)) ? off : 0.0;
      const double d = (pinned && r == 0) ? 1.0 : diag[r];
      const double pivot = d - lower * previous_upper_factor;
      const std::size_t at = std::size_t(r) * modes + k;
      inv_pivot[at] = 1.0 / pivot;
      upper_factor[at] = upper / pivot;
      previous_upper_factor = upper_factor[at];
    }
    if (sherman_morrison) {
      // z = A'^-1 u, u = (gamma, 0, ..., 0, alpha).
      for (int r = 0; r < n; ++r) {
        const double rhs = (r == 0 ? gamma : 0.0) + (r == n - 1 ? off : 0.0);
        const double prev = r > 0 ? z[r - 1] : 0.0;
        z[r] = (rhs - off * prev) * inv_pivot[std::size_t(r) * modes + k];
      }
      for (int r = n - 2; r >= 0; --r) z[r] -= upper_factor[std::size_t(r) * modes + k] * z[r + 1];
      cyclic_beta_over_gamma[k] = off / gamma;
      const double vz = z[0] + (off / gamma) * z[n - 1];
      cyclic_coef[k] = 1.0 / (1.0 + vz);
      for (int r = 0; r < n; ++r) cyclic_z[std::size_t(r) * modes + k] = z[r];
    }
  }
}

void SeparableHelmholtz::Impl::Gather(const double* f, const double* x, double* buf) const {
  double mean = 0.0;
  if (singular) {
    for (int r = 0; r < uy.count; ++r) {
      const double* row = f + grid.Index(ux.first, uy.first + r);
      for (int c = 0; c < ux.count; ++c) mean += row[c];
    }
    mean /= double(ux.count) * double(uy.count);
  }
  for (int r = 0; r < uy.count; ++r) {
    const int j = uy.first + r;
    const double* row = f + grid.Index(ux.first, j);
    double* out = buf + std::size_t(r) * modes;
    for (int c = 0; c < modes; ++c) out[c] = row[c] - mean;
    // Dirichlet data of the neighbouring columns: -b K_(unknown, Dirichlet) x_D.
    const double wy = LineWeight(topo.y, grid.ny, j);
    if (topo.x.low == EndKind::kDirichlet) out[0] += b * wy * x[grid.Index(0, j)];
    if (topo.x.high == EndKind::kDirichlet) out[modes - 1] += b * wy * x[grid.Index(grid.nx, j)];
  }
  // Dirichlet data of the neighbouring rows.
  if (topo.y.low == EndKind::kDirichlet) {
    double* out = buf;
    for (int c = 0; c < modes; ++c) {
      const int i = ux.first + c;
      out[c] += b * LineWeight(topo.x, grid.nx, i) * x[grid.Index(i, 0)];
    }
  }
  if (topo.y.high == EndKind::kDirichlet) {
    double* out = buf + std::size_t(uy.count - 1) * modes;
    for (int c = 0; c < modes; ++c) {
      const int i = ux.first + c;
      out[c] += b * LineWeight(topo.x, grid.nx, i) * x[grid.Index(i, grid.ny)];
    }
  }
  for (int c = 0; c < modes; ++c) {
    if (pre_scale[c] == 1.0) continue;
    for (int r = 0; r < uy.count; ++r) buf[std::size_t(r) * modes + c] *= pre_scale[c];
  }
}

void SeparableHelmholtz::Impl::SolveModes(double* buf) const {
  const int n = uy.count;
  const double scale = transform.scale;
  if (singular) buf[0] = 0.0;  // the pinned row of the zero mode
  {
    const double* m = inv_pivot.data();
    for (int c = 0; c < modes; ++c) buf[c] = scale * buf[c] * m[c];
  }
  for (int r = 1; r < n; ++r) {
    double* row = buf + std::size_t(r) * modes;
    const double* prev = row - modes;
    const double* m = inv_pivot.data() + std::size_t(r) * modes;
    for (int c = 0; c < modes; ++c) row[c] = (scale * row[c] + b * prev[c]) * m[c];
  }
  for (int r = n - 2; r >= 0; --r) {
    double* row = buf + std::size_t(r) * modes;
    const double* next = row + modes;
    const double* cp = upper_factor.data() + std::size_t(r) * modes;
    for (int c = 0; c < modes; ++c) row[c] -= cp[c] * next[c];
  }
  if (cyclic) {
    // x = y - [(y_0 + (beta/gamma) y_{n-1}) / (1 + v.z)] z; the factor row lies past the n rows.
    double* factor = buf + std::size_t(n) * modes;
    const double* first = buf;
    const double* last = buf + std::size_t(n - 1) * modes;
    for (int c = 0; c < modes; ++c) {
      factor[c] = cyclic_coef[c] * (first[c] + cyclic_beta_over_gamma[c] * last[c]);
    }
    for (int r = 0; r < n; ++r) {
      double* row = buf + std::size_t(r) * modes;
      const double* z = cyclic_z.data() + std::size_t(r) * modes;
      for (int c = 0; c < modes; ++c) row[c] -= factor[c] * z[c];
    }
  }
}

void SeparableHelmholtz::Impl::ApplyTransform(fftw_plan plan, double* buf, int workspace) const {
  if (type_one) {
    type_one->Apply(buf, workspace);
  } else {
    fftw_execute_r2r(plan, buf, buf);
  }
}

void SeparableHelmholtz::Impl::Scatter(const double* buf, double* x) const {
  for (int r = 0; r < uy.count; ++r) {
    double* row = x + grid.Index(ux.first, uy.first + r);
    const double* in = buf + std::size_t(r) * modes;
    for (int c = 0; c < modes; ++c) row[c] = in[c];
  }
  if (singular) {
    double weighted = 0.0, mass = 0.0;
    for (int r = 0; r < uy.count; ++r) {
      const int j = uy.first + r;
      const double wy = LineWeight(topo.y, grid.ny, j);
      const double* row = x + grid.Index(0, j);
      for (int c = 0; c < modes; ++c) {
        const int i = ux.first + c;
        const double w = wy * LineWeight(topo.x, grid.nx, i);
        weighted += w * row[i];
        mass += w;
      }
    }
    const double mean = weighted / mass;
    for (int r = 0; r < uy.count; ++r) {
      double* row = x + grid.Index(ux.first, uy.first + r);
      for (int c = 0; c < modes; ++c) row[c] -= mean;
    }
  }
  if (topo.x.low == EndKind::kPeriodic) {
    for (int j = 0; j <= grid.ny; ++j) x[grid.Index(grid.nx, j)] = x[grid.Index(0, j)];
  }
  if (topo.y.low == EndKind::kPeriodic) {
    for (int i = 0; i <= grid.nx; ++i) x[grid.Index(i, grid.ny)] = x[grid.Index(i, 0)];
  }
}

SeparableHelmholtz::SeparableHelmholtz(const Grid& grid, const BoundaryTopology& topo, double a,
                                       double b, int workspaces)
    : impl_(std::make_unique<Impl>()) {
  CheckAxis("x", grid.nx, topo.x);
  CheckAxis("y", grid.ny, topo.y);
  if (!(a >= 0.0) || !std::isfinite(a))
    throw InvalidParameter("helmholtz a", std::to_string(a), ">= 0");
  if (!(b > 0.0) || !std::isfinite(b))
    throw InvalidParameter("helmholtz b", std::to_string(b), "> 0");
  if (workspaces < 1)
    throw InvalidParameter("helmholtz workspaces", std::to_string(workspaces), ">= 1");
  Impl& s = *impl_;
  s.grid = grid;
  s.topo = topo;
  s.a = a;
  s.b = b;
  s.ux = LinesOf(topo.x, grid.nx);
  s.uy = LinesOf(topo.y, grid.ny);
  s.modes = s.ux.count;
  s.cyclic = topo.y.low == EndKind::kPeriodic;
  s.singular = a == 0.0 && topo.HasNullSpace();
  s.transform = TransformFor(topo.x, grid.nx);
  s.pre_scale.assign(s.modes, 1.0);
  if (topo.x.low == EndKind::kNeumann) s.pre_scale.front() = 2.0;
  if (topo.x.high == EndKind::kNeumann) s.pre_scale.back() = 2.0;
  s.Factorise();

  const std::size_t size = std::size_t(s.modes) * std::size_t(s.uy.count);
  std::lock_guard<std::mutex> lock(PlannerMutex());
  for (int w = 0; w < workspaces; ++w) {
    auto* buffer = static_cast<double*>(fftw_malloc(sizeof(double) * (size + s.modes)));
    if (!buffer) throw std::bad_alloc();
    s.buffers.push_back(buffer);
  }
  if (s.transform.forward == FFTW_RODFT00 || s.transform.forward == FFTW_REDFT00) {
    const auto kind = s.transform.forward == FFTW_RODFT00 ? TypeOneTransform::Kind::kSine
                                                          : TypeOneTransform::Kind::kCosine;
    s.type_one = std::make_unique<TypeOneTransform>(kind, s.modes, s.uy.count, workspaces);
    return;
  }
  const int length = s.modes;
  const unsigned flags = FftwPlannerFlags(size);
  s.forward = fftw_plan_many_r2r(1, &length, s.uy.count, s.buffers[0], nullptr, 1, length,
                                 s.buffers[0], nullptr, 1, length, &s.transform.forward, flags);
  s.backward = fftw_plan_many_r2r(1, &length, s.uy.count, s.buffers[0], nullptr, 1, length,
                                  s.buffers[0], nullptr, 1, length, &s.transform.backward, flags);
  if (!s.forward || !s.backward) throw Error("SeparableHelmholtz: FFTW could not make a plan");
}

SeparableHelmholtz::~SeparableHelmholtz() {
  std::lock_guard<std::mutex> lock(PlannerMutex());
  if (impl_->forward) fftw_destroy_plan(impl_->forward);
  if (impl_->backward) fftw_destroy_plan(impl_->backward);
  impl_->type_one.reset();
  for (double* buffer : impl_->buffers) fftw_free(buffer);
}

void SeparableHelmholtz::Solve(const double* f, double* x, int workspace) const {
  const Impl& s = *impl_;
  if (workspace < 0 || workspace >= static_cast<int>(s.buffers.size())) {
    throw InvalidParameter("helmholtz workspace", std::to_string(workspace),
                           "in [0, " + std::to_string(s.buffers.size()) + ")");
  }
  double* buf = s.buffers[workspace];
  s.Gather(f, x, buf);
  s.ApplyTransform(s.forward, buf, workspace);
  s.SolveModes(buf);
  s.ApplyTransform(s.backward, buf, workspace);
  s.Scatter(buf, x);
}

void SeparableHelmholtz::SolvePair(const double* fu, double* u, const double* fv, double* v) const {
  // num_threads(2) alone would override the caller's budget of 1 thread.
#pragma omp parallel sections num_threads(omp_get_max_threads() >= 2 ? 2 : 1)
  {
#pragma omp section
    Solve(fu, u, 0);
#pragma omp section
    Solve(fv, v, 1);
  }
}

const Grid& SeparableHelmholtz::grid() const { return impl_->grid; }
const BoundaryTopology& SeparableHelmholtz::topology() const { return impl_->topo; }
double SeparableHelmholtz::a() const { return impl_->a; }
double SeparableHelmholtz::b() const { return impl_->b; }

}  // namespace dlmfd
