// Step (33) with fixed or prescribed bodies cut out of the mesh; see particles/cut_cell_step.h.
#include "dlmfd/particles/cut_cell_step.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/particles/particle_rules.h"
#include "dlmfd/particles/shape.h"

namespace dlmfd {

CutCellStep::CutCellStep(const Params& params, const Grid& grid)
    : grid_(grid),
      domain_(params.domain),
      viscosity_(params.fluid.ImplicitViscosity(grid.h)),
      body_force_(params.fluid.body_force),
      buoyancy_acceleration_(-params.gravity),
      fluid_density_(params.fluid.density) {
  RequireCutCellScene(params);
  if (!params.fluid.IsNewtonian()) {
    const double elastic_share = 1.0 - params.fluid.DevssWeight(grid.h);  // 1 - w
    constants_.ghost_velocity +=
        (constants_.ghost_velocity_elastic - constants_.ghost_velocity) * elastic_share;
  }
  for (const ParticleParams& q : params.particles) {
    bodies_.push_back({Shape::Of(q), q.center, q.angle});
    const bool prescribed = q.motion == Motion::kPrescribed;
    velocities_.push_back(prescribed ? q.velocity : Vec2::Zero());
    rotations_.push_back(prescribed ? q.angular_velocity : 0.0);
    density_.push_back(q.density);
    moving_ = moving_ || q.motion != Motion::kFixed;
  }
  // The report's surface gaps by the collision model's measure (particles/collision_forces.h).
  std::vector<double> radii;
  std::vector<Shape> shapes;
  for (const FixedBody& body : bodies_) {
    radii.push_back(body.shape.BoundingRadius());
    shapes.push_back(body.shape);
  }
  gaps_ = std::make_unique<CollisionForces>(params, grid, std::move(radii));
  gaps_->SetShapes(shapes);
  gap_centres_.resize(bodies_.size());
  gap_angles_.resize(bodies_.size());
  // A free body starts at its given velocity; it is then Newton's law's (CutCellFreeBodies).
  for (std::size_t b = 0; b < params.particles.size(); ++b) {
    const ParticleParams& q = params.particles[b];
    if (q.motion != Motion::kFree) continue;
    velocities_[b] = q.velocity;
    rotations_[b] = q.angular_velocity;
  }
  if (std::any_of(params.particles.begin(), params.particles.end(),
                  [](const ParticleParams& q) { return q.motion == Motion::kFree; })) {
    free_bodies_ = std::make_unique<CutCellFreeBodies>(params, grid);
  }
  const CutPeriodicity periodic{params.domain.PeriodicX(), params.domain.PeriodicY()};
  geometries_.push_back(
      std::make_unique<CutCellGeometry>(grid, bodies_, CutTriangulation::kSwNe, periodic));
  if (params.domain.diagonals == MeshDiagonals::kBoth) {
    geometries_.push_back(
        std::make_unique<CutCellGeometry>(grid, bodies_, CutTriangulation::kNwSe, periodic));
  }
  for (const auto& geo : geometries_) geometry_views_.push_back(geo.get());
  fu_.assign(grid.NodeCount(), 0.0);
  fv_.assign(grid.NodeCount(), 0.0);
  MarkNodes();
}

void CutCellStep::MarkNodes() {
  const std::vector<double>& phi = geometries_[0]->distance();
  solid_nodes_.assign(grid_.NodeCount(), 1);
  inside_nodes_.assign(grid_.NodeCount(), 0);
  band_.clear();
  const bool px = domain_.PeriodicX(), py = domain_.PeriodicY();
  // The node (i, j) of the grid, across periodic sides; false outside it.
  auto neighbour = [&](int i, int j, std::size_t* k) {
    if (px) i = (i + grid_.nx) % grid_.nx;
    if (py) j = (j + grid_.ny) % grid_.ny;
    if (i < 0 || i > grid_.nx || j < 0 || j > grid_.ny) return false;
    *k = grid_.Index(i, j);
    return true;
  };
  for (int j = 0; j <= grid_.ny; ++j) {
    for (int i = 0; i <= grid_.nx; ++i) {
      const std::size_t k = grid_.Index(i, j);
      for (const auto& geo : geometries_) {
        if (geo->NodeActive(k)) solid_nodes_[k] = 0;
      }
      if (phi[k] >= 0.0) continue;
      inside_nodes_[k] = 1;
      if (solid_nodes_[k] != 0) continue;
      BandNode band{k, {}};
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          std::size_t n = 0;
          if ((di != 0 || dj != 0) && neighbour(i + di, j + dj, &n) && phi[n] >= 0.0) {
            band.fluid_neighbours.push_back(n);
          }
        }
      }
      band_.push_back(std::move(band));
    }
  }
}

void CutCellStep::ExtendIntoBodies(double* a11, double* a12, double* a22) const {
  for (const BandNode& b : band_) {
    if (b.fluid_neighbours.empty()) continue;
    double s11 = 0.0, s12 = 0.0, s22 = 0.0;
    for (const std::size_t n : b.fluid_neighbours) {
      s11 += a11[n];
      s12 += a12[n];
      s22 += a22[n];
    }
    const double w = 1.0 / static_cast<double>(b.fluid_neighbours.size());
    a11[b.node] = w * s11;
    a12[b.node] = w * s12;
    a22[b.node] = w * s22;
  }
}

CutCellStep::~CutCellStep() = default;

void CutCellStep::PrepareStep(double dt) {
  if (dt == dt_ && flow_) return;
  dt_ = dt;
  rho_over_dt_ = fluid_density_ / dt;
  flow_.reset();  // one saddle point at a time
  if (geometries_.size() == 2) {
    flow_ = std::make_unique<CutCellStokes>(*geometries_[0], *geometries_[1], domain_, viscosity_,
                                            fluid_density_, rho_over_dt_, constants_);
  } else {
    flow_ = std::make_unique<CutCellStokes>(*geometries_[0], domain_, viscosity_, fluid_density_,
                                            rho_over_dt_, constants_);
  }
}

std::vector<RigidMotion> CutCellStep::Motions() const {
  std::vector<RigidMotion> motions;
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    motions.push_back({bodies_[b].centre, velocities_[b], rotations_[b]});
  return motions;
}

// X^{n+1} = X^n + dt U (to the periodic box), theta^{n+1} = theta^n + dt omega; a body that
// reaches a side that is not periodic ends the run (cut cells have no contact model).
void CutCellStep::MoveBodies(double dt) {
  const bool periodic[2] = {domain_.PeriodicX(), domain_.PeriodicY()};
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    FixedBody& body = bodies_[b];
    body.centre += dt * velocities_[b];
    body.angle += dt * rotations_[b];
    const double r = body.shape.BoundingRadius();
    for (int k = 0; k < 2; ++k) {
      const double size = domain_.size[k], origin = k == 0 ? grid_.x0 : grid_.y0;
      if (periodic[k]) {
        body.centre[k] -= size * std::floor((body.centre[k] - origin) / size);
      } else if (body.centre[k] - r < origin || body.centre[k] + r > origin + size) {
        std::ostringstream what;
        what << "particle " << b << " reaches the " << (k == 0 ? "left or right" : "bottom or top")
             << " side (centre " << body.centre.x() << ", " << body.centre.y()
             << "): prescribed bodies with particle_mesh.kind = \"cut_cell\" have no contact "
                "model; end the run before or use periodic sides";
        throw ParticlesOverlap(what.str());
      }
    }
  }
  if (free_bodies_) {
    const double gap = free_bodies_->PairGap(bodies_);
    if (gap < 0.0) {
      std::ostringstream what;
      what << "two bodies overlap (surface gap " << gap
           << "): the collision forces (collisions.*) did not hold them apart";
      throw ParticlesOverlap(what.str());
    }
  }
  CutBodies();
}

void CutCellStep::CutBodies() {
  // In place: the saddle point refers to them (CutCellStokes::Recut).
  const CutPeriodicity periodic_axes{domain_.PeriodicX(), domain_.PeriodicY()};
  *geometries_[0] = CutCellGeometry(grid_, bodies_, CutTriangulation::kSwNe, periodic_axes);
  if (geometries_.size() == 2)
    *geometries_[1] = CutCellGeometry(grid_, bodies_, CutTriangulation::kNwSe, periodic_axes);
  MarkNodes();
}

void CutCellStep::FillBodies(double* u, double* v) const {
  const std::vector<RigidMotion> motions = Motions();
  for (std::size_t k = 0; k < grid_.NodeCount(); ++k) {
    if (solid_nodes_[k] == 0) continue;
    const RigidMotion& body = motions[static_cast<std::size_t>(geometries_[0]->NearestBody(k))];
    Vec2 arm = Vec2(grid_.X(static_cast<int>(k % grid_.NodesX())),
                    grid_.Y(static_cast<int>(k / grid_.NodesX()))) -
               body.centre;
    if (domain_.PeriodicX()) arm.x() -= grid_.Width() * std::round(arm.x() / grid_.Width());
    if (domain_.PeriodicY()) arm.y() -= grid_.Height() * std::round(arm.y() / grid_.Height());
    const Vec2 g = body.At(arm);
    u[k] = g.x();
    v[k] = g.y();
  }
}

bool CutCellStep::MoveBeforeStep(double dt, double* u, double* v) {
  if (!moving_) return false;
  FillBodies(u, v);  // u^n inside the bodies at X^n: the value of the nodes they uncover
  MoveBodies(dt);
  return true;
}

// The Uzawa iteration's start for a moving body: p* = 2 p^n - p^{n-1} where both are set (a
// pattern that moves with the body changes p at a fixed node by O(dt) a step, p* by O(dt^2)); p^n
// at nodes that were not in the fluid. The step's result is the same within its stopping rule.
void CutCellStep::ExtrapolatePressure(double* p) {
  const std::size_t np = grid_.Coarse().NodeCount();
  if (last_pressure_.size() != np) {
    last_pressure_.assign(p, p + np);
    return;
  }
  for (std::size_t k = 0; k < np; ++k) {
    const double now = p[k];
    if (now != 0.0 && last_pressure_[k] != 0.0) p[k] = 2.0 * now - last_pressure_[k];
    last_pressure_[k] = now;
  }
}

CutCellStart CutCellStep::SavedStart() const {
  if (restored_) return *restored_;  // not taken yet: no step since Restore
  CutCellStart start;
  start.previous_pressure = last_pressure_;
  if (flow_ && !moving_) {  // a moving body's operator changes every step
    start.corrections_dt = dt_;
    start.corrections = flow_->Corrections();
  }
  return start;
}

void CutCellStep::Restore(const std::vector<ParticleState>& particles, CutCellStart start) {
  if (moving_) {  // prescribed and free bodies go on from where the checkpoint has them
    for (std::size_t b = 0; b < bodies_.size() && b < particles.size(); ++b) {
      bodies_[b].centre = particles[b].position;
      bodies_[b].angle = particles[b].angle;
      if (free_bodies_ && free_bodies_->IsFree(b)) {  // and free ones at its velocity
        velocities_[b] = particles[b].velocity;
        rotations_[b] = particles[b].angular_velocity;
      }
    }
    CutBodies();
  }
  last_pressure_ = start.previous_pressure;
  restored_ = std::move(start);
}

void CutCellStep::Solve(double dt, const BoundaryData& data, std::vector<ParticleState>& particles,
                        double* u, double* v, double* p, StepReport& report,
                        const NodeForce& polymer) {
  PrepareStep(dt);
  const std::vector<RigidMotion> now = Motions();  // V^n
  if (free_bodies_) {
    // The first solve's motion V* (CutCellFreeBodies::Predict), from the load of the last step.
    CutCellFreeBodies::Loads last;
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      last.force.push_back(b < particles.size() ? particles[b].force : Vec2::Zero());
      last.torque.push_back(b < particles.size() ? particles[b].torque : 0.0);
    }
    std::vector<RigidMotion> predicted = now;
    free_bodies_->Predict(dt, bodies_, last, predicted);
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      velocities_[b] = predicted[b].velocity;
      rotations_[b] = predicted[b].angular_velocity;
    }
  }
  if (moving_) {
    // The band anew, the rest kept; after a fresh build too, so that every step's forms come from
    // the one sum (the uniform forms and the band's), which a fresh build's whole-mesh assembly
    // matches to round-off only: the first step of a run resumed from a checkpoint is then the
    // uninterrupted run's, bit for bit.
    flow_->Recut();
    flow_->SetBodyMotion(Motions());
  }
  if (restored_) {
    if (!moving_ && restored_->corrections_dt == dt && !restored_->corrections.q.empty())
      flow_->RestoreCorrections(std::move(restored_->corrections));
    restored_.reset();
  }
  const Eigen::VectorXd& mass = flow_->FluidMass();
  for (std::size_t k = 0; k < fu_.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    fu_[k] = mass[i] * (rho_over_dt_ * u[k] + body_force_.x());
    fv_[k] = mass[i] * (rho_over_dt_ * v[k] + body_force_.y());
  }
  if (polymer.present()) {
    for (std::size_t k = 0; k < fu_.size(); ++k) {
      fu_[k] += polymer.x[k];
      fv_[k] += polymer.y[k];
    }
    AddCutCellPolymerCorrection(geometry_views_, polymer.modulus, polymer.s11, polymer.s12,
                                polymer.s22, fu_.data(), fv_.data());
  }
  if (moving_) ExtrapolatePressure(p);
  const CutCellStokes::LoadStop stop = FreeLoadStop(particles);
  const CutCellStokes::LoadStop* load_stop = stop.bodies.empty() ? nullptr : &stop;
  const CutCellReport r =
      flow_->Solve(data, fu_.data(), fv_.data(), u, v, p, constants_.step_tolerance,
                   constants_.step_max_iterations, load_stop);
  report.Set("stokes_iterations", r.iterations);
  report.Set("stokes_residual", r.relative_residual);
  if (free_bodies_) {
    // Newton's law of the free bodies, implicit in their velocities (CutCellFreeBodies).
    CutCellFreeBodies::Loads first;
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      const CutCellStokes::BodyLoad load = HydrodynamicLoad(b, u, v, p);
      first.force.push_back(load.force);
      first.torque.push_back(load.torque);
    }
    std::vector<RigidMotion> motions = Motions();
    const CutCellFreeBodies::Outcome o = free_bodies_->Couple(
        *flow_, dt, bodies_, first, now, motions, u, v, p, constants_.step_tolerance,
        constants_.unit_tolerance, constants_.step_max_iterations);
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      velocities_[b] = motions[b].velocity;
      rotations_[b] = motions[b].angular_velocity;
    }
    flow_->SetBodyMotion(motions);
    int second = 0;  // K kept: the step's solution is a solve at the new velocity
    if (!o.composed) {
      const CutCellReport again =
          flow_->Solve(data, fu_.data(), fv_.data(), u, v, p, constants_.step_tolerance,
                       constants_.step_max_iterations, load_stop);
      second = again.iterations;
    }
    report.Set("rigid_mode_iterations", o.unit_iterations);
    report.Set("rigid_modes_made", o.made ? 1 : 0);
    report.Set("free_motion_iterations", second);
    report.Set("collision_contacts", o.contacts);
  }
  if (moving_) FillBodies(u, v);
  for (std::size_t b = 0; b < particles.size(); ++b) {
    ParticleState& s = particles[b];
    const FixedBody& body = bodies_[b];
    s.position = body.centre;
    s.angle = body.angle;
    const CutCellStokes::BodyLoad load = HydrodynamicLoad(b, u, v, p);
    s.force = load.force;
    s.torque = load.torque;
    s.velocity = velocities_[b];
    s.angular_velocity = rotations_[b];
  }
  ReportGaps(report);
}

// The true surface gaps at X^{n+1}, the positions the particles get (header).
void CutCellStep::ReportGaps(StepReport& report) {
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    gap_centres_[b] = bodies_[b].centre;
    gap_angles_[b] = bodies_[b].angle;
  }
  gaps_->SetAngles(gap_angles_);
  const CollisionForces::SurfaceGaps gaps = gaps_->Gaps(gap_centres_);
  report.Set("particle_min_gap", gaps.Min());
  report.Set("particle_pair_gap", gaps.pair);
  report.Set("particle_wall_gap", gaps.wall);
}

// The free bodies' load stop: bound epsilon S_b on the force, epsilon S_b R_b on the torque, S_b
// the largest of the weight less buoyancy, the last step's load less buoyancy and the viscous
// load of the body's own motion, 4 pi eta (|U_b| + R_b |omega_b|) (header).
CutCellStokes::LoadStop CutCellStep::FreeLoadStop(
    const std::vector<ParticleState>& particles) const {
  CutCellStokes::LoadStop stop;
  if (!free_bodies_) return stop;
  const double epsilon = constants_.free_load_tolerance;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (!free_bodies_->IsFree(b)) continue;
    const Shape& shape = bodies_[b].shape;
    const Vec2 buoyancy = shape.Mass(fluid_density_) * buoyancy_acceleration_;
    const double weight = (shape.Mass(density_[b]) * -buoyancy_acceleration_ + buoyancy).norm();
    const double last = b < particles.size() ? (particles[b].force - buoyancy).norm() : 0.0;
    const double radius = shape.BoundingRadius();
    const double viscous =
        4.0 * kPi * viscosity_ * (velocities_[b].norm() + radius * std::abs(rotations_[b]));
    const double scale = std::max({weight, last, viscous});
    if (scale == 0.0) continue;
    stop.bodies.push_back(static_cast<int>(b));
    stop.centres.push_back(bodies_[b].centre);
    stop.force_bound.push_back(epsilon * scale);
    stop.torque_bound.push_back(epsilon * scale * radius);
  }
  return stop;
}

// F_h and T_h of body b (header), at its present motion.
CutCellStokes::BodyLoad CutCellStep::HydrodynamicLoad(std::size_t b, const double* u,
                                                      const double* v, const double* p) const {
  const FixedBody& body = bodies_[b];
  CutCellStokes::BodyLoad load =
      flow_->Load(static_cast<int>(b), body.centre, u, v, p, fu_.data(), fv_.data());
  load.force = load.force + body.shape.Mass(fluid_density_) * buoyancy_acceleration_ +
               body.shape.Area() * body_force_;
  // The viscous form is eta grad u : grad v, whose traction on a rigid body differs from the
  // stress's in the torque by 2 eta omega V (header).
  load.torque -= 2.0 * viscosity_ * rotations_[b] * body.shape.Area();
  return load;
}

}  // namespace dlmfd
