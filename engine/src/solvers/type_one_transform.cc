#include "dlmfd/solvers/type_one_transform.h"

#include <fftw3.h>

#include <algorithm>
#include <new>
#include <string>

#include "dlmfd/core/errors.h"
#include "dlmfd/solvers/fft_planning.h"

namespace dlmfd {

TypeOneTransform::TypeOneTransform(Kind kind, int length, int rows, int workspaces)
    : kind_(kind),
      length_(length),
      rows_(rows) {
  const int shortest = kind == Kind::kSine ? 1 : 2;
  if (length < shortest) {
    throw InvalidParameter("type-I transform length", std::to_string(length),
                           ">= " + std::to_string(shortest));
  }
  if (rows < 1) throw InvalidParameter("type-I transform rows", std::to_string(rows), ">= 1");
  extended_ = kind == Kind::kSine ? 2 * (length + 1) : 2 * (length - 1);
  spectrum_ = extended_ / 2 + 1;
  const int block = std::min(rows, kBlockRows);
  try {
    for (int w = 0; w < workspaces; ++w) {
      extension_.push_back(
          static_cast<double*>(fftw_malloc(sizeof(double) * std::size_t(extended_) * block)));
      spectrum_buffers_.push_back(
          static_cast<double*>(fftw_malloc(sizeof(fftw_complex) * std::size_t(spectrum_) * block)));
      if (!extension_.back() || !spectrum_buffers_.back()) throw std::bad_alloc();
    }
    // Every workspace's buffers come from fftw_malloc, so they share the planned arrays' alignment
    // (the condition of fftw_execute_dft_r2c on other arrays).
    auto plan = [&](int howmany) -> void* {
      if (howmany == 0) return nullptr;
      const unsigned flags = FftwPlannerFlags(std::size_t(extended_) * howmany);
      fftw_plan p = fftw_plan_many_dft_r2c(
          1, &extended_, howmany, extension_[0], nullptr, 1, extended_,
          reinterpret_cast<fftw_complex*>(spectrum_buffers_[0]), nullptr, 1, spectrum_, flags);
      if (!p) throw Error("TypeOneTransform: FFTW could not make a plan");
      return p;
    };
    block_plan_ = plan(block);
    tail_plan_ = plan(rows % block);
  } catch (...) {
    Release();
    throw;
  }
}

TypeOneTransform::~TypeOneTransform() { Release(); }

void TypeOneTransform::Release() {
  for (void* p : {block_plan_, tail_plan_}) {
    if (p) fftw_destroy_plan(static_cast<fftw_plan>(p));
  }
  block_plan_ = tail_plan_ = nullptr;
  for (double* e : extension_) fftw_free(e);  // fftw_free(nullptr) is a no-op
  for (double* s : spectrum_buffers_) fftw_free(s);
  extension_.clear();
  spectrum_buffers_.clear();
}

void TypeOneTransform::TransformRows(double* data, int block_rows, void* plan, double* ext,
                                     double* spectrum_data) const {
  const int n = length_, L = extended_;
  for (int r = 0; r < block_rows; ++r) {
    const double* in = data + std::size_t(r) * n;
    double* e = ext + std::size_t(r) * L;
    if (kind_ == Kind::kSine) {
      e[0] = 0.0;
      e[n + 1] = 0.0;
      for (int j = 0; j < n; ++j) e[1 + j] = in[j];
      for (int j = 0; j < n; ++j) e[L - 1 - j] = -in[j];
    } else {
      for (int j = 0; j < n; ++j) e[j] = in[j];
      for (int j = 1; j + 1 < n; ++j) e[L - j] = in[j];
    }
  }
  auto* spectrum = reinterpret_cast<fftw_complex*>(spectrum_data);
  fftw_execute_dft_r2c(static_cast<fftw_plan>(plan), ext, spectrum);
  for (int r = 0; r < block_rows; ++r) {
    const fftw_complex* s = spectrum + std::size_t(r) * spectrum_;
    double* out = data + std::size_t(r) * n;
    if (kind_ == Kind::kSine) {
      for (int k = 0; k < n; ++k) out[k] = -s[k + 1][1];
    } else {
      for (int k = 0; k < n; ++k) out[k] = s[k][0];
    }
  }
}

void TypeOneTransform::ApplyBlock(double* data, int block, int workspace) const {
  const int first = block * kBlockRows;
  const int count = std::min(kBlockRows, rows_ - first);
  // A full block has the block plan; only the last block can be shorter (its own plan).
  void* plan = count == std::min(rows_, kBlockRows) ? block_plan_ : tail_plan_;
  TransformRows(data + std::size_t(first) * length_, count, plan, extension_[workspace],
                spectrum_buffers_[workspace]);
}

void TypeOneTransform::Apply(double* data, int workspace) const {
  for (int b = 0; b < Blocks(); ++b) ApplyBlock(data, b, workspace);
}

}  // namespace dlmfd
