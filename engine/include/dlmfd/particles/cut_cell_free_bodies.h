// Free rigid bodies cut out of the mesh (particle_mesh.kind = "cut_cell",
// particles/cut_cell_step.h; issue 33 point 2; docs/evidence/cut_cell_boundary.md, "A free body"):
// Newton's law over a step, implicit in the bodies' velocities through the fluid.
//
// For the step's cut geometry (the bodies at X^{n+1}) and load, step (33) is linear in the
// boundary value g = V_b + omega_b x (x - X_b) that Nitsche's terms impose on each body's chords,
// and so is the hydrodynamic force and torque read from its residual (CutCellStokes::Load):
//   F_h(V) = F_h(V*) + K (V - V*),   V = (U_1, omega_1, ..., U_N, omega_N) over the free bodies,
// with column s of K the force and torque on every free body of the solve with g = e_s on one
// body (a unit translation along x or y, or a unit rotation), no load and homogeneous Dirichlet
// data (velocity sides read as walls), plus -2 eta V_b on the rotation's own torque (the
// traction of eta grad u : grad v, particles/cut_cell_step.h). V* is the motion of the step's
// first solve (Predict, below). Newton's law over the step,
//   M_b (U_b - U_b^n) / dt = F_h,b(V) + M_b g + F'_b,   I_b (omega_b - omega_b^n) / dt = T_h,b(V),
// is then a linear system of 3N unknowns (the bodies coupled through the liquid),
//   (M / dt - K) (V - V*) = F_h(V*) + M g + F' + M (V^n - V*) / dt,
// and the step's solution is the first solve's plus sum_s (V - V*)_s times the unit solves' (the
// same as a solve with g = V up to the solves' tolerance, which enters times V - V*, small when
// the motion is smooth). F_h holds the liquid's inertia between the line where it is read and the
// body ((rho_L / dt) M_l (u^{n+1/4} - u^n) there, and the pressure the body's acceleration
// makes), so K holds the added mass: M / dt - K is positive definite for any body density, and
// the update stays stable for light and neutrally buoyant bodies, where an explicit force then
// velocity update is not (the added-mass instability at rho_p / rho_f near or below 1).
// F' are the collision forces (14)-(15) of the paper (particles/collision_forces.h) at X^{n+1},
// on the free bodies only (fixed and prescribed ones do not feel them; they push the free ones).
// M = rho_p V, I the shape's (rho_p V R^2 / 2 a disk, rho_p V (a^2 + b^2) / 4 an ellipse); g the
// gravity (F_h holds the buoyancy -rho_L V g).
// The position: X^{n+1} = X^n + dt U^n, theta^{n+1} = theta^n + dt omega^n (the cut at t_{n+1}
// must be known before the step: first order in the transient, exact at a terminal velocity).
// Cost: 1 + 3N Stokes solves a step, the 3N sharing the step's operators and factorisations and
// starting from the step's Galerkin start (particles/pressure_correction_basis.h) from their last
// step's pressure. Disks and ellipses (the cut at the angle theta; docs/evidence/
// cut_cell_boundary.md, "Moving ellipses"); the collision forces see bounding circles.
// K kept (particle_mesh.rigid_modes_refresh = r > 0, the default 1): K changes by O(|U| dt / h) a
// step, so it is made anew only once a body has moved r h since it was made (an ellipse also
// once |theta - theta_K| a > r h: its K turns with it) or dt changed; in between dV comes from
// the older K and the step solves once more, with g = V, for its solution and the force it
// reports, started from the first solve plus the last K's unit solutions times
// V - V* (made within r h of here: 1.2 Uzawa iterations a step on the 5.2 pair against 3.9 from
// the first solve alone; docs/evidence/cut_cell_boundary.md, "The solve at V started from the
// kept unit solutions"). Newton's law then holds to (K - K_old) dV, which vanishes at a terminal
// velocity: 2 solves a step instead of 1 + 3N (docs/evidence/cut_cell_boundary.md, "A free
// body": Faxen's fall speed moves by 2e-8, the 5.2 pair's first second by 1.1e-4 of its speed,
// light bodies as stable).
// The unit solves' tolerance (docs/evidence/cut_cell_boundary.md, "Where a free step's CPU
// goes"): where a K of this dt was kept before this step (Predict made V*), K is made anew from
// unit solves that stop at CutCellConstants::unit_tolerance (K's accuracy: it enters the step
// times V - V*), and the step's solution is a solve at V started from their composition, as where
// K is kept (Newton's law then holds to the new K's error times V - V*); where none was (the first
// step, after a resume or a new dt: V* = V^n, the motion all from the unit solves) they stop at
// the step's tolerance and their composition is the step's solution (Newton's law to round-off).
// The first solve's motion (Predict; docs/evidence/cut_cell_boundary.md, "The first solve's
// motion" and "A stopping rule on the body's load"): Newton's law over the step with the last
// step's load F_h^n for F_h(V*), the kept K, the collision forces at X^{n+1} (known before the
// step's solves; Couple reads the same) and the load's change at a fixed motion over the last
// step, D = F_h(V*') - F_h^{n-1} - K (V*' - V^{n-1}) (V*', F_h(V*'): the last step's first solve),
//   (M / dt - K) (V* - V^n) = F_h^n + M g + F'(X^{n+1}) + D,
// D left out while a body is in contact (now or in the last step: a wall force's change is not
// smooth) and until a step has measured it; V* = V^n while no K of this dt is kept (the first
// step, after a resume or a new dt). The error of a kept K, (K - K_old) (V - V*), shrinks with
// V - V*; the implicit M / dt - K keeps V* from growing where M / dt << K (creeping flow); D makes
// V* the linear extrapolation of V for light bodies (F_h^n holds the added mass's reaction to the
// last step's acceleration), so the solve at V starts near its answer. Both solves then stop on
// the body's load too (CutCellStokes::LoadStop, particles/cut_cell_step.h), or the force's error,
// of one sign step after step, drifts. Measured against D left out (main ef534c1): the 5.2 pair's
// Uzawa iterations a step (first solve, at V) 11.4 / 7.2 -> 11.6 / 3.8, the light disk 1.5e-5 ->
// 8.8e-6 of K every step, the wall-contact disk 0.976 -> 0.977 g*; without the load's rule the
// light disk drifted 2.0e-4. The linear extrapolation 2 V^n - V^{n-1} overshoots the wall
// contact (0.867 g*).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/particles/collision_forces.h"
#include "dlmfd/particles/cut_cell_geometry.h"
#include "dlmfd/particles/cut_cell_stokes.h"

namespace dlmfd {

class CutCellFreeBodies {
 public:
  CutCellFreeBodies(const Params& params, const Grid& grid);

  bool Any() const { return !free_.empty(); }
  bool IsFree(std::size_t body) const { return is_free_[body] != 0; }

  // The hydrodynamic load of the step's first solve on each body (F_h, T_h as the step reports
  // them, at the motion the solve imposed), indexed as the bodies.
  struct Loads {
    std::vector<Vec2> force;
    std::vector<double> torque;
  };
  struct Outcome {
    int unit_iterations = 0;  // the unit solves' Uzawa iterations, all together
    bool made = false;        // K was made this step (its unit solves may take 0 iterations)
    int contacts = 0;         // active collision contacts at X^{n+1}
    // K was made this step at the step's tolerance and u, v, p hold the step's solution; else (K
    // kept from an earlier step, particle_mesh.rigid_modes_refresh, or made at unit_tolerance)
    // `motions` is set and u, v, p hold a start, and the step solves again with them.
    bool composed = true;
  };
  // After Predict and the step's first solve (u, v, p: its solution, with every body's motion
  // `motions`, the free ones at V*): the free bodies' velocities and rotations of t_{n+1} into
  // `motions`, the solution into u, v, p (inactive nodes 0, as the solve leaves them). bodies: at
  // X^{n+1}, as the flow is cut. Throws SolverNotConverged. now: V^n. The unit solves stop at
  // `tolerance` where no K of this dt was kept before this step (no prediction: the first step,
  // after a resume or a new dt), and their composition is then the step's solution; else at
  // unit_tolerance (K's accuracy: header), and the step solves again at V from their composition.
  Outcome Couple(CutCellStokes& flow, double dt, const std::vector<FixedBody>& bodies,
                 const Loads& first, const std::vector<RigidMotion>& now,
                 std::vector<RigidMotion>& motions, double* u, double* v, double* p,
                 double tolerance, double unit_tolerance, int max_iterations);

  // The motion V* of the step's first solve (header), and the collision forces at X^{n+1}
  // (Couple's: call Predict first in every step): `motions` holds V^n on entry and V* on return
  // (V^n where no K of this dt is kept yet). last: the load the last step reported, F_h^n.
  // bodies: at X^{n+1}.
  void Predict(double dt, const std::vector<FixedBody>& bodies, const Loads& last,
               std::vector<RigidMotion>& motions);

  // Whether K must be made anew this step: never made, another dt, or a body moved more than
  // refresh_ h since it was (across a periodic seam the shortest way: a wrap is no move), or a
  // shape that turns with its angle (an ellipse) turned so far that its bounding radius's end
  // moved that much (|theta - theta_K| R > refresh_ h).
  bool NeedsK(double dt, const std::vector<FixedBody>& bodies) const;
  // K (k_) from the 3N unit solves; the flow's body motion is left at `motions`.
  void MakeK(CutCellStokes& flow, const std::vector<FixedBody>& bodies,
             const std::vector<RigidMotion>& motions, double tolerance, int max_iterations,
             Outcome& outcome);

  // The smallest surface gap between two bodies at these centres (NaN for fewer than two), for
  // the step's overlap check.
  double PairGap(const std::vector<FixedBody>& bodies);

 private:
  Grid grid_;
  double viscosity_;
  Vec2 gravity_;
  std::vector<std::size_t> free_;       // the free bodies' indices
  std::vector<unsigned char> is_free_;  // per body
  std::vector<double> mass_, inertia_;  // per body (free ones)
  std::vector<double> area_;            // per body
  BoundaryData homogeneous_;            // the Dirichlet sides' data read as walls: zero
  CollisionForces collisions_;
  std::vector<Vec2> positions_, contact_forces_;
  int contacts_ = 0;                       // active contacts at X^{n+1} (Predict)
  std::vector<Vec2> last_contact_forces_;  // F' of the last step (Predict: a body in contact)
  Loads last_;                             // F_h^n, as Predict read it
  bool has_last_ = false, has_change_ = false;
  Eigen::VectorXd change_;  // D of the last step (Couple)
  // The collision forces at these centres into contact_forces_; the number of active contacts.
  int ContactForces(const std::vector<FixedBody>& bodies);
  // M / dt - K (the bodies' own mass and inertia on the diagonal).
  Eigen::MatrixXd NewtonMatrix(double dt) const;
  // The unit solves' solutions (3 per free body), kept: their pressure is the next step's start.
  std::vector<std::vector<double>> unit_u_, unit_v_, unit_p_;
  // K kept (particle_mesh.rigid_modes_refresh): the matrix, the dt and the bodies' centres it was
  // made with.
  double refresh_ = 0.0;  // in units of h
  bool periodic_x_ = false, periodic_y_ = false;
  Eigen::MatrixXd k_;
  double k_dt_ = 0.0;
  std::vector<Vec2> k_centres_;
  std::vector<double> k_angles_;
};

}  // namespace dlmfd
