// The rigid modes of the multiplier points and the neutral-particle projector; see
// particles/rigid_modes.h.
#include "dlmfd/particles/rigid_modes.h"

#include <Eigen/LU>

namespace dlmfd {

RigidModes::RigidModes(const MultiplierPoints& points, const std::vector<Body>& bodies) {
  for (const Body& body : bodies) {
    inv_excess_mass_.push_back(body.inv_excess_mass);
    inv_excess_inertia_.push_back(body.inv_excess_inertia);
    neutral_.push_back(body.neutral ? 1 : 0);
    any_neutral_ = any_neutral_ || body.neutral;
  }
  gram_rigid_.resize(points.SetCount());
  rigid_gram_inverse_.resize(points.SetCount());
  for (std::size_t m = 0; m < points.SetCount(); ++m) BuildSet(points, m);
}

void RigidModes::BuildSet(const MultiplierPoints& points, std::size_t m) {
  const std::vector<Vec2>& nodes = points.SetPoints(m);
  const int count = points.SetCount(m);
  const std::size_t size = 2 * static_cast<std::size_t>(count);
  std::vector<double> mode(size);
  std::vector<double>& gc = gram_rigid_[m];
  gc.assign(3 * size, 0.0);
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < count; ++k) {
      const Vec2 r = nodes[k];
      const Vec2 e = c == 0 ? Vec2(1.0, 0.0) : (c == 1 ? Vec2(0.0, 1.0) : Perp(r));
      mode[2 * k] = e.x();
      mode[2 * k + 1] = e.y();
    }
    points.ApplySetProduct(m, mode.data(), gc.data() + c * size);
  }
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();  // C^T G C, column a = C^T (G C)_a
  for (int a = 0; a < 3; ++a) {
    for (int k = 0; k < count; ++k) {
      const Vec2 gc_k(gc[a * size + 2 * k], gc[a * size + 2 * k + 1]);
      s(0, a) += gc_k.x();
      s(1, a) += gc_k.y();
      s(2, a) += Perp(nodes[k]).dot(gc_k);
    }
  }
  rigid_gram_inverse_[m] = (0.5 * (s + s.transpose())).inverse();
}

Eigen::Vector3d RigidModes::RigidPart(const MultiplierPoints& points, std::size_t p,
                                      const double* a) const {
  const std::size_t size = 2 * static_cast<std::size_t>(points.Count(p));
  const double* gc = gram_rigid_[points.SetIndex(p)].data();
  Eigen::Vector3d moments;
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (std::size_t q = 0; q < size; ++q) sum += gc[c * size + q] * a[q];
    moments[c] = sum;
  }
  return rigid_gram_inverse_[points.SetIndex(p)] * moments;
}

void RigidModes::ProjectMismatchOf(const MultiplierPoints& points, std::size_t p, double* a) const {
  const Eigen::Vector3d rigid = RigidPart(points, p, a);
  const std::vector<Vec2>& r = points.Points(p);
  for (int k = 0; k < points.Count(p); ++k) {
    const Vec2 motion = Vec2(rigid[0], rigid[1]) + rigid[2] * Perp(r[k]);
    a[2 * k] -= motion.x();
    a[2 * k + 1] -= motion.y();
  }
}

void RigidModes::ProjectMismatch(const MultiplierPoints& points, double* a) const {
  if (!any_neutral_) return;
  for (std::size_t p = 0; p < points.ParticleCount(); ++p) {
    if (neutral_[p]) ProjectMismatchOf(points, p, a + 2 * points.Begin(p));
  }
}

void RigidModes::ProjectForcesOf(const MultiplierPoints& points, std::size_t p, double* f) const {
  const std::size_t size = 2 * static_cast<std::size_t>(points.Count(p));
  const std::vector<Vec2>& r = points.Points(p);
  Eigen::Vector3d moments = Eigen::Vector3d::Zero();  // C^T f
  for (int k = 0; k < points.Count(p); ++k) {
    const Vec2 force(f[2 * k], f[2 * k + 1]);
    moments += Eigen::Vector3d(force.x(), force.y(), Perp(r[k]).dot(force));
  }
  const Eigen::Vector3d t = rigid_gram_inverse_[points.SetIndex(p)] * moments;
  const double* gc = gram_rigid_[points.SetIndex(p)].data();
  for (std::size_t q = 0; q < size; ++q) {
    f[q] -= gc[q] * t[0] + gc[size + q] * t[1] + gc[2 * size + q] * t[2];
  }
}

void RigidModes::ProjectForces(const MultiplierPoints& points, double* f) const {
  if (!any_neutral_) return;
  for (std::size_t p = 0; p < points.ParticleCount(); ++p) {
    if (neutral_[p]) ProjectForcesOf(points, p, f + 2 * points.Begin(p));
  }
}

void RigidModes::ParticularForces(const MultiplierPoints& points, std::size_t p,
                                  const Vec2& net_force, double net_torque, double* f) const {
  const Eigen::Vector3d t = rigid_gram_inverse_[points.SetIndex(p)] *
                            Eigen::Vector3d(net_force.x(), net_force.y(), net_torque);
  const std::size_t size = 2 * static_cast<std::size_t>(points.Count(p));
  const double* gc = gram_rigid_[points.SetIndex(p)].data();
  for (std::size_t q = 0; q < size; ++q) {
    f[q] = gc[q] * t[0] + gc[size + q] * t[1] + gc[2 * size + q] * t[2];
  }
}

}  // namespace dlmfd
