// Matrix-free finite-element operators of the P1-iso-P2 / P1 pair on the uniform SW-NE mesh
// (paper section 3; method notes 1, section 1). Every function reads and writes full node arrays
// (Grid::NodeCount() values, x fastest) and returns a value at every node (rows of the full
// Galerkin matrix, natural boundary rows included); callers ignore the rows of Dirichlet nodes.
// Element-wise assembly is used where boundary data matter (B, B^T, G), so non-zero Dirichlet data
// are right. Periodic topologies wrap the stencils and fold the repeated node into the first.
//
// Scales: M ~ h^2, G and B ~ h, K scale-free.
// Lumped mass: the trapezoid rule h^2 Dx (x) Dy (1/2 on edges, 1/4 on non-periodic corners). It
// equals the row-sum lumped P1 mass except at corners (|T|/3 per triangle gives 1/3 or 1/6 there);
// the separable form is what makes (a M + b K) diagonalisable by transforms in x.
#pragma once

#include <Eigen/SparseCore>

#include "dlmfd/core/grid.h"
#include "dlmfd/mesh/boundary_topology.h"

namespace dlmfd {

// out = M_l f.
void ApplyLumpedMass(const Grid& grid, const BoundaryTopology& topo, const double* f, double* out);
// The diagonal of M_l as a node array (periodic duplicates carry their first node's value, so the
// array can divide; ApplyLumpedMass, like every Apply*, gives their rows zero).
void LumpedMassDiagonal(const Grid& grid, const BoundaryTopology& topo, double* out);
// out = K u, K_ij = int grad phi_i . grad phi_j (5-point Laplacian in the interior).
void ApplyStiffness(const Grid& grid, const BoundaryTopology& topo, const double* u, double* out);
// The next three integrate on the SW-NE mesh, or with MeshDiagonals::kBoth give the mean of that
// and the same form on the NW-SE mesh (domain.diagonals), gathered in one sweep over the nodes
// (src/mesh/grid_kernels.h, Diagonal): twice the arithmetic, one pass over the arguments. M and K
// are the same on both meshes (the trapezoid lumping; the 5-point Laplacian). gx = G_x f, gy = G_y
// f with (G_x f)_i = int phi_i d_x f_h (P1-P1 on the h-mesh).
void ApplyIntegratedGradient(const Grid& grid, const BoundaryTopology& topo, const double* f,
                             double* gx, double* gy,
                             MeshDiagonals diagonals = MeshDiagonals::kSwNe);
// out (pressure nodes, grid.Coarse()) = B (u, v), (B v)_Q = int q_Q div v_h.
void ApplyDivergence(const Grid& grid, const BoundaryTopology& pressure_topo, const double* u,
                     const double* v, double* out, MeshDiagonals diagonals = MeshDiagonals::kSwNe);
// (out_u, out_v) (velocity nodes) = B^T p, (B^T p)_i = int p_h div phi_i (per component).
void ApplyDivergenceTranspose(const Grid& grid, const BoundaryTopology& pressure_topo,
                              const double* p, double* out_u, double* out_v,
                              MeshDiagonals diagonals = MeshDiagonals::kSwNe);

// Assembled reference matrices over all nodes of the grid (periodic duplicates folded into the
// first node; the duplicate rows and columns are empty). For tests and small problems only. G and B
// on either triangulation's triangles, or their mean (MeshDiagonals::kBoth).
Eigen::SparseMatrix<double> AssembleConsistentMass(const Grid& grid, const BoundaryTopology& topo);
Eigen::SparseMatrix<double> AssembleStiffness(const Grid& grid, const BoundaryTopology& topo);
Eigen::SparseMatrix<double> AssembleGradientX(const Grid& grid, const BoundaryTopology& topo,
                                              MeshDiagonals diagonals = MeshDiagonals::kSwNe);
Eigen::SparseMatrix<double> AssembleGradientY(const Grid& grid, const BoundaryTopology& topo,
                                              MeshDiagonals diagonals = MeshDiagonals::kSwNe);
// B_x, B_y: (pressure nodes) x (velocity nodes).
Eigen::SparseMatrix<double> AssembleDivergenceX(const Grid& grid,
                                                const BoundaryTopology& pressure_topo,
                                                MeshDiagonals diagonals = MeshDiagonals::kSwNe);
Eigen::SparseMatrix<double> AssembleDivergenceY(const Grid& grid,
                                                const BoundaryTopology& pressure_topo,
                                                MeshDiagonals diagonals = MeshDiagonals::kSwNe);

}  // namespace dlmfd
