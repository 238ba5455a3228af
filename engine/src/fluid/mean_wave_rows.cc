#include "mean_wave_rows.h"

#include "dlmfd/core/target_clones.h"

namespace dlmfd::wave_rows {
namespace {

// The loops proper: every pointer a parameter of its own, __restrict, so that no store can alias a
// load (the vectoriser needs no run-time overlap checks).
DLMFD_AVX2_CLONES void MatrixLoop(int cells, const double* __restrict x0,
                                  const double* __restrict x1, const double* __restrict y0,
                                  const double* __restrict y1, double* __restrict bb,
                                  double* __restrict bc, double* __restrict bd,
                                  double* __restrict cc, double* __restrict cd,
                                  double* __restrict dd) {
  for (int ci = 0; ci < cells; ++ci) {
    const CellCorners k(x0[ci], x0[ci + 1], x1[ci + 1], x1[ci], y0[ci], y0[ci + 1], y1[ci + 1],
                        y1[ci]);
    double a1, b1, c1, a2, b2, c2, a3, b3, c3, a4, b4, c4;
    k.Triangle(0, 1, 2, a1, b1, c1);  // T1
    k.Triangle(0, 2, 3, a2, b2, c2);  // T2
    k.Triangle(0, 1, 3, a3, b3, c3);  // T3
    k.Triangle(1, 2, 3, a4, b4, c4);  // T4
    bb[ci] = 0.5 * (a1 + a3 - 2.0 * b1 + c1 + c4);
    bc[ci] = 0.5 * (b1 - b4 - c1 - c4);
    bd[ci] = 0.5 * (b3 + b4);
    cc[ci] = 0.5 * (a2 + a4 + 2.0 * b4 + c1 + c4);
    cd[ci] = -0.5 * (a2 + a4 - b2 + b4);
    dd[ci] = 0.5 * (a2 + a4 - 2.0 * b2 + c2 + c3);
  }
}

DLMFD_AVX2_CLONES void SharesLoop(int cells, const double* __restrict bb,
                                  const double* __restrict bc, const double* __restrict bd,
                                  const double* __restrict cc, const double* __restrict cd,
                                  const double* __restrict dd, const double* __restrict f0,
                                  const double* __restrict f1, double* __restrict sa,
                                  double* __restrict sb, double* __restrict sc,
                                  double* __restrict sd) {
  for (int ci = 0; ci < cells; ++ci) {
    const double fa = f0[ci];
    const double eb = f0[ci + 1] - fa, ec = f1[ci + 1] - fa, ed = f1[ci] - fa;
    const double b = bb[ci] * eb + bc[ci] * ec + bd[ci] * ed;
    const double c = bc[ci] * eb + cc[ci] * ec + cd[ci] * ed;
    const double d = bd[ci] * eb + cd[ci] * ec + dd[ci] * ed;
    sa[ci] = -(b + c + d);
    sb[ci] = b;
    sc[ci] = c;
    sd[ci] = d;
  }
}

DLMFD_AVX2_CLONES void GatherLoop(int nodes, const double* __restrict a, const double* __restrict b,
                                  const double* __restrict c, const double* __restrict d,
                                  double* __restrict out) {
  for (int i = 0; i < nodes; ++i) out[i] = a[i] + b[i] + c[i] + d[i];
}

}  // namespace

void CellMatrixRow(int cells, const double* x0, const double* x1, const double* y0,
                   const double* y1, double* const out[6]) {
  MatrixLoop(cells, x0, x1, y0, y1, out[0], out[1], out[2], out[3], out[4], out[5]);
}

void CellSharesRow(int cells, const double* const m[6], const double* f0, const double* f1,
                   double* const share[4]) {
  SharesLoop(cells, m[0], m[1], m[2], m[3], m[4], m[5], f0, f1, share[0], share[1], share[2],
             share[3]);
}

void GatherRow(int nodes, const double* a, const double* b, const double* c, const double* d,
               double* out) {
  GatherLoop(nodes, a, b, c, d, out);
}

}  // namespace dlmfd::wave_rows
