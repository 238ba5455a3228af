#include "dlmfd/conformation/inflow_state.h"

#include <array>
#include <cmath>
#include <sstream>
#include <string>

#include "dlmfd/conformation/model_pointwise_update.h"
#include "dlmfd/conformation/oldroyd_b_relaxation.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/core/number_text.h"

namespace dlmfd {

SymTensor SteadyConformation(const Mat2& l, double lambda) {
  const double c = 1.0 / lambda;
  // Rows of the 3x3 system M (A11, A12, A22) = (c, 0, c).
  const double m[3][3] = {{c - 2.0 * l.m11, -2.0 * l.m12, 0.0},
                          {-l.m21, c - l.m11 - l.m22, -l.m12},
                          {0.0, -2.0 * l.m21, c - 2.0 * l.m22}};
  const std::array<double, 3> x = SolveThreeByThree(m, {c, 0.0, c});
  const SymTensor a{x[0], x[1], x[2]};
  // The steady state exists (and attracts) iff every eigenvalue of L - I/(2 lambda) has a negative
  // real part; then it is SPD. Otherwise no fully developed state exists.
  const double half_trace = 0.5 * (l.m11 + l.m22);
  const double d = l.m11 - half_trace;
  const double q2 = d * d + l.m12 * l.m21;
  const double max_real_eig = half_trace + (q2 > 0.0 ? std::sqrt(q2) : 0.0);
  if (!(2.0 * lambda * max_real_eig < 1.0) || !IsFinite(a) || !(MinEigenvalue(a) > 0.0)) {
    std::ostringstream value;
    value << "lambda max Re eig(L) = " << lambda * max_real_eig;
    throw InvalidParameter(
        "fluid.relaxation_time", value.str(),
        "2 lambda max Re eig(L) < 1 at an inflow boundary (no steady Oldroyd-B state)");
  }
  return a;
}

SymTensor SimpleShearConformation(double lambda, double shear_rate) {
  const double wi = lambda * shear_rate;
  return SymTensor{1.0 + 2.0 * wi * wi, wi, 1.0};
}

bool InflowGradient(const Grid& grid, const DomainParams& domain, Side side, int k, Mat2* l) {
  *l = Mat2{};
  const BoundarySide& b = domain.side(side);
  if (b.type != SideType::kVelocity || b.profile != Profile::kPoiseuille) return false;
  const bool vertical = (side == Side::kLeft || side == Side::kRight);
  const double length = vertical ? grid.Height() : grid.Width();
  const double s = k * grid.h;
  const double dphi_ds = 4.0 * (length - 2.0 * s) / (length * length);
  // L = max (dphi/ds) e_s^T: the velocity varies along the side only.
  if (vertical) {
    l->m12 = b.max.x() * dphi_ds;
    l->m22 = b.max.y() * dphi_ds;
  } else {
    l->m11 = b.max.x() * dphi_ds;
    l->m21 = b.max.y() * dphi_ds;
  }
  return true;
}

SymTensor InflowConformation(const Grid& grid, const DomainParams& domain, Side side, int k,
                             double lambda) {
  Mat2 l;
  if (!InflowGradient(grid, domain, side, k, &l)) return SymTensor{};
  return SteadyConformation(l, lambda);
}

SymTensor InflowConformation(const Grid& grid, const DomainParams& domain, Side side, int k,
                             double lambda, const RelaxationModel& model) {
  if (dynamic_cast<const OldroydBRelaxation*>(&model) != nullptr) {
    return InflowConformation(grid, domain, side, k, lambda);
  }
  Mat2 l;
  if (!InflowGradient(grid, domain, side, k, &l)) return SymTensor{};
  return SteadyModelConformation(model, l, lambda);
}

void ValidateInflowStates(const Params& params, const Grid& grid) {
  if (params.fluid.IsNewtonian()) return;  // no conformation, no inflow state
  const double lambda = params.fluid.relaxation_time;
  const std::unique_ptr<RelaxationModel> model = MakeRelaxationModel(params.fluid);
  const char* names[4] = {"left", "right", "bottom", "top"};
  for (int s = 0; s < 4; ++s) {
    const Side side = static_cast<Side>(s);
    if (params.domain.side(side).type != SideType::kVelocity) continue;
    const int nodes = (side == Side::kLeft || side == Side::kRight ? grid.ny : grid.nx) + 1;
    for (int k = 0; k < nodes; ++k) {
      try {
        InflowConformation(grid, params.domain, side, k, lambda, *model);
      } catch (const InvalidParameter& e) {
        throw InvalidParameter(
            e.key(), ExactText(lambda),
            e.allowed() + ": here " + e.value() + " at node " + std::to_string(k) +
                " of domain.boundary." + names[s] +
                " (a smaller lambda, or a smaller component of its max along the side)");
      }
    }
  }
}

}  // namespace dlmfd
