// The rules a scene's particles obey so that the DLM/FD step (36)-(38) is well posed. The scene
// validation (scene/scene_validation.h) applies ValidateParticles to every scene before anything
// runs; RigidBodyConstraint's constructor applies the two DLM rules again as its guard, so each
// rule has one definition.
//
// - A free particle is not lighter than the liquid: its excess mass (rho_d - rho_L) V in (36)-(38)
//   is positive, or zero (neutrally buoyant: the rigid-mode projector handles it); a negative one
//   makes the multiplier problem (37) indefinite, and its solver is CG. (Not with cut cells, which
//   have no multiplier: particles/cut_cell_free_bodies.h.)
// - With splitting.constraint = "viscous", no free particle is neutrally buoyant (nor this with
//   cut cells).
// - The ring mesh (particle_mesh.kind = "ring") is a disk's: other shapes need collocation points.
// - Cut cells (particle_mesh.kind = "cut_cell", particles/cut_cell_step.h) hold fixed, prescribed
//   and free disks (particles/cut_cell_free_bodies.h), also in a liquid with a polymer (moving ones
//   are moved and A extended before the polymer's force: docs/evidence/cut_cell_boundary.md, "The
//   polymer around a free body" and "The polymer around a towed body"),
//   with all the viscosity in step (33) (splitting.beta = 0: the advection step (34) does not see
//   the bodies), and without domain.flow_rate (the cut-cell step has no flux control; a body force
//   drives a periodic box). Periodic sides and boxes without an outflow side are supported. An
//   ellipse is cut as a disk is (its exact signed distance at its angle): a fixed one in any liquid
//   (docs/evidence/cut_cell_boundary.md, "A fixed ellipse"), a prescribed or free one in a
//   Newtonian liquid ("Moving ellipses": Jeffery's orbit) whose tip's radius of curvature b^2 / a
//   is at least kMovingEllipseTipCells h (a / b = 2 ran at 1.6 h and more; a / b = 4 at 0.6 h and
//   0.8 h had a step fail, its angular velocity jumping to 20-130 where Jeffery's is below 1); a
//   moving ellipse in a polymer is refused (not measured).
// - The velocity grid has at most 2^32 - 1 nodes: E and E^T store 32-bit node indices.
// - At t = 0 every disk lies inside the domain (crossing periodic sides only) and no two disks
//   overlap (centre distances by the nearest periodic image).
#pragma once

#include <cstddef>
#include <optional>

#include "dlmfd/core/errors.h"
#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/particles/shape.h"

namespace dlmfd {

// Throws InvalidParameter (particles.P.density) when free particle p is lighter than the liquid,
// (particles.P.diameter) when its excess mass is too small for a double.
void RequireNotLighterThanLiquid(const Params& params, std::size_t p);
// Throws InvalidParameter (particles.P.density) when free particle p is neutrally buoyant and
// splitting.constraint = "viscous" (the coupled Stokes step (33) solves for heavy free, fixed and
// prescribed particles; particles/viscous_constraint.h).
void RequireCoupledInStokes(const Params& params, std::size_t p);
// Throws InvalidParameter (particle_mesh.kind) when particle p's shape is not a disk: the ring
// mesh of particles/particle_mesh.h is built on disks only.
void RequireRingMeshShape(const Shape& shape, std::size_t p);
// A moving ellipse's least tip radius of curvature b^2 / a with cut cells, in cells (header).
inline constexpr double kMovingEllipseTipCells = 1.6;
// Throws InvalidParameter (particles.P.shape, domain.h, splitting.beta, domain.flow_rate) when the
// scene breaks a cut-cell rule above (particle_mesh.kind = "cut_cell").
void RequireCutCellScene(const Params& params);
// The first cut-cell rule above that the scene breaks, whatever its particle_mesh.kind, as the
// error RequireCutCellScene would throw; none where cut cells can run it. particle_mesh.kind =
// "auto" reads it (scene/auto_particle_mesh.h), so the two never disagree.
std::optional<InvalidParameter> CutCellObstacle(const Params& params);
// Throws InvalidParameter (domain.h) when `grid` has more nodes than 32-bit indices count.
void RequireIndexableGrid(const Params& params, const Grid& grid);
// Every rule above, for every particle of the scene (none: the grid rule does not apply).
void ValidateParticles(const Params& params, const Grid& grid);

}  // namespace dlmfd
