// Step (34) of the paper, u^{n+1/4} -> u^{n+2/4}: the advection-diffusion substep of the
// Marchuk-Yanenko scheme, behind one interface so that the scheme is chosen once per run
// (splitting.advection) and the time loop holds one object:
//   least_squares: the paper's least-squares CG (advection_least_squares.h);
//   wave:          the explicit wave-like scheme of Dean and Glowinski (advection_wave.h).
// Each scheme names its own columns of the step report: advection_iterations and
// advection_residual (least squares), wave_substeps (wave); diagnostics.csv prints them.
#pragma once

#include <memory>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"
#include "dlmfd/fluid/advection_report.h"
#include "dlmfd/fluid/boundary_data.h"

namespace dlmfd {

// kappa of the steady-state correction of both schemes (splitting.steady_correction): the share of
// the implicit viscosity that the removed streamline diffusion may reach at a node.
inline constexpr double kTaylorViscosityShare = 0.5;

// kappa nu_N, the cap of the removed diffusion, with the correction; 0 without it. nu_N is the
// viscosity the fluid steps treat implicitly on the velocity mesh of size h
// (FluidParams::ImplicitViscosity).
inline double SteadyCorrectionCap(SteadyCorrection correction, const FluidParams& fluid, double h) {
  return correction == SteadyCorrection::kTaylor
             ? kTaylorViscosityShare * fluid.ImplicitViscosity(h) / fluid.density
             : 0.0;
}

// theta = min(1, cap / streamline): the share of a node's streamline diffusion that is removed.
inline double SteadyCorrectionShare(double streamline, double cap) {
  return streamline > cap ? cap / streamline : 1.0;
}

class VelocityAdvection {
 public:
  virtual ~VelocityAdvection() = default;
  // Called before step (33) with u^n, the velocity the step starts from. With
  // splitting.steady_correction = "tendency" the scheme keeps it: the tendency of (33) is
  // (u^{n+1/4} - u^n) / dt. A Solve without a BeginStep since the last one takes that tendency as
  // 0.
  virtual void BeginStep(const double* /*u*/, const double* /*v*/) {}
  // In: u, v = u^{n+1/4}. Out: u, v = u^{n+2/4} after dt. What depends on dt (the implicit
  // diffusion's fast solver) is built for the first call's and rebuilt when a call brings another.
  virtual AdvectionReport Solve(double dt, double* u, double* v) = 0;
  // Writes the scheme's columns of `report` from the result of Solve.
  virtual void Record(const AdvectionReport& result, StepReport& report) const = 0;
};

// The scheme of params.splitting.advection, with the weight beta of (34); boundary_data must
// outlive it.
std::unique_ptr<VelocityAdvection> MakeVelocityAdvection(const Grid& grid, const Params& params,
                                                         const BoundaryData& boundary_data);

}  // namespace dlmfd
