// Newton's law of free bodies cut out of the mesh; see particles/cut_cell_free_bodies.h.
#include "dlmfd/particles/cut_cell_free_bodies.h"

#include <cmath>

#include <Eigen/LU>

#include "dlmfd/particles/shape.h"

namespace dlmfd {
namespace {

// The scene's sides with every Dirichlet side's data zero (a wall): the unit solves' data.
DomainParams Homogeneous(DomainParams domain) {
  for (BoundarySide& side : domain.sides) {
    if (side.type == SideType::kVelocity) side = BoundarySide{};
  }
  return domain;
}

std::vector<double> Radii(const Params& params) {
  std::vector<double> radii;
  for (const ParticleParams& q : params.particles) radii.push_back(q.Radius());
  return radii;
}

}  // namespace

CutCellFreeBodies::CutCellFreeBodies(const Params& params, const Grid& grid)
    : grid_(grid),
      viscosity_(params.fluid.ImplicitViscosity(grid.h)),
      gravity_(params.gravity),
      homogeneous_(grid, Homogeneous(params.domain)),
      collisions_(params, grid, Radii(params)),
      refresh_(params.particle_mesh.rigid_modes_refresh),
      periodic_x_(params.domain.PeriodicX()),
      periodic_y_(params.domain.PeriodicY()) {
  for (std::size_t b = 0; b < params.particles.size(); ++b) {
    const ParticleParams& q = params.particles[b];
    const Shape shape = Shape::Of(q);
    const bool free = q.motion == Motion::kFree;
    is_free_.push_back(free ? 1 : 0);
    if (free) free_.push_back(b);
    mass_.push_back(shape.Mass(q.density));
    inertia_.push_back(shape.MomentOfInertia(q.density));
    area_.push_back(shape.Area());
  }
  const std::size_t units = 3 * free_.size();
  unit_u_.assign(units, std::vector<double>(grid.NodeCount(), 0.0));
  unit_v_.assign(units, std::vector<double>(grid.NodeCount(), 0.0));
  unit_p_.assign(units, std::vector<double>(grid.Coarse().NodeCount(), 0.0));
  positions_.resize(params.particles.size());
  contact_forces_.resize(params.particles.size());
  last_contact_forces_.assign(params.particles.size(), Vec2::Zero());
}

bool CutCellFreeBodies::NeedsK(double dt, const std::vector<FixedBody>& bodies) const {
  if (refresh_ <= 0.0 || k_.size() == 0 || dt != k_dt_ || k_centres_.size() != bodies.size())
    return true;
  const double reach = refresh_ * grid_.h;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    Vec2 moved = bodies[b].centre - k_centres_[b];  // across a periodic seam: the shortest way
    if (periodic_x_) moved.x() -= grid_.Width() * std::round(moved.x() / grid_.Width());
    if (periodic_y_) moved.y() -= grid_.Height() * std::round(moved.y() / grid_.Height());
    if (moved.norm() > reach) return true;
    const Shape& shape = bodies[b].shape;
    if (shape.TurnsWithAngle() &&
        std::abs(bodies[b].angle - k_angles_[b]) * shape.BoundingRadius() > reach)
      return true;
  }
  return false;
}

int CutCellFreeBodies::ContactForces(const std::vector<FixedBody>& bodies) {
  for (std::size_t b = 0; b < bodies.size(); ++b) positions_[b] = bodies[b].centre;
  return collisions_.Compute(positions_, contact_forces_);
}

Eigen::MatrixXd CutCellFreeBodies::NewtonMatrix(double dt) const {
  Eigen::MatrixXd a = -k_;
  for (std::size_t c = 0; c < free_.size(); ++c) {
    const std::size_t b = free_[c];
    const auto r = static_cast<Eigen::Index>(3 * c);
    a(r, r) += mass_[b] / dt;
    a(r + 1, r + 1) += mass_[b] / dt;
    a(r + 2, r + 2) += inertia_[b] / dt;
  }
  return a;
}

// Newton's law over the step with the load F_h^n + K (V* - V^n): the last step's, the kept K
// and the collision forces at X^{n+1} (header).
void CutCellFreeBodies::Predict(double dt, const std::vector<FixedBody>& bodies, const Loads& last,
                                std::vector<RigidMotion>& motions) {
  contacts_ = ContactForces(bodies);  // at X^{n+1}: Couple's too
  has_last_ = false;
  if (k_.size() == 0 || dt != k_dt_) return;  // no K of this dt yet: V* = V^n
  last_ = last;
  has_last_ = true;
  // D, the last step's change of the load at a fixed motion, left out while a body is in contact
  // (now or in the last step).
  bool touching = contacts_ > 0;
  for (const std::size_t b : free_) touching = touching || last_contact_forces_[b].norm() > 0.0;
  const bool with_change = has_change_ && !touching;
  const std::size_t nf = free_.size();
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(3 * nf));
  for (std::size_t c = 0; c < nf; ++c) {
    const std::size_t b = free_[c];
    const auto r = static_cast<Eigen::Index>(3 * c);
    const Vec2 f = last.force[b] + mass_[b] * gravity_ + contact_forces_[b];
    rhs[r] = f.x();
    rhs[r + 1] = f.y();
    rhs[r + 2] = last.torque[b];
  }
  if (with_change) rhs += change_;
  const Eigen::VectorXd dv = NewtonMatrix(dt).partialPivLu().solve(rhs);
  for (std::size_t c = 0; c < nf; ++c) {
    const std::size_t b = free_[c];
    const auto r = static_cast<Eigen::Index>(3 * c);
    motions[b].velocity += Vec2(dv[r], dv[r + 1]);
    motions[b].angular_velocity += dv[r + 2];
  }
}

double CutCellFreeBodies::PairGap(const std::vector<FixedBody>& bodies) {
  for (std::size_t b = 0; b < bodies.size(); ++b) positions_[b] = bodies[b].centre;
  return collisions_.Gaps(positions_).pair;
}

// K: the force and torque on every free body of each unit motion (the bodies at `motions`' centres,
// which the flow is left at).
void CutCellFreeBodies::MakeK(CutCellStokes& flow, const std::vector<FixedBody>& bodies,
                              const std::vector<RigidMotion>& motions, double tolerance,
                              int max_iterations, Outcome& outcome) {
  const std::size_t nf = free_.size(), units = 3 * nf;
  k_ = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(units), static_cast<Eigen::Index>(units));
  for (std::size_t s = 0; s < units; ++s) {
    const std::size_t body = free_[s / 3];
    const int mode = static_cast<int>(s % 3);  // 0: U_x, 1: U_y, 2: omega
    std::vector<RigidMotion> unit = motions;
    for (RigidMotion& m : unit) {
      m.velocity = Vec2::Zero();
      m.angular_velocity = 0.0;
    }
    if (mode < 2) {
      unit[body].velocity[mode] = 1.0;
    } else {
      unit[body].angular_velocity = 1.0;
    }
    flow.SetBodyMotion(unit);
    outcome.unit_iterations +=
        flow.Solve(homogeneous_, nullptr, nullptr, unit_u_[s].data(), unit_v_[s].data(),
                   unit_p_[s].data(), tolerance, max_iterations)
            .iterations;
    for (std::size_t c = 0; c < nf; ++c) {
      const CutCellStokes::BodyLoad load =
          flow.Load(static_cast<int>(free_[c]), bodies[free_[c]].centre, unit_u_[s].data(),
                    unit_v_[s].data(), unit_p_[s].data(), nullptr, nullptr);
      const auto col = static_cast<Eigen::Index>(s);
      k_(static_cast<Eigen::Index>(3 * c), col) = load.force.x();
      k_(static_cast<Eigen::Index>(3 * c + 1), col) = load.force.y();
      k_(static_cast<Eigen::Index>(3 * c + 2), col) = load.torque;
    }
  }
  for (std::size_t c = 0; c < nf; ++c) {  // the stress's torque of a turning body
    const auto r = static_cast<Eigen::Index>(3 * c + 2);
    k_(r, r) -= 2.0 * viscosity_ * area_[free_[c]];
  }
  flow.SetBodyMotion(motions);
}

CutCellFreeBodies::Outcome CutCellFreeBodies::Couple(
    CutCellStokes& flow, double dt, const std::vector<FixedBody>& bodies, const Loads& first,
    const std::vector<RigidMotion>& now, std::vector<RigidMotion>& motions, double* u, double* v,
    double* p, double tolerance, double unit_tolerance, int max_iterations) {
  Outcome outcome;
  const std::size_t nf = free_.size(), units = 3 * nf;
  const bool made = NeedsK(dt, bodies);
  // With a prediction from a kept K (has_last_) the step's solution is a solve at V started from
  // the composition below, so the unit solves need K's accuracy only (header).
  const bool loose = made && has_last_;
  if (made) {
    k_dt_ = dt;
    k_centres_.clear();
    k_angles_.clear();
    for (const FixedBody& body : bodies) {
      k_centres_.push_back(body.centre);
      k_angles_.push_back(body.angle);
    }
    MakeK(flow, bodies, motions, loose ? unit_tolerance : tolerance, max_iterations, outcome);
  }
  outcome.made = made;
  outcome.composed = made && !loose;
  // The collision forces at X^{n+1} (Predict's);
  // (M / dt - K) (V - V*) = F_h(V*) + M g + F' + M (V^n - V*) / dt.
  outcome.contacts = contacts_;
  const Eigen::MatrixXd a = NewtonMatrix(dt);
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(units));
  for (std::size_t c = 0; c < nf; ++c) {
    const std::size_t b = free_[c];
    const auto r = static_cast<Eigen::Index>(3 * c);
    const Vec2 f = first.force[b] + mass_[b] * gravity_ + contact_forces_[b] +
                   (mass_[b] / dt) * (now[b].velocity - motions[b].velocity);
    rhs[r] = f.x();
    rhs[r + 1] = f.y();
    rhs[r + 2] = first.torque[b] +
                 (inertia_[b] / dt) * (now[b].angular_velocity - motions[b].angular_velocity);
  }
  last_contact_forces_ = contact_forces_;
  const Eigen::VectorXd dv = a.partialPivLu().solve(rhs);
  // D = F_h(V*) - F_h^n - K (V* - V^n): the change of the load at a fixed motion over the step.
  has_change_ = has_last_;
  if (has_last_) {
    Eigen::VectorXd dstar(static_cast<Eigen::Index>(units));
    for (std::size_t c = 0; c < nf; ++c) {
      const std::size_t b = free_[c];
      const auto r = static_cast<Eigen::Index>(3 * c);
      dstar[r] = motions[b].velocity.x() - now[b].velocity.x();
      dstar[r + 1] = motions[b].velocity.y() - now[b].velocity.y();
      dstar[r + 2] = motions[b].angular_velocity - now[b].angular_velocity;
    }
    change_ = -(k_ * dstar);
    for (std::size_t c = 0; c < nf; ++c) {
      const std::size_t b = free_[c];
      const auto r = static_cast<Eigen::Index>(3 * c);
      change_[r] += first.force[b].x() - last_.force[b].x();
      change_[r + 1] += first.force[b].y() - last_.force[b].y();
      change_[r + 2] += first.torque[b] - last_.torque[b];
    }
  }
  has_last_ = false;
  // The first solve's plus the unit solves' times V - V*: with K made at the step's tolerance the
  // step's solution, else the start of the step's solve at V, from this step's unit solutions or,
  // K kept, from the last K's (made within refresh_ h of here; across a periodic seam the fields
  // lie about the body too, the box's arrays being periodic).
  const std::size_t n = grid_.NodeCount(), np = grid_.Coarse().NodeCount();
  for (std::size_t s = 0; s < units; ++s) {
    const double w = dv[static_cast<Eigen::Index>(s)];
    for (std::size_t i = 0; i < n; ++i) {
      u[i] += w * unit_u_[s][i];
      v[i] += w * unit_v_[s][i];
    }
    for (std::size_t i = 0; i < np; ++i) p[i] += w * unit_p_[s][i];
  }
  for (std::size_t c = 0; c < nf; ++c) {
    const std::size_t b = free_[c];
    const auto r = static_cast<Eigen::Index>(3 * c);
    motions[b].velocity += Vec2(dv[r], dv[r + 1]);
    motions[b].angular_velocity += dv[r + 2];
  }
  return outcome;
}

}  // namespace dlmfd
