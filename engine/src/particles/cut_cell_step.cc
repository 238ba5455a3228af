// Step (33) with fixed bodies cut out of the mesh; see particles/cut_cell_step.h.
#include "dlmfd/particles/cut_cell_step.h"

#include "dlmfd/particles/particle_rules.h"
#include "dlmfd/particles/shape.h"

namespace dlmfd {

CutCellStep::CutCellStep(const Params& params, const Grid& grid)
    : domain_(params.domain),
      viscosity_(params.fluid.ImplicitViscosity(grid.h)),
      body_force_(params.fluid.body_force),
      buoyancy_acceleration_(-params.gravity),
      fluid_density_(params.fluid.density) {
  RequireCutCellScene(params);
  for (const ParticleParams& q : params.particles)
    bodies_.push_back({Shape::Of(q), q.center, q.angle});
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

void CutCellStep::PrepareStep(double dt) {
  if (dt == dt_) return;
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

void CutCellStep::Solve(double dt, const BoundaryData& data, std::vector<ParticleState>& particles,
                        double* u, double* v, double* p, StepReport& report) {
  PrepareStep(dt);
  const Eigen::VectorXd& mass = flow_->FluidMass();
  for (std::size_t k = 0; k < fu_.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    fu_[k] = mass[i] * (rho_over_dt_ * u[k] + body_force_.x());
    fv_[k] = mass[i] * (rho_over_dt_ * v[k] + body_force_.y());
  }
  const CutCellReport r = flow_->Solve(data, fu_.data(), fv_.data(), u, v, p,
                                       constants_.step_tolerance, constants_.step_max_iterations);
  report.Set("stokes_iterations", r.iterations);
  report.Set("stokes_residual", r.relative_residual);
  for (std::size_t b = 0; b < particles.size(); ++b) {
    ParticleState& s = particles[b];
    const CutCellStokes::BodyLoad load =
        flow_->Load(static_cast<int>(b), s.position, u, v, p, fu_.data(), fv_.data());
    const Shape& shape = bodies_[b].shape;
    s.force = load.force + shape.Mass(fluid_density_) * buoyancy_acceleration_ +
              shape.Area() * body_force_;
    s.torque = load.torque;
    s.velocity = Vec2::Zero();
    s.angular_velocity = 0.0;
  }
}

}  // namespace dlmfd
