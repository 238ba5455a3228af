// Step (33) of the Marchuk-Yanenko scheme with fixed bodies cut out of the uniform mesh
// (particle_mesh.kind = "cut_cell"; issue 33, docs/evidence/cut_cell_boundary.md, "A second-order
// boundary"):
//   (rho/dt) (u^{n+1/4} - u^n, v)_l + eta (grad u^{n+1/4}, grad v) - (p, div v) = (f, v),
//   (q, div u^{n+1/4}) = 0   on the fluid part only, u = 0 on the bodies by Nitsche's method
// (particles/cut_cell_stokes.h has the forms, the ghost penalties and the solver: Uzawa /
// CG on the pressure with exact velocity solves by a capacitance matrix against the fast solvers,
// warm-started from p^n). f is the liquid's body force
// (fluid.body_force); eta the whole viscosity (a Newtonian liquid, splitting.alpha = 1: the rules
// of particles/particle_rules.h). The advection step (34) then runs on the whole grid as without
// particles, and there is no step (36)-(38): the bodies do not move.
// The hydrodynamic force and torque on each body, from the residual of this step's fluid forms
// with a test function equal to 1 near the body (CutCellStokes::Load; the discrete stress over a
// closed line in the fluid around it, the fluid's inertia between the line and the body included):
//   F_h = -sum_i Phi_i R_i - rho_L V g + V f,   T_h = -sum_i Phi_i (x_i - X) x R_i,
// R = (rho/dt) M_l (u^{n+1/4} - u^n) + eta K u^{n+1/4} - B^T p - M_l f. The fluid steps carry no
// gravity, so -rho_L V g is the hydrostatic buoyancy, as in the DLM force (particles/
// particle_step.h); f taken as a mean pressure gradient -grad p_m = f acts on the body's volume
// too, V f, as the DLM force has it (there f acts on the whole domain, the body's inside
// included): in a periodic box at steady state F_h = f L^2, the force per body of Sangani &
// Acrivos. Periodic sides and boxes without an outflow side as in particles/cut_cell_stokes.h (the
// square array: docs/evidence/cut_cell_boundary.md, "Periodic boxes: the square array"). With
// domain.diagonals = "both" every form is the mean over the two triangulations. Report columns:
// stokes_iterations (Uzawa / CG), stokes_residual (the saddle point's relative residual).
#pragma once

#include <memory>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/particles/cut_cell_geometry.h"
#include "dlmfd/particles/cut_cell_stokes.h"

namespace dlmfd {

class CutCellStep {
 public:
  // The scene obeys RequireCutCellScene (particles/particle_rules.h); throws InvalidParameter
  // otherwise.
  CutCellStep(const Params& params, const Grid& grid);
  ~CutCellStep();
  CutCellStep(const CutCellStep&) = delete;
  CutCellStep& operator=(const CutCellStep&) = delete;

  // A step of dt. u, v, p: u^n and the last pressure on entry (the warm start), u^{n+1/4},
  // p^{n+1/4} on return with the Dirichlet data of `data` (its time set to t_{n+1}); particles get
  // F_h and T_h. The saddle point of (rho/dt) is built for the first call's dt and rebuilt when a
  // call brings another. Throws SolverNotConverged.
  void Solve(double dt, const BoundaryData& data, std::vector<ParticleState>& particles, double* u,
             double* v, double* p, StepReport& report);

 private:
  void PrepareStep(double dt);  // flow_ and rho_over_dt_ for a step of dt

  std::vector<FixedBody> bodies_;
  std::vector<std::unique_ptr<CutCellGeometry>> geometries_;  // SW-NE, then NW-SE with "both"
  DomainParams domain_;
  double viscosity_;                     // eta of the forms
  std::unique_ptr<CutCellStokes> flow_;  // of dt_
  double dt_ = 0.0, rho_over_dt_ = 0.0;  // of the last step; 0 before the first
  Vec2 body_force_;
  Vec2 buoyancy_acceleration_;  // -g: F_h adds rho_L V (-g)
  double fluid_density_;
  CutCellConstants constants_;
  std::vector<double> fu_, fv_;  // the load of the step: M_l (rho/dt u^n + f)
};

}  // namespace dlmfd
