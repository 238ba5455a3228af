#include "dlmfd/conformation/pointwise_update.h"

#include "dlmfd/core/target_clones.h"

namespace dlmfd {

DLMFD_AVX2_CLONES void OnePanelRow(int count, const OnePanelConstants& k,
                                   const double* __restrict a11, const double* __restrict a12,
                                   const double* __restrict a22, const double* __restrict l11,
                                   const double* __restrict l12, const double* __restrict l21,
                                   const double* __restrict l22, double* __restrict o11,
                                   double* __restrict o12, double* __restrict o22) {
  constexpr double k12 = 1.0 / 12.0, k30 = 1.0 / 30.0, k56 = 1.0 / 56.0, k90 = 1.0 / 90.0;
  constexpr double k6 = 1.0 / 6.0, k20 = 1.0 / 20.0, k42 = 1.0 / 42.0, k72 = 1.0 / 72.0,
                   k110 = 1.0 / 110.0;
  const double half_dt = 0.5 * k.dt, delta = kGaussOffset * k.dt;
  for (int i = 0; i < count; ++i) {
    const double ht = 0.5 * (l11[i] + l22[i]);
    const double d = l11[i] - ht;
    const double q2 = d * d + l12[i] * l21[i];
    const double xh = q2 * half_dt * half_dt, xd = q2 * delta * delta;
    const double c_h =
        1.0 + xh * 0.5 * (1.0 + xh * k12 * (1.0 + xh * k30 * (1.0 + xh * k56 * (1.0 + xh * k90))));
    const double s_h =
        half_dt *
        (1.0 +
         xh * k6 * (1.0 + xh * k20 * (1.0 + xh * k42 * (1.0 + xh * k72 * (1.0 + xh * k110)))));
    const double c_d =
        1.0 + xd * 0.5 * (1.0 + xd * k12 * (1.0 + xd * k30 * (1.0 + xd * k56 * (1.0 + xd * k90))));
    const double s_d =
        delta *
        (1.0 +
         xd * k6 * (1.0 + xd * k20 * (1.0 + xd * k42 * (1.0 + xd * k72 * (1.0 + xd * k110)))));
    const double e_h = ExpPolynomial(half_dt * ht);
    const double g2 = ExpPolynomial(2.0 * delta * ht), g2_inv = ExpPolynomial(-2.0 * delta * ht);
    const Mat2 e{e_h * (c_h + s_h * d), e_h * s_h * l12[i], e_h * s_h * l21[i],
                 e_h * (c_h - s_h * d)};
    const double plus = k.w1 * g2_inv + k.w3 * g2, minus = k.w3 * g2 - k.w1 * g2_inv;
    const double cc = c_d * c_d, ss = s_d * s_d, cs = minus * c_d * s_d;
    const SymTensor inner = Congruence(e, SymTensor{a11[i], a12[i], a22[i]});
    const SymTensor middle{
        k.decay * inner.a11 + plus * (cc + ss * (d * d + l12[i] * l12[i])) + cs * 2.0 * d + k.w2,
        k.decay * inner.a12 + plus * ss * d * (l21[i] - l12[i]) + cs * (l12[i] + l21[i]),
        k.decay * inner.a22 + plus * (cc + ss * (d * d + l21[i] * l21[i])) - cs * 2.0 * d + k.w2};
    const SymTensor out = Congruence(e, middle);
    o11[i] = out.a11;
    o12[i] = out.a12;
    o22[i] = out.a22;
  }
}

}  // namespace dlmfd
