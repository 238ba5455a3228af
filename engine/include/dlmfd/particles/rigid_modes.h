// The rigid modes of the multiplier points and the particle side of the DLM step (37): the rigid
// motion C (U, omega) at the points, its transpose (the net force and torque of nodal forces), the
// excess-mass response, and the projector of neutrally buoyant particles.
//
// C = [e_x, e_y, r_perp] at the points of a particle (r_perp = (-r_y, r_x), r relative to the
// centre), so C (U, omega) = U + omega r_perp and C^T nu = (sum_k nu_k, sum_k r_perp_k . nu_k).
// Particle side of (37): m_e (U - U*)/dt = -sum_k nu_k, j_e (omega - omega*)/dt = -sum_k r_perp_k .
// nu_k with m_e = (rho_d - rho_L) pi R^2, j_e = m_e R^2 / 2, so a force increment nu gives the
// response -dt D^-1 C^T nu, D = diag(m_e, m_e, j_e); D^-1 = 0 for fixed, prescribed and neutral
// particles (their motion is not moved by the forces).
// Neutrally buoyant free particles (rho_d = rho_L): the momentum equations become C^T nu = f
// (method notes in particles/rigid_body_constraint.h), solved with the G-orthogonal projector
// P = I - C S^-1 C^T G, S = C^T G C (3x3 per point set, constant while the points translate;
// rebuilt when an ellipse's points turn). Here: S^-1 and G C per point set, the G-weighted rigid
// part S^-1 (G C)^T a of a nodal field, P on mismatches (a -= C S^-1 (G C)^T a), its transpose on
// forces (f -= G C S^-1 C^T f) and the particular forces G C S^-1 (F, T) whose net force is F and
// net torque T (a disk's collisions have T = 0). Not supported: free particles lighter than the
// liquid (RigidBodyConstraint rejects them).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "dlmfd/core/params.h"
#include "dlmfd/particles/multiplier_points.h"

namespace dlmfd {

class RigidModes {
 public:
  // What the particle side of (37) needs of particle p: D^-1 (zeros when its motion is not moved by
  // the forces) and whether it is neutral (free with rho_d = rho_L).
  struct Body {
    double inv_excess_mass = 0.0;
    double inv_excess_inertia = 0.0;
    bool neutral = false;
  };

  // r_perp = e_z x r.
  static Vec2 Perp(const Vec2& r) { return Vec2(-r.y(), r.x()); }

  RigidModes() = default;
  // bodies[p] for every particle of points.
  RigidModes(const MultiplierPoints& points, const std::vector<Body>& bodies);

  // G C and S^-1 of point set m again, after its points turned (MultiplierPoints::Turn).
  void Refresh(const MultiplierPoints& points, std::size_t m) { BuildSet(points, m); }

  bool IsNeutral(std::size_t p) const { return neutral_[p] != 0; }
  // D^-1 of particle p (zeros when its motion is not moved by the forces).
  double InverseExcessMass(std::size_t p) const { return inv_excess_mass_[p]; }
  double InverseExcessInertia(std::size_t p) const { return inv_excess_inertia_[p]; }
  bool AnyNeutral() const { return any_neutral_; }

  // (sum, torque) = C^T f for the nodal forces f of particle p (f: its block).
  void NetForceAndTorque(const MultiplierPoints& points, std::size_t p, const double* f, Vec2& sum,
                         double& torque) const {
    const std::vector<Vec2>& r = points.Points(p);
    Vec2 s = Vec2::Zero();
    double t = 0.0;
    for (int k = 0; k < points.Count(p); ++k) {
      const Vec2 force(f[2 * k], f[2 * k + 1]);
      s += force;
      t += Perp(r[k]).dot(force);
    }
    sum = s;
    torque = t;
  }
  // (velocity, omega) = -dt D^-1 C^T f: the rigid response of particle p to nodal forces f.
  void Response(const MultiplierPoints& points, std::size_t p, double dt, const double* f,
                Vec2& velocity, double& omega) const {
    Vec2 sum;
    double torque;
    NetForceAndTorque(points, p, f, sum, torque);
    velocity = -dt * inv_excess_mass_[p] * sum;
    omega = -dt * inv_excess_inertia_[p] * torque;
  }

  // (U, omega) = S^-1 (G C)^T a: the G-weighted rigid part of a nodal field a of particle p.
  Eigen::Vector3d RigidPart(const MultiplierPoints& points, std::size_t p, const double* a) const;
  // a -= C RigidPart(a) for particle p (a: its block), and P a on every neutral particle (a:
  // stacked).
  void ProjectMismatchOf(const MultiplierPoints& points, std::size_t p, double* a) const;
  void ProjectMismatch(const MultiplierPoints& points, double* a) const;
  // f -= G C S^-1 C^T f for particle p (f: its block), and on every neutral particle (stacked).
  void ProjectForcesOf(const MultiplierPoints& points, std::size_t p, double* f) const;
  void ProjectForces(const MultiplierPoints& points, double* f) const;
  // f = G C S^-1 (net_force, net_torque) on the block of particle p: C^T f = (net_force,
  // net_torque).
  void ParticularForces(const MultiplierPoints& points, std::size_t p, const Vec2& net_force,
                        double net_torque, double* f) const;

 private:
  void BuildSet(const MultiplierPoints& points, std::size_t m);

  std::vector<double> inv_excess_mass_, inv_excess_inertia_;  // per particle: D^-1
  std::vector<char> neutral_;
  bool any_neutral_ = false;
  std::vector<std::vector<double>> gram_rigid_;  // per point set: G C, column c at [c * 2 N + q]
  std::vector<Eigen::Matrix3d> rigid_gram_inverse_;  // per point set: S^-1
};

}  // namespace dlmfd
