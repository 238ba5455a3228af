// Quadratic evaluation of a velocity field at a point: the 6-node P2 basis of the 2h macro-triangle
// (a triangle of the pressure mesh) that holds the point. The P1-iso-P2 velocity nodes are exactly
// the P2 nodes of the pressure triangles, so this is the P2 interpolant of the nodal values
// (particle-coupling.md section 3; Basilisk's DLMFD uses the biquadratic 3x3 stencil instead).
//
// Macro square (I, J) of side 2h has its south-west node at velocity node (2I, 2J) (domain.size / h
// is even, so the pressure nodes are the even velocity nodes); local coordinates (xi, eta) in
// [0, 1]^2 in units of 2h. Its SW-NE diagonal splits it as the h-squares are split (the four
// h-triangles of a macro-triangle are h-triangles of the velocity mesh). With barycentric
// coordinates (l0, l1, l2) of the macro-triangle, the weights are l_k (2 l_k - 1) at the vertices
// and 4 l_a l_b at the edge midpoints: T1 (xi >= eta) = (a, b, c) with l = (1 - xi, xi - eta, eta),
// T2 = (a, c, d) with l = (1 - eta, xi, eta - xi), a = (0, 0), b = (1, 0), c = (1, 1), d = (0, 1).
// P2 reproduces every polynomial of degree <= 2, so a rigid motion (linear) exactly.
// On a periodic axis the macro-square index wraps (the velocity node line 2I + 2 of the last square
// is line 0); a point on the far side of a non-periodic axis belongs to the last square at t = 1.
#pragma once

#include <cmath>

#include "dlmfd/core/grid.h"
#include "point_location.h"

namespace dlmfd::kernels {

// The 6 velocity nodes (i[q], j[q]) of the P2 stencil of a point and their weights.
struct P2Stencil {
  int i[6];
  int j[6];
  double weight[6];
};

// The velocity node line at offset k = 0, 1, 2 (in h) from node line 2c of macro cell c on an axis
// of `cells` velocity cells: 2c + k, wrapped on a periodic axis.
inline int MacroLine(int c, int k, int cells, bool periodic) {
  const int line = 2 * c + k;
  return (periodic && line >= cells) ? line - cells : line;
}

// The P2 weights of the SW-NE macro-triangle that holds local coordinates (xi, eta), on the nodes
// of the macro square at offsets (a, b) in h, a, b = 0, 1, 2 (zero at the three nodes off that
// triangle); *first tells which triangle, (a, b, c) (xi >= eta) or (a, c, d).
inline void P2WeightsOnMacroNodes(double xi, double eta, double w[3][3], bool* first) {
  // Vertices v0, v1, v2 (offsets in h) with barycentric coordinates l0, l1, l2, then the edge
  // midpoints v0v1, v1v2, v0v2.
  int vi[3], vj[3];
  double l[3];
  *first = xi >= eta;
  if (*first) {
    vi[0] = 0, vj[0] = 0, vi[1] = 2, vj[1] = 0, vi[2] = 2, vj[2] = 2;
    l[0] = 1.0 - xi, l[1] = xi - eta, l[2] = eta;
  } else {
    vi[0] = 0, vj[0] = 0, vi[1] = 2, vj[1] = 2, vi[2] = 0, vj[2] = 2;
    l[0] = 1.0 - eta, l[1] = xi, l[2] = eta - xi;
  }
  for (int b = 0; b < 3; ++b)
    for (int a = 0; a < 3; ++a) w[a][b] = 0.0;
  static constexpr int kEdge[3][2] = {{0, 1}, {1, 2}, {0, 2}};
  for (int q = 0; q < 3; ++q) {
    w[vi[q]][vj[q]] = l[q] * (2.0 * l[q] - 1.0);
    const int a = kEdge[q][0], b = kEdge[q][1];
    w[(vi[a] + vi[b]) / 2][(vj[a] + vj[b]) / 2] = 4.0 * l[a] * l[b];
  }
}

// The stencil at local coordinates (xi, eta) of macro square (ci, cj) (units of 2h): the six nodes
// of its macro-triangle, the vertices first, then the edge midpoints.
inline P2Stencil P2StencilInMacroSquare(const Grid& grid, bool periodic_x, bool periodic_y, int ci,
                                        int cj, double xi, double eta) {
  double w[3][3];
  bool first = true;
  P2WeightsOnMacroNodes(xi, eta, w, &first);
  static constexpr int kNodes[2][6][2] = {{{0, 0}, {2, 0}, {2, 2}, {1, 0}, {2, 1}, {1, 1}},
                                          {{0, 0}, {2, 2}, {0, 2}, {1, 1}, {1, 2}, {0, 1}}};
  const int(*nodes)[2] = kNodes[first ? 0 : 1];
  P2Stencil s;
  for (int q = 0; q < 6; ++q) {
    s.i[q] = MacroLine(ci, nodes[q][0], grid.nx, periodic_x);
    s.j[q] = MacroLine(cj, nodes[q][1], grid.ny, periodic_y);
    s.weight[q] = w[nodes[q][0]][nodes[q][1]];
  }
  return s;
}

// The 9 velocity nodes of the biquadratic (Q2) stencil of a point and their weights.
struct Q2Stencil {
  int i[9];
  int j[9];
  double weight[9];
};

// The 1-D quadratic Lagrange weights of the nodes at 0, 1/2, 1 at local coordinate t in [0, 1].
inline void QuadraticLagrange(double t, double w[3]) {
  w[0] = 2.0 * (t - 0.5) * (t - 1.0);
  w[1] = -4.0 * t * (t - 1.0);
  w[2] = 2.0 * t * (t - 0.5);
}

// The Q2 stencil at local coordinates (xi, eta) of macro square (ci, cj): weight L_a(xi) L_b(eta)
// at node (2 ci + a, 2 cj + b), a, b = 0, 1, 2. Q2 reproduces every polynomial of degree <= 2 in
// each variable (a rigid motion exactly), and it is symmetric under x -> -x and y -> -y, which the
// P2 basis of the SW-NE macro-triangles is not.
inline Q2Stencil Q2StencilInMacroSquare(const Grid& grid, bool periodic_x, bool periodic_y, int ci,
                                        int cj, double xi, double eta) {
  double wx[3], wy[3];
  QuadraticLagrange(xi, wx);
  QuadraticLagrange(eta, wy);
  Q2Stencil s;
  for (int b = 0; b < 3; ++b) {
    for (int a = 0; a < 3; ++a) {
      s.i[3 * b + a] = MacroLine(ci, a, grid.nx, periodic_x);
      s.j[3 * b + a] = MacroLine(cj, b, grid.ny, periodic_y);
      s.weight[3 * b + a] = wx[a] * wy[b];
    }
  }
  return s;
}

// The mean of the P2 interpolants on the SW-NE macro-triangles and on the NW-SE ones (the mirror
// image x -> -x of the former: its weight at offset (a, b) is the SW-NE weight at (2 - a, b) of the
// point (1 - xi, eta)), as a 3x3 stencil: domain.diagonals = "both" (core/params.h). It reproduces
// the polynomials of degree <= 2 as each P2 does, and it is symmetric under x -> -x and y -> -y.
inline Q2Stencil MeanP2StencilInMacroSquare(const Grid& grid, bool periodic_x, bool periodic_y,
                                            int ci, int cj, double xi, double eta) {
  double w[3][3], m[3][3];
  bool first = true;
  P2WeightsOnMacroNodes(xi, eta, w, &first);
  P2WeightsOnMacroNodes(1.0 - xi, eta, m, &first);
  Q2Stencil s;
  for (int b = 0; b < 3; ++b) {
    for (int a = 0; a < 3; ++a) {
      s.i[3 * b + a] = MacroLine(ci, a, grid.nx, periodic_x);
      s.j[3 * b + a] = MacroLine(cj, b, grid.ny, periodic_y);
      s.weight[3 * b + a] = 0.5 * (w[a][b] + m[2 - a][b]);
    }
  }
  return s;
}

// The macro square (ci, cj) and local coordinates (xi, eta) of point (x, y): true, or false when it
// lies beyond a non-periodic side, with *side that side (as LocatePoint: 0 left, 1 right, 2 bottom,
// 3 top). Requires even grid.nx and grid.ny.
inline bool LocateInMacroMesh(const Grid& grid, bool periodic_x, bool periodic_y, double x,
                              double y, int* ci, int* cj, double* xi, double* eta, int* side) {
  const double macro = 2.0 * grid.h;
  if (!LocateOnAxis((x - grid.x0) / macro, grid.nx / 2, periodic_x, ci, xi)) {
    *side = *ci < 0 ? 0 : 1;
    return false;
  }
  if (!LocateOnAxis((y - grid.y0) / macro, grid.ny / 2, periodic_y, cj, eta)) {
    *side = *cj < 0 ? 2 : 3;
    return false;
  }
  return true;
}

// Locates point (x, y) in the macro mesh: true with the stencil `build` makes of its macro square
// and local coordinates (P2StencilInMacroSquare, Q2StencilInMacroSquare); false when it lies beyond
// a non-periodic side, with *side that side.
template <class Stencil>
inline bool LocateInMacroSquare(const Grid& grid, bool periodic_x, bool periodic_y, double x,
                                double y,
                                Stencil (*build)(const Grid&, bool, bool, int, int, double, double),
                                Stencil* stencil, int* side) {
  int ci = 0, cj = 0;
  double xi = 0.0, eta = 0.0;
  if (!LocateInMacroMesh(grid, periodic_x, periodic_y, x, y, &ci, &cj, &xi, &eta, side)) {
    return false;
  }
  *stencil = build(grid, periodic_x, periodic_y, ci, cj, xi, eta);
  return true;
}

// The P2 stencil of point (x, y), as LocateInMacroSquare.
inline bool LocatePointQuadratic(const Grid& grid, bool periodic_x, bool periodic_y, double x,
                                 double y, P2Stencil* stencil, int* side) {
  return LocateInMacroSquare(grid, periodic_x, periodic_y, x, y, &P2StencilInMacroSquare, stencil,
                             side);
}

// The mean P2 stencil of point (x, y), as LocateInMacroSquare.
inline bool LocatePointMeanQuadratic(const Grid& grid, bool periodic_x, bool periodic_y, double x,
                                     double y, Q2Stencil* stencil, int* side) {
  return LocateInMacroSquare(grid, periodic_x, periodic_y, x, y, &MeanP2StencilInMacroSquare,
                             stencil, side);
}

// The Q2 stencil of point (x, y), as LocateInMacroSquare.
inline bool LocatePointBiquadratic(const Grid& grid, bool periodic_x, bool periodic_y, double x,
                                   double y, Q2Stencil* stencil, int* side) {
  return LocateInMacroSquare(grid, periodic_x, periodic_y, x, y, &Q2StencilInMacroSquare, stencil,
                             side);
}

}  // namespace dlmfd::kernels
