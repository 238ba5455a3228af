// Step (33) with fixed or prescribed bodies cut out of the mesh; see particles/cut_cell_step.h.
#include "dlmfd/particles/cut_cell_step.h"

#include <cmath>
#include <sstream>

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
  for (const ParticleParams& q : params.particles) {
    bodies_.push_back({Shape::Of(q), q.center, q.angle});
    const bool prescribed = q.motion == Motion::kPrescribed;
    velocities_.push_back(prescribed ? q.velocity : Vec2::Zero());
    rotations_.push_back(prescribed ? q.angular_velocity : 0.0);
    moving_ = moving_ || prescribed;
  }
  const CutPeriodicity periodic{params.domain.PeriodicX(), params.domain.PeriodicY()};
  geometries_.push_back(
      std::make_unique<CutCellGeometry>(grid, bodies_, CutTriangulation::kSwNe, periodic));
  if (params.domain.diagonals == MeshDiagonals::kBoth) {
    geometries_.push_back(
        std::make_unique<CutCellGeometry>(grid, bodies_, CutTriangulation::kNwSe, periodic));
  }
  fu_.assign(grid.NodeCount(), 0.0);
  fv_.assign(grid.NodeCount(), 0.0);
}

CutCellStep::~CutCellStep() = default;

bool CutCellStep::PrepareStep(double dt) {
  if (dt == dt_ && flow_) return false;
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
  return true;
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
  // In place: the saddle point refers to them (CutCellStokes::Recut).
  const CutPeriodicity periodic_axes{periodic[0], periodic[1]};
  *geometries_[0] = CutCellGeometry(grid_, bodies_, CutTriangulation::kSwNe, periodic_axes);
  if (geometries_.size() == 2)
    *geometries_[1] = CutCellGeometry(grid_, bodies_, CutTriangulation::kNwSe, periodic_axes);
}

void CutCellStep::FillBodies(double* u, double* v) const {
  const std::vector<RigidMotion> motions = Motions();
  for (std::size_t k = 0; k < grid_.NodeCount(); ++k) {
    bool active = false;
    for (const auto& geo : geometries_) active = active || geo->NodeActive(k);
    if (active) continue;
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

void CutCellStep::Solve(double dt, const BoundaryData& data, std::vector<ParticleState>& particles,
                        double* u, double* v, double* p, StepReport& report) {
  if (moving_) {
    FillBodies(u, v);  // u^n inside the bodies at X^n: the value of the nodes they uncover
    MoveBodies(dt);
  }
  const bool fresh = PrepareStep(dt);
  if (moving_) {
    if (!fresh) flow_->Recut();  // the band anew, the rest kept
    flow_->SetBodyMotion(Motions());
  }
  const Eigen::VectorXd& mass = flow_->FluidMass();
  for (std::size_t k = 0; k < fu_.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    fu_[k] = mass[i] * (rho_over_dt_ * u[k] + body_force_.x());
    fv_[k] = mass[i] * (rho_over_dt_ * v[k] + body_force_.y());
  }
  if (moving_) ExtrapolatePressure(p);
  const CutCellReport r = flow_->Solve(data, fu_.data(), fv_.data(), u, v, p,
                                       constants_.step_tolerance, constants_.step_max_iterations);
  if (moving_) FillBodies(u, v);
  report.Set("stokes_iterations", r.iterations);
  report.Set("stokes_residual", r.relative_residual);
  for (std::size_t b = 0; b < particles.size(); ++b) {
    ParticleState& s = particles[b];
    const FixedBody& body = bodies_[b];
    s.position = body.centre;
    s.angle = body.angle;
    const CutCellStokes::BodyLoad load =
        flow_->Load(static_cast<int>(b), s.position, u, v, p, fu_.data(), fv_.data());
    s.force = load.force + body.shape.Mass(fluid_density_) * buoyancy_acceleration_ +
              body.shape.Area() * body_force_;
    // The viscous form is eta grad u : grad v, whose traction on a rigid body differs from the
    // stress's in the torque by 2 eta omega V (header).
    s.torque = load.torque - 2.0 * viscosity_ * rotations_[b] * body.shape.Area();
    s.velocity = velocities_[b];
    s.angular_velocity = rotations_[b];
  }
}

}  // namespace dlmfd
