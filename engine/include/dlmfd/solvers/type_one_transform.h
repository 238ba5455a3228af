// Batched type-I sine and cosine transforms (FFTW's RODFT00 and REDFT00, the same definitions and
// scale) computed through a real-to-complex DFT of the odd or even extension of each row:
//   DST-I, n points:  e = (0, X_0, ..., X_{n-1}, 0, -X_{n-1}, ..., -X_0), L = 2(n + 1),
//                     Y_k = 2 sum_j X_j sin(pi (j+1)(k+1) / (n+1)) = -Im E_{k+1};
//   DCT-I, n points:  e = (X_0, ..., X_{n-1}, X_{n-2}, ..., X_1), L = 2(n - 1),
//                     Y_k = X_0 + (-1)^k X_{n-1} + 2 sum_{j=1}^{n-2} X_j cos(pi j k / (n-1)) = Re
//                     E_k,
// with E = DFT(e). Why: FFTW 3.3 computes RODFT00/REDFT00 by padding to the same length-L real DFT
// in its halfcomplex form plus copies, which on the paper's grid (n = 191 velocity, n = 97 pressure
// columns) takes about twice as long as the SIMD r2c codelets on the same extension
// (docs/evidence/performance.md, "Fast solves"). The extension is exact algebra, so accuracy is
// that of the FFT; tests/unit/type_one_transform_test.cc compares with FFTW's r2r on random rows.
//
// Apply transforms `rows` contiguous rows of `length` values in place, in blocks of kBlockRows rows
// whose extension and spectrum (about 100 KB) stay in the core's L2 cache: extending whole arrays
// (2.4 MB each on the paper's grid) made the stores of the extension the most expensive part.
// ApplyBlock transforms one of those blocks, so that a caller can share the blocks between threads
// (SeparableHelmholtz does); the blocks are the same whatever the thread count, so every row gets
// the same bits. Plans are made at construction, which must hold the FFTW planner lock (it is not
// thread-safe); Apply and ApplyBlock may run concurrently on distinct workspaces (each its own
// extension and spectrum buffers) and allocate nothing.
#pragma once

#include <vector>

namespace dlmfd {

class TypeOneTransform {
 public:
  enum class Kind { kSine, kCosine };  // DST-I (RODFT00), DCT-I (REDFT00)

  TypeOneTransform(Kind kind, int length, int rows, int workspaces);
  ~TypeOneTransform();
  TypeOneTransform(const TypeOneTransform&) = delete;
  TypeOneTransform& operator=(const TypeOneTransform&) = delete;

  static constexpr int kBlockRows = 16;

  // All rows, block after block, on the workspace's buffers.
  void Apply(double* data, int workspace) const;
  // The rows of block b in [0, Blocks()) (rows b kBlockRows onwards) of the rows starting at data.
  void ApplyBlock(double* data, int block, int workspace) const;
  int Blocks() const { return (rows_ + kBlockRows - 1) / kBlockRows; }

 private:
  void TransformRows(double* data, int block_rows, void* plan, double* ext, double* spectrum) const;
  void Release();  // plans and buffers (destructor, and a constructor that throws)

  Kind kind_;
  int length_, rows_, extended_, spectrum_;  // n, rows, L, L/2 + 1
  std::vector<double*> extension_;           // per workspace: kBlockRows x L
  std::vector<double*> spectrum_buffers_;    // per workspace: kBlockRows x (L/2 + 1) complex
  void* block_plan_ = nullptr;               // fftw_plan of kBlockRows rows (workspace 0's buffers)
  void* tail_plan_ = nullptr;                // of rows % kBlockRows rows, when not 0
};

}  // namespace dlmfd
