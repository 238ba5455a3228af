#include "dlmfd/particles/cut_cell_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dlmfd {
namespace {

// The fluid part (phi >= 0) of a triangle with vertex values ph: its polygon (at most 4 vertices)
// and the chord's two ends where the sign changes.
struct Clipped {
  std::vector<Vec2> polygon;
  std::vector<Vec2> chord;
};

Clipped ClipFluid(const std::array<Vec2, 3>& x, const std::array<double, 3>& ph) {
  Clipped c;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    if (ph[k] >= 0.0) c.polygon.push_back(x[k]);
    if ((ph[k] >= 0.0) != (ph[k1] >= 0.0)) {
      const double s = ph[k] / (ph[k] - ph[k1]);
      const Vec2 p = x[k] + s * (x[k1] - x[k]);
      c.polygon.push_back(p);
      c.chord.push_back(p);
    }
  }
  return c;
}

double TwiceSignedArea(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
}

// A node flag of a periodic mesh set on a node and its repeats alike (either set: both set).
void SyncPeriodicFlags(const Grid& mesh, CutPeriodicity periodic,
                       std::vector<unsigned char>& flags) {
  auto join = [&](std::size_t a, std::size_t b) { flags[a] = flags[b] = flags[a] | flags[b]; };
  if (periodic.x)
    for (int j = 0; j <= mesh.ny; ++j) join(mesh.Index(0, j), mesh.Index(mesh.nx, j));
  if (periodic.y)
    for (int i = 0; i <= mesh.nx; ++i) join(mesh.Index(i, 0), mesh.Index(i, mesh.ny));
}

}  // namespace

CutCellGeometry::CutCellGeometry(const Grid& grid, const std::vector<FixedBody>& bodies,
                                 CutTriangulation triangulation, CutPeriodicity periodic)
    : grid_(grid),
      triangulation_(triangulation),
      periodic_(periodic) {
  const std::size_t n = grid.NodeCount();
  phi_.assign(n, std::numeric_limits<double>::infinity());
  nearest_.assign(n, -1);
  // The bodies' periodic images: offsets of -1, 0, 1 box lengths along each periodic axis.
  std::vector<Vec2> images;
  for (int a = -1; a <= 1; ++a)
    for (int c = -1; c <= 1; ++c)
      if ((a == 0 || periodic.x) && (c == 0 || periodic.y))
        images.emplace_back(a * grid.Width(), c * grid.Height());
  for (int b = 0; b < static_cast<int>(bodies.size()); ++b) {
    const FixedBody& body = bodies[b];
    const double reach = body.shape.BoundingRadius() + 3.0 * grid.h;
    for (const Vec2& offset : images) {
      for (int j = 0; j <= grid.ny; ++j) {
        for (int i = 0; i <= grid.nx; ++i) {
          const Vec2 r = Vec2(grid.X(i), grid.Y(j)) - body.centre - offset;
          // Far nodes: the distance to the bounding circle, a lower bound with the right sign.
          const double d = r.norm() > reach ? r.norm() - body.shape.BoundingRadius()
                                            : body.shape.SignedDistance(Rotate(-body.angle, r));
          const std::size_t k = grid.Index(i, j);
          if (d < phi_[k]) {
            phi_[k] = d;
            nearest_[k] = b;
          }
        }
      }
    }
  }
  for (double& d : phi_)
    if (std::abs(d) < 1e-9 * grid.h) d = 0.0;  // a node on the boundary, up to round-off
  ClassifyTriangles();
}

namespace {

std::array<int, 3> MeshTriangleNodes(const Grid& mesh, CutTriangulation tri, int t) {
  const int square = t / 2, i = square % mesh.nx, j = square / mesh.nx;
  const int n00 = static_cast<int>(mesh.Index(i, j)), n10 = n00 + 1;
  const int n01 = static_cast<int>(mesh.Index(i, j + 1)), n11 = n01 + 1;
  if (tri == CutTriangulation::kSwNe) {
    if (t % 2 == 0) return {n00, n10, n11};
    return {n00, n11, n01};
  }
  if (t % 2 == 0) return {n00, n10, n01};
  return {n10, n11, n01};
}

std::array<Vec2, 3> MeshTriangleGradients(double h, CutTriangulation tri, int t) {
  const double r = 1.0 / h;
  if (tri == CutTriangulation::kSwNe) {
    if (t % 2 == 0) return {Vec2(-r, 0.0), Vec2(r, -r), Vec2(0.0, r)};
    return {Vec2(0.0, -r), Vec2(r, 0.0), Vec2(-r, r)};
  }
  if (t % 2 == 0) return {Vec2(-r, -r), Vec2(r, 0.0), Vec2(0.0, r)};
  return {Vec2(0.0, -r), Vec2(r, r), Vec2(-r, 0.0)};
}

}  // namespace

std::array<int, 3> CutCellGeometry::TriangleNodes(int t) const {
  return MeshTriangleNodes(grid_, triangulation_, t);
}

std::array<Vec2, 3> CutCellGeometry::TriangleGradients(int t) const {
  return MeshTriangleGradients(grid_.h, triangulation_, t);
}

// In units of h from the macro's corner (i % 2, j % 2), with a the centroid's offset in it: SW-NE:
// lower (a + 2/3, b + 1/3), upper (a + 1/3, b + 2/3), lower in its macro where x >= y; NW-SE:
// lower-left (a + 1/3, b + 1/3), upper-right (a + 2/3, b + 2/3), lower-left where x + y <= 2. In
// thirds of h, integers: the same choice as in floating point (its two sides differ by 1/3 h or
// more), without rounding.
int CutCellGeometry::MacroOf(int t) const {
  const int square = t / 2, i = square % grid_.nx, j = square / grid_.nx;
  const int first = 2 * ((j / 2) * (grid_.nx / 2) + i / 2);
  const int a = i % 2, b = j % 2;
  if (triangulation_ == CutTriangulation::kSwNe) {
    const bool lower = t % 2 == 0 ? 3 * a + 2 >= 3 * b + 1 : 3 * a + 1 >= 3 * b + 2;
    return first + (lower ? 0 : 1);
  }
  const int c = t % 2 == 0 ? 1 : 2;  // thirds
  const bool lower_left = 3 * (a + b) + 2 * c <= 6;
  return first + (lower_left ? 0 : 1);
}

std::array<int, 3> CutCellGeometry::MacroNodes(int macro) const {
  return MeshTriangleNodes(grid_.Coarse(), triangulation_, macro);
}

std::array<Vec2, 3> CutCellGeometry::MacroGradients(int macro) const {
  return MeshTriangleGradients(2.0 * grid_.h, triangulation_, macro);
}

void CutCellGeometry::ClassifyTriangles() {
  const int count = TriangleCount();
  state_.assign(count, ElementState::kFluid);
  node_active_.assign(grid_.NodeCount(), 0);
  const Grid coarse = grid_.Coarse();
  macro_active_.assign(2 * coarse.nx * coarse.ny, 0);
  macro_touched_.assign(macro_active_.size(), 0);
  pressure_active_.assign(coarse.NodeCount(), 0);
  for (int t = 0; t < count; ++t) {
    const std::array<int, 3> nodes = TriangleNodes(t);
    bool all_fluid = true, any_positive = false;
    int zeros = 0;
    for (int k : nodes) {
      all_fluid = all_fluid && phi_[k] >= 0.0;
      any_positive = any_positive || phi_[k] > 0.0;
      zeros += phi_[k] == 0.0 ? 1 : 0;
    }
    if (all_fluid && zeros == 2) {  // an edge on the boundary: a whole triangle with a chord
      state_[t] = ElementState::kCut;
      BuildCut(t);
      macro_touched_[MacroOf(t)] = 1;
    } else if (all_fluid) {
      state_[t] = ElementState::kFluid;
    } else if (any_positive) {
      state_[t] = ElementState::kCut;
      BuildCut(t);
      macro_touched_[MacroOf(t)] = 1;
    } else {
      state_[t] = ElementState::kSolid;
      continue;
    }
    for (int k : nodes) node_active_[k] = 1;
    macro_active_[MacroOf(t)] = 1;
  }
  for (int m = 0; m < static_cast<int>(macro_active_.size()); ++m)
    if (macro_active_[m])
      for (int q : MacroNodes(m)) pressure_active_[q] = 1;
  SyncPeriodicFlags(grid_, periodic_, node_active_);
  SyncPeriodicFlags(coarse, periodic_, pressure_active_);
}

void CutCellGeometry::BuildCut(int t) {
  CutTriangle c;
  c.triangle = t;
  c.nodes = TriangleNodes(t);
  c.grads = TriangleGradients(t);
  std::array<Vec2, 3> x;
  std::array<double, 3> ph{};
  double smallest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const std::size_t node = static_cast<std::size_t>(c.nodes[k]);
    const int i = static_cast<int>(node % static_cast<std::size_t>(grid_.NodesX()));
    const int j = static_cast<int>(node / static_cast<std::size_t>(grid_.NodesX()));
    x[k] = Vec2(grid_.X(i), grid_.Y(j));
    ph[k] = phi_[node];
    if (ph[k] < smallest) {
      smallest = ph[k];
      c.body = nearest_[node];
    }
  }
  Clipped clip = ClipFluid(x, ph);
  if (clip.chord.empty())  // the whole triangle, its edge between the two zeros on the boundary
    for (int k = 0; k < 3; ++k)
      if (ph[k] == 0.0) clip.chord.push_back(x[k]);
  // Area and centroid of the polygon; its P1 mass by the edge-midpoint rule on a fan.
  double twice = 0.0;
  Vec2 moment = Vec2::Zero();
  const std::size_t m = clip.polygon.size();
  for (std::size_t k = 1; k + 1 < m; ++k) {
    const Vec2 &a = clip.polygon[0], &b = clip.polygon[k], &d = clip.polygon[k + 1];
    const double tw = std::abs(TwiceSignedArea(a, b, d));
    twice += tw;
    moment += tw * (a + b + d) / 3.0;
    for (const Vec2& q : {Vec2(0.5 * (a + b)), Vec2(0.5 * (b + d)), Vec2(0.5 * (d + a))}) {
      std::array<double, 3> basis{};
      for (int r = 0; r < 3; ++r) basis[r] = (r == 0 ? 1.0 : 0.0) + c.grads[r].dot(q - x[0]);
      for (int r = 0; r < 3; ++r)
        for (int s = 0; s < 3; ++s) c.mass[r][s] += tw / 6.0 * basis[r] * basis[s];
    }
  }
  c.area = 0.5 * twice;
  c.centroid = moment / twice;
  c.chord_a = clip.chord[0];
  c.chord_b = clip.chord[1];
  Vec2 grad_phi = Vec2::Zero();  // the gradient of the linear distance points into the fluid
  for (int k = 0; k < 3; ++k) grad_phi += ph[k] * c.grads[k];
  c.normal = -grad_phi.normalized();
  cuts_.push_back(c);
}

double CutCellGeometry::CutFluidArea() const {
  double a = 0.0;
  for (const CutTriangle& c : cuts_) a += c.area;
  return a;
}

double CutCellGeometry::ChordLength() const {
  double l = 0.0;
  for (const CutTriangle& c : cuts_) l += (c.chord_b - c.chord_a).norm();
  return l;
}

}  // namespace dlmfd
