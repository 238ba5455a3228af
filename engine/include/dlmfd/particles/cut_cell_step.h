// Step (33) of the Marchuk-Yanenko scheme with fixed or prescribed bodies cut out of the uniform
// mesh (particle_mesh.kind = "cut_cell"; issue 33, docs/evidence/cut_cell_boundary.md, "A
// second-order boundary" and "A body in prescribed motion"):
//   (rho/dt) (u^{n+1/4} - u^n, v)_l + eta (grad u^{n+1/4}, grad v) - (p, div v) = (f, v),
//   (q, div u^{n+1/4}) = 0   on the fluid part only, u = U + omega x (x - X) on the bodies by
// Nitsche's method (0 on fixed ones)
// (particles/cut_cell_stokes.h has the forms, the ghost penalties and the solver: Uzawa /
// CG on the pressure with exact velocity solves by a capacitance matrix against the fast solvers,
// warm-started from p^n). f is the liquid's body force
// (fluid.body_force); eta the whole viscosity (a Newtonian liquid, splitting.alpha = 1: the rules
// of particles/particle_rules.h). The advection step (34) then runs on the whole grid as without
// particles, and there is no step (36)-(38): fixed bodies stay, prescribed ones move at their
// given U and omega, free ones by Newton's law, implicit in their velocities through step (33)
// (particles/cut_cell_free_bodies.h: 3 more Stokes solves a free body, the paper's collision
// forces (14)-(15); the step's solves stop also on the free bodies' loads, FreeLoadStop, within
// CutCellConstants::free_load_tolerance of each one's load scale: the largest of its weight less
// buoyancy, its last load less buoyancy and 4 pi eta (|U| + R |omega|), the viscous load of its
// motion: docs/evidence/cut_cell_boundary.md, "A stopping rule on the body's load"). A moving body
// is cut at t_{n+1} (X^{n+1} = X^n + dt U, theta^{n+1} = theta^n + dt omega, with a free body's
// U^n, omega^n; step (33) is implicit), so the geometry, the forms and the capacitance matrix are
// rebuilt every step (the chords move with the body even where the cut set does not change), at the
// cost of the band (CutCellStokes::Recut: the uniform forms, the fast solvers and the capacitance
// matrix's fast solves of the rows that stay in the band are kept), and the pressure iteration
// starts from 2 p^n - p^{n-1}. The nodes inside a body (no fluid in their support) carry its rigid
// motion, before the step at X^n and after it at X^{n+1}: a node that the body uncovers enters the
// step with the rigid value u^n = U + omega x (x_i - X^n) in its mass term, and the advection step
// (34) sees the body move. Cost a step against the fixed body's:
// docs/evidence/cut_cell_boundary.md, "A body in prescribed motion".
// The hydrodynamic force and torque on each body, from the residual of this step's fluid forms
// with a test function equal to 1 near the body (CutCellStokes::Load; the discrete stress over a
// closed line in the fluid around it, the fluid's inertia between the line and the body included):
//   F_h = -sum_i Phi_i R_i - rho_L V g + V f,   T_h = -sum_i Phi_i (x_i - X) x R_i,
// R = (rho/dt) M_l (u^{n+1/4} - u^n) + eta K u^{n+1/4} - B^T p - M_l f; a body turning at omega
// adds -2 eta omega V to T_h: the viscous form eta grad u : grad v has the traction eta d_n u, not
// the stress's eta (grad u + grad u^T) n, and on a rigid motion u = U + omega x r the two differ
// by eta integral of r x (grad u^T n) = eta int_body curl u = 2 eta omega V in the torque (0 in the
// force: int grad(div u) = 0). E.g. a disk turning in unbounded liquid, u_theta = omega R^2 / r:
// eta d_n u = -eta omega on its boundary, the stress -2 eta omega (measured: docs/evidence/
// cut_cell_boundary.md, "A body in prescribed motion"). The fluid steps carry no
// gravity, so -rho_L V g is the hydrostatic buoyancy, as in the DLM force (particles/
// particle_step.h); f taken as a mean pressure gradient -grad p_m = f acts on the body's volume
// too, V f, as the DLM force has it (there f acts on the whole domain, the body's inside
// included): in a periodic box at steady state F_h = f L^2, the force per body of Sangani &
// Acrivos. Periodic sides and boxes without an outflow side as in particles/cut_cell_stokes.h (the
// square array: docs/evidence/cut_cell_boundary.md, "Periodic boxes: the square array"). With
// domain.diagonals = "both" every form is the mean over the two triangulations. With a polymer
// (fixed, prescribed or free bodies) its force joins the load as the fluid part's integral
// (particles/cut_cell_polymer_force.h), so F_h holds the polymer's traction; step (35) holds A = I
// at the nodes inside the bodies (InsideNodes), and then the nodes inside a body that are vertices
// of a cut triangle take the mean of their neighbours' A in the fluid (ExtendIntoBodies), so that
// the fluid polygon's stress is interpolated from fluid values. (Letting those nodes evolve by
// step (35) with the velocity's extension into the body ran away at Wi = 0.9, R/h = 8: nothing
// carries A out of the body there.) The velocity's ghost penalty grows with the polymer's elastic
// share (CutCellConstants::ghost_velocity_elastic): with the Newtonian one the confined cylinder
// blew up at Wi = 0.6, R/h = 24. Report columns:
// stokes_iterations (Uzawa / CG), stokes_residual (the saddle point's relative residual); with
// free bodies rigid_mode_iterations (the unit solves' Uzawa iterations, all together),
// rigid_modes_made (1 where K was made this step, 0 where kept), free_motion_iterations (the solve
// at the new velocity; 0 where none) and collision_contacts; with any bodies particle_pair_gap,
// particle_wall_gap and particle_min_gap at X^{n+1}, the true surface gaps of the collocation path
// (particles/particle_step.h), measured by the collision model (CollisionForces::Gaps; NaN where
// there is nothing to measure).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/core/state.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/particles/collision_forces.h"
#include "dlmfd/particles/cut_cell_free_bodies.h"
#include "dlmfd/particles/cut_cell_geometry.h"
#include "dlmfd/particles/cut_cell_polymer_force.h"
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

  // The bodies to X^{n+1} and the band marked there (u^n filled into them at X^n first): every
  // step calls it before Solve, which does not move the bodies, so that with a polymer A can be
  // extended into the new band (ExtendIntoBodies) before the polymer's force of the step is made
  // from it (a node of the new band that was deeper inside at X^n holds A = I from step (35)).
  // False, and nothing done, without a moving body.
  bool MoveBeforeStep(double dt, double* u, double* v);
  // A step of dt, the bodies at X^{n+1} (MoveBeforeStep first). u, v, p: u^n (at nodes that were
  // inside a body at X^n, its rigid motion) and the last pressure on entry (the warm start),
  // u^{n+1/4}, p^{n+1/4} on return with the Dirichlet data of `data` (its time set to t_{n+1});
  // particles get F_h and T_h (prescribed ones also X^{n+1}, theta^{n+1}; free ones also U^{n+1},
  // omega^{n+1}). The saddle point of (rho/dt) is built for the first call's dt and rebuilt when a
  // call brings another, and every step when a body moves. Throws SolverNotConverged, and
  // ParticlesOverlap when a moving body reaches a side that is not periodic or two bodies overlap.
  // polymer: the polymer's whole-mesh force of (33) and its stress (core/node_force.h; absent: a
  // Newtonian liquid).
  void Solve(double dt, const BoundaryData& data, std::vector<ParticleState>& particles, double* u,
             double* v, double* p, StepReport& report, const NodeForce& polymer = {});
  // What the step keeps of earlier steps beyond the state, for a checkpoint (core/state.h): p^{n-1}
  // of a moving body's extrapolated start, and around fixed bodies the pressure corrections of the
  // Uzawa start with the dt of their operator.
  CutCellStart SavedStart() const;
  // A run resumed from a checkpoint: prescribed bodies where the particles are (X^n, theta^n), and
  // SavedStart's start again (the corrections at the next Solve, once its operator is built, if it
  // is theirs: fixed bodies, the same dt), so the resumed run takes the steps of the run that wrote
  // the checkpoint, bit for bit.
  void Restore(const std::vector<ParticleState>& particles, CutCellStart start);
  // Per velocity node, 1 inside a body (the distance phi < 0, particles/cut_cell_geometry.h), at
  // the bodies' last positions: where step (35) holds A = I.
  const std::vector<unsigned char>& InsideNodes() const { return inside_nodes_; }
  // A at the nodes inside a body that are vertices of a cut triangle: the mean of their
  // neighbours' (the 8 around them, across periodic sides) in the fluid, phi >= 0; every such
  // node has one, a vertex of its cut triangle. A convex combination: SPD stays SPD.
  void ExtendIntoBodies(double* a11, double* a12, double* a22) const;

 private:
  // flow_ and rho_over_dt_ for a step of dt (flow_ made anew for a new dt).
  void PrepareStep(double dt);
  // Prescribed bodies: X, theta to t + dt, the geometries cut anew there (CutBodies).
  void MoveBodies(double dt);
  // The geometries cut anew (in place) at the bodies' places, and the nodes marked for them.
  void CutBodies();
  std::vector<RigidMotion> Motions() const;
  // F_h and T_h of body b at its present motion (header), from the step's solution.
  CutCellStokes::BodyLoad HydrodynamicLoad(std::size_t b, const double* u, const double* v,
                                           const double* p) const;
  // The free bodies' solves' stopping rule on their loads (CutCellConstants::free_load_tolerance);
  // particles: the last step's state (its load). Empty without free bodies.
  CutCellStokes::LoadStop FreeLoadStop(const std::vector<ParticleState>& particles) const;
  // particle_pair_gap, particle_wall_gap, particle_min_gap at the bodies' places (header).
  void ReportGaps(StepReport& report);
  // The rigid motion of the nearest body at every node without fluid in its support.
  void FillBodies(double* u, double* v) const;
  // solid_nodes_, inside_nodes_ and band_ of the present geometries.
  void MarkNodes();

  std::vector<FixedBody> bodies_;                   // at the last step's end (X^{n+1})
  std::vector<Vec2> velocities_;                    // U of each body (0: fixed)
  std::vector<double> rotations_;                   // omega of each body
  std::vector<double> density_;                     // rho_p of each body
  bool moving_ = false;                             // some body is prescribed or free
  std::unique_ptr<CutCellFreeBodies> free_bodies_;  // some body is free
  std::unique_ptr<CollisionForces> gaps_;           // the report's surface gaps
  std::vector<Vec2> gap_centres_;                   // X^{n+1} of each body, for gaps_
  std::vector<double> gap_angles_;                  // theta^{n+1} of each body, for gaps_
  Grid grid_;
  std::vector<std::unique_ptr<CutCellGeometry>> geometries_;  // SW-NE, then NW-SE with "both"
  std::vector<const CutCellGeometry*> geometry_views_;  // the same, read-only (moved in place)
  DomainParams domain_;
  double viscosity_;                     // eta of the forms
  std::unique_ptr<CutCellStokes> flow_;  // of dt_
  double dt_ = 0.0, rho_over_dt_ = 0.0;  // of the last step; 0 before the first
  Vec2 body_force_;
  Vec2 buoyancy_acceleration_;  // -g: F_h adds rho_L V (-g)
  double fluid_density_;
  CutCellConstants constants_;
  std::vector<double> fu_, fv_;  // the load of the step: M_l (rho/dt u^n + f) (+ the polymer's)
  std::vector<unsigned char> solid_nodes_;   // no fluid in the node's support
  std::vector<unsigned char> inside_nodes_;  // phi < 0
  struct BandNode {
    std::size_t node;
    std::vector<std::size_t> fluid_neighbours;
  };
  std::vector<BandNode> band_;  // inside a body, not solid
  // A moving body: p^{n-1}, for the extrapolated start of the pressure iteration.
  void ExtrapolatePressure(double* p);
  std::vector<double> last_pressure_;
  std::optional<CutCellStart> restored_;  // Restore's, until the next Solve takes it
};

}  // namespace dlmfd
