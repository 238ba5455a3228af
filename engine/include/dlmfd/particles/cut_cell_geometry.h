// The cut elements of the uniform SW-NE mesh around fixed rigid bodies: the geometry that the
// cut-cell boundary (particles/cut_cell_stokes.h; issue 33) integrates on.
//
// Every velocity node x_i carries the signed distance phi_i = min_b d_b(x_i) to the bodies (d_b
// from the body's Shape in its frame: negative inside; values within 1e-9 h of zero are set to 0,
// a node on the boundary). The boundary is the zero line of the P1 interpolant of phi: in each
// h-triangle a chord, so the discrete body differs from the true one by O(h^2) in position, area
// and length. An h-triangle is
//   fluid  when phi >= 0 at its three vertices,
//   cut    when phi > 0 at one vertex at least and phi < 0 at another, or when phi = 0 at two
//          vertices and phi > 0 at the third (its edge is a piece of the boundary: without it
//          Nitsche's terms would miss that piece; a disk of radius 5h centred on a node has two),
//   solid  otherwise (a triangle that only touches the boundary is solid).
// A cut triangle keeps its fluid polygon (phi >= 0 part): area, centroid, the exact P1 mass matrix
// over it (edge-midpoint rule on a fan: exact for quadratics), and its chord with the unit normal
// pointing out of the fluid (into the body). A velocity node is active when it is a vertex of a
// fluid or cut triangle; the others carry no unknown. The pressure's 2h macro-triangles (each the
// union of four h-triangles of the same diagonal side) are active when they hold an active
// h-triangle and touched when they hold a cut one.
//
// Triangle numbering: square (i, j) holds triangles 2 (j nx + i) and 2 (j nx + i) + 1; on the
// SW-NE triangulation (the paper's) the lower (i, j), (i+1, j), (i+1, j+1) and the upper (i, j),
// (i+1, j+1), (i, j+1); on its mirror image, NW-SE, the lower-left (i, j), (i+1, j), (i, j+1) and
// the upper-right (i+1, j), (i+1, j+1), (i, j+1). The same on the 2h grid, whose macro-triangles
// are the unions of four h-triangles of the same triangulation.
// Periodic sides (CutPeriodicity): the distance is the smallest over the bodies' periodic images,
// so a body across a periodic side is cut on both sides, and ForEachFace also visits the faces
// across the periodic sides. Node indices stay those of the grid (the repeated last column or row
// included); the forms map a repeated node to its first (particles/cut_cell_stokes.h).
// Reference: Burman, Claus, Hansbo, Larson & Massing, "CutFEM: discretizing geometry and partial
// differential equations", Int. J. Numer. Methods Eng. 104 (2015) 472-501.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/core/params.h"
#include "dlmfd/particles/shape.h"

namespace dlmfd {

// A body at rest: its shape, centre and angle (x_world = centre + Rot(angle) r_body).
struct FixedBody {
  Shape shape;
  Vec2 centre = Vec2::Zero();
  double angle = 0.0;
};

enum class ElementState : unsigned char { kFluid, kCut, kSolid };
// Which axes of the mesh are periodic (the last node column or row repeats the first).
struct CutPeriodicity {
  bool x = false;
  bool y = false;
};
enum class CutTriangulation { kSwNe, kNwSe };

struct CutTriangle {
  int triangle = 0;             // h-triangle index (header)
  int body = 0;                 // the body whose distance is smallest at its vertices
  std::array<int, 3> nodes{};   // velocity node indices
  std::array<Vec2, 3> grads{};  // P1 basis gradients
  double area = 0.0;            // of the fluid part
  Vec2 centroid = Vec2::Zero();
  std::array<std::array<double, 3>, 3> mass{};  // int_fluid phi_i phi_j
  Vec2 chord_a = Vec2::Zero(), chord_b = Vec2::Zero();
  Vec2 normal = Vec2::Zero();  // unit, out of the fluid
};

class CutCellGeometry {
 public:
  CutCellGeometry(const Grid& grid, const std::vector<FixedBody>& bodies,
                  CutTriangulation triangulation = CutTriangulation::kSwNe,
                  CutPeriodicity periodic = {});

  const Grid& grid() const { return grid_; }
  CutPeriodicity periodic() const { return periodic_; }
  CutTriangulation triangulation() const { return triangulation_; }
  int TriangleCount() const { return 2 * grid_.nx * grid_.ny; }
  // The three velocity nodes of h-triangle t and their P1 gradients.
  std::array<int, 3> TriangleNodes(int t) const;
  std::array<Vec2, 3> TriangleGradients(int t) const;
  // The macro-triangle (2h grid) that holds h-triangle t, and its three pressure nodes.
  int MacroOf(int t) const;
  std::array<int, 3> MacroNodes(int macro) const;
  std::array<Vec2, 3> MacroGradients(int macro) const;
  // The triangles t (a lower or lower-left one, even) and u (upper or upper-right, odd) of each
  // interior face, its unit normal (any orientation) and length, on this grid's triangulation
  // (h-mesh) or on the 2h mesh, the faces across periodic sides included: visits f(t, u, normal,
  // length).
  template <class Visit>
  void ForEachFace(const Grid& mesh, Visit f) const;

  ElementState State(int t) const { return state_[t]; }
  bool Active(int t) const { return state_[t] != ElementState::kSolid; }
  const std::vector<CutTriangle>& cut_triangles() const { return cuts_; }
  const std::vector<double>& distance() const { return phi_; }  // per velocity node
  int NearestBody(std::size_t node) const { return nearest_[node]; }
  bool NodeActive(std::size_t node) const { return node_active_[node] != 0; }
  bool MacroActive(int macro) const { return macro_active_[macro] != 0; }
  bool MacroTouched(int macro) const { return macro_touched_[macro] != 0; }
  bool PressureNodeActive(std::size_t node) const { return pressure_active_[node] != 0; }

  // Sums over the cut triangles (tests): the fluid area inside cut triangles, the chords' length.
  double CutFluidArea() const;
  double ChordLength() const;

 private:
  void ClassifyTriangles();
  void BuildCut(int t);

  Grid grid_;
  CutTriangulation triangulation_;
  CutPeriodicity periodic_;
  std::vector<double> phi_;
  std::vector<int> nearest_;  // per node: the body of smallest distance
  std::vector<ElementState> state_;
  std::vector<CutTriangle> cuts_;
  std::vector<unsigned char> node_active_, macro_active_, macro_touched_, pressure_active_;
};

template <class Visit>
void CutCellGeometry::ForEachFace(const Grid& mesh, Visit f) const {
  const double s2 = std::sqrt(0.5);
  const bool sw_ne = triangulation_ == CutTriangulation::kSwNe;
  auto upper = [&](int i, int j) { return 2 * (j * mesh.nx + i) + 1; };
  for (int j = 0; j < mesh.ny; ++j) {
    for (int i = 0; i < mesh.nx; ++i) {
      const int t = 2 * (j * mesh.nx + i);
      f(t, t + 1, sw_ne ? Vec2(s2, -s2) : Vec2(s2, s2), std::sqrt(2.0) * mesh.h);
      if (j > 0) f(t, upper(i, j - 1), Vec2(0.0, 1.0), mesh.h);
      if (j == 0 && periodic_.y) f(t, upper(i, mesh.ny - 1), Vec2(0.0, 1.0), mesh.h);
      if (sw_ne && i + 1 < mesh.nx) f(t, upper(i + 1, j), Vec2(1.0, 0.0), mesh.h);
      if (sw_ne && i + 1 == mesh.nx && periodic_.x) f(t, upper(0, j), Vec2(1.0, 0.0), mesh.h);
      if (!sw_ne && i > 0) f(t, upper(i - 1, j), Vec2(1.0, 0.0), mesh.h);
      if (!sw_ne && i == 0 && periodic_.x) f(t, upper(mesh.nx - 1, j), Vec2(1.0, 0.0), mesh.h);
    }
  }
}

}  // namespace dlmfd
