// The multiplier mesh of one disk (method notes 2, section 1.1) and its H1 Gram matrix (24).
//
// Equations: <mu, lambda>_P = int_P (mu . lambda + R^2 grad mu : grad lambda) dx, paper (24).
// Discrete method: a centre node plus n_r = ceil(R / h_p) rings at r_k = k R / n_r, ring k holding
// round(2 pi r_k / h_p) nodes (at least 3; every other ring shifted by half a spacing), so the
// boundary nodes lie on the circle. Rings are triangulated ring to ring by a merge walk in angle
// (no Delaunay). On this mesh the P1 consistent mass M_p and stiffness K_p give G = M_p + R^2 K_p,
// per velocity component. Nodes are stored relative to the centre; the mesh translates with the
// particle and does not rotate (disks need no orientation).
// Solver: none (G is applied, never inverted). Not supported: non-circular particles.
// References: Glowinski, Pan, Hesla, Joseph, Periaux, J. Comput. Phys. 169 (2001) 363-426, and
// method notes 2, section 1.1 (R = 0.1, h_p = 1/70 gives 7 rings and 177 nodes).
#pragma once

#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "dlmfd/core/params.h"

namespace dlmfd {

class ParticleMesh {
 public:
  // Throws InvalidParameter when radius or mesh_size is not > 0.
  ParticleMesh(double radius, double mesh_size);

  double radius() const { return radius_; }
  int NodeCount() const { return static_cast<int>(nodes_.size()); }
  int RingCount() const { return ring_count_; }
  // Node positions relative to the centre.
  const std::vector<Vec2>& nodes() const { return nodes_; }
  const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }
  // Sum of the triangle areas (the inscribed polygon: pi R^2 up to O(h_p^2)).
  double Area() const;

  // out = G in for one scalar field on the nodes (G = M_p + R^2 K_p).
  void ApplyGram(const double* in, double* out) const;
  // out = G in for a two-component field stored node by node (x0, y0, x1, y1, ...).
  void ApplyGram2(const double* in, double* out) const;
  // <a, b>_G for two-component fields stored node by node.
  double GramDot2(const double* a, const double* b, double* scratch) const;

  // Assembled matrices, for tests.
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& Mass() const { return mass_; }
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& Stiffness() const { return stiffness_; }
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& Gram() const { return gram_; }

 private:
  void BuildNodesAndTriangles(double mesh_size);
  void Assemble();

  double radius_;
  int ring_count_ = 0;
  std::vector<Vec2> nodes_;
  std::vector<std::array<int, 3>> triangles_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> mass_, stiffness_, gram_;
};

}  // namespace dlmfd
