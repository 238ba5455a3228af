// Ring mesh of a disk and its H1 Gram matrix (24); see particles/particle_mesh.h.
#include "dlmfd/particles/particle_mesh.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "dlmfd/core/constants.h"
#include "dlmfd/core/errors.h"

namespace dlmfd {

namespace {

double SignedArea(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
}

}  // namespace

ParticleMesh::ParticleMesh(double radius, double mesh_size)
    : radius_(radius) {
  if (!(radius > 0.0))
    throw InvalidParameter("particles.diameter", std::to_string(2 * radius), "> 0");
  if (!(mesh_size > 0.0))
    throw InvalidParameter("particle_mesh.h", std::to_string(mesh_size), "> 0");
  BuildNodesAndTriangles(mesh_size);
  Assemble();
}

void ParticleMesh::BuildNodesAndTriangles(double mesh_size) {
  // 1e-9 guards R / h_p = 7.000000000000001 from giving an extra ring.
  ring_count_ = std::max(1, static_cast<int>(std::ceil(radius_ / mesh_size - 1e-9)));
  nodes_.push_back(Vec2::Zero());
  int inner_start = 0, inner_count = 1;
  double inner_offset = 0.0;
  for (int k = 1; k <= ring_count_; ++k) {
    const double r = radius_ * k / ring_count_;
    const int count = std::max(3, static_cast<int>(std::lround(2.0 * kPi * r / mesh_size)));
    const double spacing = 2.0 * kPi / count;
    const double offset = (k % 2 == 1) ? 0.5 * spacing : 0.0;
    const int start = static_cast<int>(nodes_.size());
    for (int j = 0; j < count; ++j) {
      const double angle = offset + j * spacing;
      nodes_.emplace_back(r * std::cos(angle), r * std::sin(angle));
    }
    auto add = [this](int a, int b, int c) {
      if (SignedArea(nodes_[a], nodes_[b], nodes_[c]) < 0.0) std::swap(b, c);
      triangles_.push_back({a, b, c});
    };
    if (inner_count == 1) {
      for (int j = 0; j < count; ++j) add(inner_start, start + j, start + (j + 1) % count);
    } else {
      // Merge walk in angle: the outer sequence starts at the last outer node not after the first
      // inner node, so both sequences cover one turn from (almost) the same angle.
      const double inner_spacing = 2.0 * kPi / inner_count;
      int first = static_cast<int>(std::floor((inner_offset - offset) / spacing));
      const double outer_start = offset + first * spacing;
      first = ((first % count) + count) % count;
      int i = 0, j = 0;
      while (i < inner_count || j < count) {
        const double next_inner = inner_offset + (i + 1) * inner_spacing;
        const double next_outer = outer_start + (j + 1) * spacing;
        const int ai = inner_start + i % inner_count;
        const int bj = start + (first + j) % count;
        if (j == count || (i < inner_count && next_inner <= next_outer)) {
          add(ai, inner_start + (i + 1) % inner_count, bj);
          ++i;
        } else {
          add(ai, bj, start + (first + j + 1) % count);
          ++j;
        }
      }
    }
    inner_start = start;
    inner_count = count;
    inner_offset = offset;
  }
}

void ParticleMesh::Assemble() {
  const int n = NodeCount();
  std::vector<Eigen::Triplet<double>> m, s;
  m.reserve(9 * triangles_.size());
  s.reserve(9 * triangles_.size());
  for (const auto& t : triangles_) {
    const Vec2& p0 = nodes_[t[0]];
    const Vec2& p1 = nodes_[t[1]];
    const Vec2& p2 = nodes_[t[2]];
    const double area = SignedArea(p0, p1, p2);
    // Gradients of the barycentric functions: grad phi_a = perp(p_c - p_b) / (2 area).
    Vec2 grad[3];
    const Vec2* p[3] = {&p0, &p1, &p2};
    for (int a = 0; a < 3; ++a) {
      const Vec2 e = *p[(a + 2) % 3] - *p[(a + 1) % 3];
      grad[a] = Vec2(-e.y(), e.x()) / (2.0 * area);
    }
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        m.emplace_back(t[a], t[b], area / 12.0 * (a == b ? 2.0 : 1.0));
        s.emplace_back(t[a], t[b], area * grad[a].dot(grad[b]));
      }
    }
  }
  mass_.resize(n, n);
  mass_.setFromTriplets(m.begin(), m.end());
  stiffness_.resize(n, n);
  stiffness_.setFromTriplets(s.begin(), s.end());
  gram_ = mass_ + radius_ * radius_ * stiffness_;
  gram_.makeCompressed();
}

double ParticleMesh::Area() const {
  double area = 0.0;
  for (const auto& t : triangles_) area += SignedArea(nodes_[t[0]], nodes_[t[1]], nodes_[t[2]]);
  return area;
}

void ParticleMesh::ApplyGram(const double* in, double* out) const {
  const int* outer = gram_.outerIndexPtr();
  const int* inner = gram_.innerIndexPtr();
  const double* value = gram_.valuePtr();
  for (int row = 0; row < gram_.rows(); ++row) {
    double sum = 0.0;
    for (int q = outer[row]; q < outer[row + 1]; ++q) sum += value[q] * in[inner[q]];
    out[row] = sum;
  }
}

void ParticleMesh::ApplyGram2(const double* in, double* out) const {
  const int* outer = gram_.outerIndexPtr();
  const int* inner = gram_.innerIndexPtr();
  const double* value = gram_.valuePtr();
  for (int row = 0; row < gram_.rows(); ++row) {
    double sx = 0.0, sy = 0.0;
    for (int q = outer[row]; q < outer[row + 1]; ++q) {
      sx += value[q] * in[2 * inner[q]];
      sy += value[q] * in[2 * inner[q] + 1];
    }
    out[2 * row] = sx;
    out[2 * row + 1] = sy;
  }
}

double ParticleMesh::GramDot2(const double* a, const double* b, double* scratch) const {
  ApplyGram2(b, scratch);
  double sum = 0.0;
  for (int q = 0; q < 2 * NodeCount(); ++q) sum += a[q] * scratch[q];
  return sum;
}

}  // namespace dlmfd
