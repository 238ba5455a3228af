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
//
// Threads (issue 34): a solve, or a batch of them (SolvePair), is one OpenMP region of three
// phases, each shared by the whole team: (1) blocks of kBlockRows rows gathered and transformed
// forward (rows are independent), (2) the tridiagonal sweeps in y on pieces of the modes (modes are
// independent), (3) blocks transformed back and scattered. The singular case adds the sums of its
// two means, taken per row and then over the rows in order. The blocks are the same and every mode
// and row sees the same operations whatever the team, so the result does not depend on the thread
// count, bit for bit (tests/unit/separable_helmholtz_test.cc).
#include "dlmfd/solvers/separable_helmholtz.h"

#include <fftw3.h>
#include <omp.h>

#include <algorithm>
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

// Rows per block of phases (1) and (3): a block's rows and the transform's scratch stay in L2.
constexpr int kBlockRows = TypeOneTransform::kBlockRows;
// The sweeps' mode pieces start on multiples of 8 modes (a cache line of doubles). A row of the
// buffer is `modes` long, so the threads still share one line a row where `modes` is not a
// multiple of 8; padding the rows to whole lines was measured and gained nothing (the pressure
// solve on two threads, docs/evidence/performance.md, "What this machine gives a second thread").
constexpr int kModeAlign = 8;

}  // namespace

struct SeparableHelmholtz::Impl {
  Grid grid;
  BoundaryTopology topo;
  double a = 0.0, b = 0.0;
  UnknownLines ux, uy;
  int modes = 0;   // = ux.count, the transform length
  int blocks = 0;  // row blocks of kBlockRows rows (the last may be shorter)
  bool cyclic = false;
  bool singular = false;
  Transform transform{};
  std::vector<double> pre_scale;     // per unknown column: 1 / w (Neumann ends of cosine kinds: 2)
  std::vector<double> inv_pivot;     // uy.count x modes
  std::vector<double> upper_factor;  // uy.count x modes: c'_r = upper_r / pivot_r
  std::vector<double> cyclic_z;      // uy.count x modes: A'^-1 u of Sherman-Morrison
  std::vector<double> cyclic_coef;   // per mode: 1 / (1 + v.z), 0 for the pinned mode
  std::vector<double> cyclic_beta_over_gamma;  // per mode: beta / gamma
  std::vector<double*> buffers;  // per system of a batch: rows x modes, plus one row of scratch
  int teams = 1;                 // the most threads a solve uses: one transform scratch each
  double unknown_weight = 0.0;   // singular: sum of the trapezoid weights of the unknown nodes
  std::vector<double> row_sums;  // singular: per system and row, the partial sums of the means
  // DD and NN in x: the type-I transforms (their own inverse up to the scale) through a real DFT of
  // the extension (type_one_transform.h); the other kinds: FFTW r2r plans of a full block and of
  // the last, shorter one.
  std::unique_ptr<TypeOneTransform> type_one;
  fftw_plan forward = nullptr, backward = nullptr, forward_tail = nullptr, backward_tail = nullptr;

  void Factorise();
  void TransformBlock(bool forward_direction, double* buf, int block, int thread) const;
  double RowSum(const double* f, int r) const;
  void GatherRow(const double* f, const double* x, double mean, double* buf, int r) const;
  void SolveModes(double* buf, int first, int last) const;
  double ScatterRow(const double* buf, double* x, int r) const;
  void FinishRow(double* x, double mean, int r) const;
  void SolveBatch(int count, const double* const* f, double* const* x);
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

void SeparableHelmholtz::Impl::TransformBlock(bool forward_direction, double* buf, int block,
                                              int thread) const {
  if (type_one) {
    type_one->ApplyBlock(buf, block, thread);
    return;
  }
  const bool tail = block == blocks - 1 && uy.count % kBlockRows != 0 && uy.count > kBlockRows;
  fftw_plan plan =
      forward_direction ? (tail ? forward_tail : forward) : (tail ? backward_tail : backward);
  double* rows = buf + std::size_t(block) * kBlockRows * modes;
  fftw_execute_r2r(plan, rows, rows);
}

// The sum of f over the unknown nodes of row r (the singular case's mean, summed per row).
double SeparableHelmholtz::Impl::RowSum(const double* f, int r) const {
  const double* row = f + grid.Index(ux.first, uy.first + r);
  double sum = 0.0;
  for (int c = 0; c < ux.count; ++c) sum += row[c];
  return sum;
}

// Row r of the transform buffer: f - mean at the unknowns, the Dirichlet data of the neighbouring
// columns and rows (-b K_(unknown, Dirichlet) x_D), the pre-scale of the cosine kinds' ends.
void SeparableHelmholtz::Impl::GatherRow(const double* f, const double* x, double mean, double* buf,
                                         int r) const {
  const int j = uy.first + r;
  const double* row = f + grid.Index(ux.first, j);
  double* out = buf + std::size_t(r) * modes;
  for (int c = 0; c < modes; ++c) out[c] = row[c] - mean;
  const double wy = LineWeight(topo.y, grid.ny, j);
  if (topo.x.low == EndKind::kDirichlet) out[0] += b * wy * x[grid.Index(0, j)];
  if (topo.x.high == EndKind::kDirichlet) out[modes - 1] += b * wy * x[grid.Index(grid.nx, j)];
  const bool below = r == 0 && topo.y.low == EndKind::kDirichlet;
  const bool above = r == uy.count - 1 && topo.y.high == EndKind::kDirichlet;
  for (const int data_row : {below ? 0 : -1, above ? grid.ny : -1}) {
    if (data_row < 0) continue;
    for (int c = 0; c < modes; ++c) {
      const int i = ux.first + c;
      out[c] += b * LineWeight(topo.x, grid.nx, i) * x[grid.Index(i, data_row)];
    }
  }
  for (int c = 0; c < modes; ++c) out[c] *= pre_scale[c];
}

// The tridiagonal solves in y of modes [first, last).
void SeparableHelmholtz::Impl::SolveModes(double* buf, int first, int last) const {
  const int n = uy.count;
  const double scale = transform.scale;
  if (singular && first == 0) buf[0] = 0.0;  // the pinned row of the zero mode
  {
    const double* m = inv_pivot.data();
    for (int c = first; c < last; ++c) buf[c] = scale * buf[c] * m[c];
  }
  for (int r = 1; r < n; ++r) {
    double* row = buf + std::size_t(r) * modes;
    const double* prev = row - modes;
    const double* m = inv_pivot.data() + std::size_t(r) * modes;
    for (int c = first; c < last; ++c) row[c] = (scale * row[c] + b * prev[c]) * m[c];
  }
  for (int r = n - 2; r >= 0; --r) {
    double* row = buf + std::size_t(r) * modes;
    const double* next = row + modes;
    const double* cp = upper_factor.data() + std::size_t(r) * modes;
    for (int c = first; c < last; ++c) row[c] -= cp[c] * next[c];
  }
  if (cyclic) {
    // x = y - [(y_0 + (beta/gamma) y_{n-1}) / (1 + v.z)] z; the factor row lies past the n rows.
    double* factor = buf + std::size_t(n) * modes;
    const double* top = buf;
    const double* bottom = buf + std::size_t(n - 1) * modes;
    for (int c = first; c < last; ++c) {
      factor[c] = cyclic_coef[c] * (top[c] + cyclic_beta_over_gamma[c] * bottom[c]);
    }
    for (int r = 0; r < n; ++r) {
      double* row = buf + std::size_t(r) * modes;
      const double* z = cyclic_z.data() + std::size_t(r) * modes;
      for (int c = first; c < last; ++c) row[c] -= factor[c] * z[c];
    }
  }
}

// Writes row r of the unknowns; returns its trapezoid-weighted sum in the singular case (0 else).
double SeparableHelmholtz::Impl::ScatterRow(const double* buf, double* x, int r) const {
  const int j = uy.first + r;
  double* row = x + grid.Index(ux.first, j);
  const double* in = buf + std::size_t(r) * modes;
  for (int c = 0; c < modes; ++c) row[c] = in[c];
  if (!singular) return 0.0;
  const double wy = LineWeight(topo.y, grid.ny, j);
  double weighted = 0.0;
  for (int c = 0; c < modes; ++c)
    weighted += wy * LineWeight(topo.x, grid.nx, ux.first + c) * row[c];
  return weighted;
}

// Row r less the mean (singular case), and the periodic duplicates it owns: with a periodic x the
// last node of its row (the first and last unknown rows also those of the Dirichlet rows beyond
// them), with a periodic y the duplicate row ny when r is row 0 (row 0 alone writes row ny, so
// that no two threads write one node).
void SeparableHelmholtz::Impl::FinishRow(double* x, double mean, int r) const {
  const int j = uy.first + r;
  if (singular) {
    double* row = x + grid.Index(ux.first, j);
    for (int c = 0; c < modes; ++c) row[c] -= mean;
  }
  if (topo.x.low == EndKind::kPeriodic) {
    const int low = r == 0 ? 0 : j;
    const int high = r == uy.count - 1 && !cyclic ? grid.ny : j;
    for (int jj = low; jj <= high; ++jj) x[grid.Index(grid.nx, jj)] = x[grid.Index(0, jj)];
  }
  if (topo.y.low == EndKind::kPeriodic && j == 0) {
    std::copy_n(x + grid.Index(0, 0), grid.NodesX(), x + grid.Index(0, grid.ny));
  }
}

void SeparableHelmholtz::Impl::SolveBatch(int count, const double* const* f, double* const* x) {
  const int rows = uy.count;
  const int team = std::max(1, std::min(omp_get_max_threads(), teams));
  // Mode pieces per system: enough for the team, each at least kModeAlign modes wide.
  const int pieces =
      std::max(1, std::min((team + count - 1) / count, std::max(1, modes / kModeAlign)));
  auto piece_start = [&](int k) {
    if (k >= pieces) return modes;
    const int at = static_cast<int>((long(modes) * k) / pieces);
    return std::min(modes, (at / kModeAlign) * kModeAlign);
  };
  double* sums = row_sums.data();
#pragma omp parallel num_threads(team)
  {
    const int thread = omp_get_thread_num();
    double means[2] = {0.0, 0.0};  // per system (at most 2), the same in every thread
    if (singular) {
#pragma omp for schedule(static)
      for (long item = 0; item < long(count) * rows; ++item) {
        sums[item] = RowSum(f[item / rows], static_cast<int>(item % rows));
      }
      for (int s = 0; s < count; ++s) {
        double sum = 0.0;
        for (int r = 0; r < rows; ++r) sum += sums[std::size_t(s) * rows + r];
        means[s] = sum / (double(ux.count) * double(rows));
      }
    }
#pragma omp for schedule(static)
    for (int item = 0; item < count * blocks; ++item) {
      const int s = item / blocks, block = item % blocks;
      const int last = std::min(rows, (block + 1) * kBlockRows);
      for (int r = block * kBlockRows; r < last; ++r)
        GatherRow(f[s], x[s], means[s], buffers[s], r);
      TransformBlock(true, buffers[s], block, thread);
    }
#pragma omp for schedule(static)
    for (int item = 0; item < count * pieces; ++item) {
      const int s = item / pieces, k = item % pieces;
      SolveModes(buffers[s], piece_start(k), piece_start(k + 1));
    }
#pragma omp for schedule(static)
    for (int item = 0; item < count * blocks; ++item) {
      const int s = item / blocks, block = item % blocks;
      TransformBlock(false, buffers[s], block, thread);
      const int last = std::min(rows, (block + 1) * kBlockRows);
      for (int r = block * kBlockRows; r < last; ++r) {
        const double weighted = ScatterRow(buffers[s], x[s], r);
        if (singular) {
          sums[std::size_t(s) * rows + r] = weighted;
        } else {
          FinishRow(x[s], 0.0, r);
        }
      }
    }
    if (singular) {  // (the loop's closing barrier: every row's sum is in)
      for (int s = 0; s < count; ++s) {
        double weighted = 0.0;
        for (int r = 0; r < rows; ++r) weighted += sums[std::size_t(s) * rows + r];
        means[s] = weighted / unknown_weight;
      }
#pragma omp for schedule(static)
      for (long item = 0; item < long(count) * rows; ++item) {
        const int s = static_cast<int>(item / rows);
        FinishRow(x[s], means[s], static_cast<int>(item % rows));
      }
    }
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
  if (workspaces < 1 || workspaces > 2)
    throw InvalidParameter("helmholtz workspaces", std::to_string(workspaces), "1 or 2");
  Impl& s = *impl_;
  s.grid = grid;
  s.topo = topo;
  s.a = a;
  s.b = b;
  s.ux = LinesOf(topo.x, grid.nx);
  s.uy = LinesOf(topo.y, grid.ny);
  s.modes = s.ux.count;
  s.blocks = (s.uy.count + kBlockRows - 1) / kBlockRows;
  s.cyclic = topo.y.low == EndKind::kPeriodic;
  s.singular = a == 0.0 && topo.HasNullSpace();
  s.transform = TransformFor(topo.x, grid.nx);
  s.pre_scale.assign(s.modes, 1.0);
  if (topo.x.low == EndKind::kNeumann) s.pre_scale.front() = 2.0;
  if (topo.x.high == EndKind::kNeumann) s.pre_scale.back() = 2.0;
  s.Factorise();
  s.teams = std::max(1, omp_get_max_threads());
  if (s.singular) {
    s.row_sums.assign(std::size_t(workspaces) * s.uy.count, 0.0);
    for (int r = 0; r < s.uy.count; ++r) {
      const double wy = LineWeight(topo.y, grid.ny, s.uy.first + r);
      for (int c = 0; c < s.modes; ++c) {
        s.unknown_weight += wy * LineWeight(topo.x, grid.nx, s.ux.first + c);
      }
    }
  }

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
    s.type_one = std::make_unique<TypeOneTransform>(kind, s.modes, s.uy.count, s.teams);
    return;
  }
  // Plans of one block of rows, executed on every block (each starts kBlockRows rows further: the
  // same alignment as the buffer's start), and of the last block when it is shorter.
  const int length = s.modes;
  auto plan = [&](int howmany, fftw_r2r_kind kind) -> fftw_plan {
    if (howmany == 0) return nullptr;
    const unsigned flags = FftwPlannerFlags(std::size_t(length) * howmany);
    fftw_plan p = fftw_plan_many_r2r(1, &length, howmany, s.buffers[0], nullptr, 1, length,
                                     s.buffers[0], nullptr, 1, length, &kind, flags);
    if (!p) throw Error("SeparableHelmholtz: FFTW could not make a plan");
    return p;
  };
  const int block = std::min(s.uy.count, kBlockRows);
  const int tail = s.uy.count > kBlockRows ? s.uy.count % kBlockRows : 0;
  s.forward = plan(block, s.transform.forward);
  s.backward = plan(block, s.transform.backward);
  s.forward_tail = plan(tail, s.transform.forward);
  s.backward_tail = plan(tail, s.transform.backward);
}

SeparableHelmholtz::~SeparableHelmholtz() {
  std::lock_guard<std::mutex> lock(PlannerMutex());
  for (fftw_plan p : {impl_->forward, impl_->backward, impl_->forward_tail, impl_->backward_tail}) {
    if (p) fftw_destroy_plan(p);
  }
  impl_->type_one.reset();
  for (double* buffer : impl_->buffers) fftw_free(buffer);
}

void SeparableHelmholtz::Solve(const double* f, double* x) const { impl_->SolveBatch(1, &f, &x); }

void SeparableHelmholtz::SolvePair(const double* fu, double* u, const double* fv, double* v) const {
  if (impl_->buffers.size() < 2) {
    throw InvalidParameter("helmholtz workspaces", "1", "2 for SolvePair");
  }
  const double* f[2] = {fu, fv};
  double* x[2] = {u, v};
  impl_->SolveBatch(2, f, x);
}

const Grid& SeparableHelmholtz::grid() const { return impl_->grid; }
const BoundaryTopology& SeparableHelmholtz::topology() const { return impl_->topo; }
double SeparableHelmholtz::a() const { return impl_->a; }
double SeparableHelmholtz::b() const { return impl_->b; }

}  // namespace dlmfd
