// The polymer force on the fluid part of a cut mesh (particles/cut_cell_polymer_force.h): the
// whole-mesh force of conformation/polymer_force.h corrected on the solid and cut triangles is
// f_i = -int_{Omega_f} grad phi_i : tau_p. Checked by its moments, which hold for any tau_p
// because sum_i phi_i = 1 and sum_i x_i phi_i = x on the mesh:
//   sum_i f_i = 0,   sum_i x_i fx_i = -int_{Omega_f} tau_11,   sum_i y_i fx_i = -int tau_12,
//   sum_i y_i fy_i = -int tau_22,
// with tau_p linear (P1 exact) against the integrals over the fluid part in closed form: the box
// minus the disk, to the chords' area error (at most the perimeter times the largest sagitta,
// (sqrt(2) h)^2 / (8 r), of a chord across a triangle); with tau_p constant the force vanishes at
// every node whose support is all fluid and inside the box. SW-NE and both triangulations; a
// periodic box with the disk across its side (the repeated nodes fold into the first).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dlmfd/conformation/polymer_force.h"
#include "dlmfd/particles/cut_cell_polymer_force.h"

namespace dlmfd {
namespace {

struct MeshCase {
  MeshDiagonals diagonals;
  bool periodic_x;
};

struct Moments {
  double sum_fx = 0.0, sum_fy = 0.0, x_fx = 0.0, y_fx = 0.0, y_fy = 0.0, scale = 0.0;
};

// The fluid-part force of tau_p = G (S - I) with S given by its node values s(x, y).
template <class Field>
std::vector<double> CutForce(const MeshCase& c, const Grid& g, const Vec2& centre, double radius,
                             double modulus, Field s, std::vector<double>* fy_out) {
  DomainParams domain;
  domain.size = Vec2(g.Width(), g.Height());
  domain.h = g.h;
  domain.diagonals = c.diagonals;
  if (c.periodic_x) {
    domain.sides[static_cast<int>(Side::kLeft)].type = SideType::kPeriodic;
    domain.sides[static_cast<int>(Side::kRight)].type = SideType::kPeriodic;
  }
  std::vector<double> a11(g.NodeCount()), a12(g.NodeCount()), a22(g.NodeCount());
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      // A periodic field: the repeated last column holds the first's value.
      const double x = c.periodic_x && i == g.nx ? g.X(0) : g.X(i);
      const auto [s11, s12, s22] = s(x, g.Y(j));
      const std::size_t k = g.Index(i, j);
      a11[k] = s11, a12[k] = s12, a22[k] = s22;
    }
  }
  std::vector<double> fx(g.NodeCount(), 0.0), fy(g.NodeCount(), 0.0);
  AddPolymerForce(g, domain, modulus, a11.data(), a12.data(), a22.data(), fx.data(), fy.data());
  std::vector<FixedBody> bodies(1);
  bodies[0].shape = Shape::Disk(radius);
  bodies[0].centre = centre;
  const CutPeriodicity periodic{c.periodic_x, false};
  const CutCellGeometry sw_ne(g, bodies, CutTriangulation::kSwNe, periodic);
  const CutCellGeometry nw_se(g, bodies, CutTriangulation::kNwSe, periodic);
  std::vector<const CutCellGeometry*> geometries{&sw_ne};
  if (c.diagonals == MeshDiagonals::kBoth) geometries.push_back(&nw_se);
  AddCutCellPolymerCorrection(geometries, modulus, a11.data(), a12.data(), a22.data(), fx.data(),
                              fy.data());
  *fy_out = fy;
  return fx;
}

Moments MomentsOf(const Grid& g, const std::vector<double>& fx, const std::vector<double>& fy) {
  Moments m;
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const std::size_t k = g.Index(i, j);
      m.sum_fx += fx[k];
      m.sum_fy += fy[k];
      m.x_fx += g.X(i) * fx[k];
      m.y_fx += g.Y(j) * fx[k];
      m.y_fy += g.Y(j) * fy[k];
      m.scale = std::max({m.scale, std::abs(fx[k]), std::abs(fy[k])});
    }
  }
  return m;
}

class CutCellPolymerForce : public ::testing::TestWithParam<MeshCase> {};

// tau_11 = G (x + 1), tau_12 = G y / 2, tau_22 = G (2 - y): linear, so the integrals over the
// fluid part are the box's minus the disk's, exactly but for the chords.
TEST_P(CutCellPolymerForce, ItsMomentsAreTheStressIntegralsOverTheFluidPart) {
  const MeshCase c = GetParam();
  const Grid g{40, 32, 1.0 / 32, 0.0, 0.0};  // 1.25 x 1
  const double r = 0.21, modulus = 0.7;
  const Vec2 centre = c.periodic_x ? Vec2(0.07, 0.513) : Vec2(0.61, 0.487);
  auto s = [](double x, double y) {
    return std::array<double, 3>{x + 2.0, 0.5 * y, 3.0 - y};  // S - I = (x + 1, y / 2, 2 - y)
  };
  std::vector<double> fy;
  const std::vector<double> fx = CutForce(c, g, centre, r, modulus, s, &fy);
  const Moments m = MomentsOf(g, fx, fy);
  const double pi = std::acos(-1.0), w = g.Width(), hgt = g.Height();
  const double disk = pi * r * r;
  // The disk's first moments are its centre times its area. In the periodic box x is not a
  // periodic field (S at the repeated column is the first's), so there the x-moment is not checked.
  const double disk_x = centre.x() * disk;
  const double int_t11 = modulus * ((0.5 * w * w * hgt + w * hgt) - (disk_x + disk));
  const double int_t12 = modulus * 0.5 * (0.5 * w * hgt * hgt - centre.y() * disk);
  const double int_t22 =
      modulus * ((2.0 * w * hgt - 0.5 * w * hgt * hgt) - (2.0 * disk - centre.y() * disk));
  // The chords' area error bound times the largest |tau| over the box (|G (S - I)| <= 2.25 G).
  const double chords = 2.0 * pi * r * (2.0 * g.h * g.h) / (8.0 * r) * 2.25 * modulus;
  EXPECT_NEAR(m.sum_fx, 0.0, 1e-13 * m.scale * g.NodeCount());
  EXPECT_NEAR(m.sum_fy, 0.0, 1e-13 * m.scale * g.NodeCount());
  if (!c.periodic_x) {
    EXPECT_NEAR(m.x_fx, -int_t11, chords);
  }
  EXPECT_NEAR(m.y_fx, -int_t12, chords);
  EXPECT_NEAR(m.y_fy, -int_t22, chords);
  // The moments of the whole mesh's force (no disk) are the box's integrals to round-off: the
  // correction is what removes the disk.
  EXPECT_GT(std::abs(m.y_fy + modulus * (2.0 * w * hgt - 0.5 * w * hgt * hgt)), 10.0 * chords);
}

// A constant stress: no force at a node whose support is fluid and inside the box.
TEST_P(CutCellPolymerForce, AConstantStressPushesOnlyAtTheBodyAndTheSides) {
  const MeshCase c = GetParam();
  const Grid g{40, 32, 1.0 / 32, 0.0, 0.0};
  const Vec2 centre = c.periodic_x ? Vec2(0.07, 0.513) : Vec2(0.61, 0.487);
  const double r = 0.21;
  auto s = [](double, double) { return std::array<double, 3>{2.5, 0.3, 0.8}; };
  std::vector<double> fy;
  const std::vector<double> fx = CutForce(c, g, centre, r, 1.0, s, &fy);
  double near = 0.0, far = 0.0;
  for (int j = 0; j <= g.ny; ++j) {
    for (int i = 0; i <= g.nx; ++i) {
      const std::size_t k = g.Index(i, j);
      double dx = g.X(i) - centre.x();
      if (c.periodic_x) dx -= g.Width() * std::round(dx / g.Width());
      const double d = std::hypot(dx, g.Y(j) - centre.y()) - r;
      const bool side = j == 0 || j == g.ny || (!c.periodic_x && (i == 0 || i == g.nx));
      const double f = std::hypot(fx[k], fy[k]);
      if (std::abs(d) < 2.0 * g.h) {
        near = std::max(near, f);
      } else if (!side && !(c.periodic_x && i == g.nx)) {
        far = std::max(far, f);
      }
    }
  }
  EXPECT_GT(near, 0.1 * g.h);  // the body's traction, O(h |tau|) a node
  EXPECT_LT(far, 1e-14);
}

INSTANTIATE_TEST_SUITE_P(Meshes, CutCellPolymerForce,
                         ::testing::Values(MeshCase{MeshDiagonals::kSwNe, false},
                                           MeshCase{MeshDiagonals::kBoth, false},
                                           MeshCase{MeshDiagonals::kBoth, true}));

}  // namespace
}  // namespace dlmfd
