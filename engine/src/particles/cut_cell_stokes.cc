#include "dlmfd/particles/cut_cell_stokes.h"

#include <Eigen/SparseLU>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "dlmfd/core/errors.h"
#include "dlmfd/mesh/boundary_topology.h"
#include "dlmfd/particles/cut_cell_capacitance.h"
#include "dlmfd/particles/pressure_correction_basis.h"
#include "dlmfd/solvers/gmres.h"
#include "dlmfd/solvers/separable_helmholtz.h"

namespace dlmfd {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using Triplets = std::vector<Eigen::Triplet<double>>;

// The P1 basis of a triangle with first vertex x0 and gradients g, at x.
std::array<double, 3> Basis(const Vec2& x0, const std::array<Vec2, 3>& g, const Vec2& x) {
  return {1.0 + g[0].dot(x - x0), g[1].dot(x - x0), g[2].dot(x - x0)};
}

Vec2 NodePosition(const Grid& grid, int node) {
  return Vec2(grid.X(node % grid.NodesX()), grid.Y(node / grid.NodesX()));
}

// The P1 basis of the macro-triangle `macro` at x.
std::array<double, 3> MacroBasis(const CutCellGeometry& geo, int macro, const Vec2& x) {
  return Basis(NodePosition(geo.grid().Coarse(), geo.MacroNodes(macro)[0]),
               geo.MacroGradients(macro), x);
}

// Ghost penalty scale * |F| [d_n phi_i][d_n phi_j] over the interior faces of the h-mesh (or of
// the 2h mesh) shared by two active triangles, at least one of them touched.
template <class Nodes, class Gradients, class Active, class Touched>
void AddGhostPenalty(const CutCellGeometry& geo, const Grid& mesh, Nodes nodes, Gradients gradients,
                     Active active, Touched touched, double scale, Triplets& out) {
  geo.ForEachFace(mesh, [&](int t, int u, const Vec2& n, double length) {
    if (!active(t) || !active(u) || !(touched(t) || touched(u))) return;
    const std::array<int, 3> a = nodes(t), b = nodes(u);
    const std::array<Vec2, 3> ga = gradients(t), gb = gradients(u);
    const std::array<int, 6> idx{a[0], a[1], a[2], b[0], b[1], b[2]};
    std::array<double, 6> jump{};
    for (int k = 0; k < 3; ++k) {
      jump[k] = ga[k].dot(n);
      jump[3 + k] = -gb[k].dot(n);
    }
    for (int p = 0; p < 6; ++p)
      for (int q = 0; q < 6; ++q)
        out.emplace_back(idx[p], idx[q], scale * length * jump[p] * jump[q]);
  });
}

// A row-major matrix assembled row by row (Reserve at least its entries first): row `row` of m,
// its columns through `index` (-1: left out) plus `offset`, divided by `divisor`. Entries that are
// exactly 0 are left out: the assembly stores the couplings whose sums vanish (the diagonal
// neighbours of the stiffness on right triangles, half the velocity block's entries at D/h = 20;
// a fifth of the divergence's), and a product adds nothing for them.
struct ReducedRows {
  std::vector<int> outer{0}, inner;
  std::vector<double> values;
  std::size_t size = 0;
  void Append(const RowSparse& m, int row, const std::vector<int>& index, int offset,
              double divisor) {
    const int* cols = m.innerIndexPtr();
    const double* vals = m.valuePtr();
    for (int e = m.outerIndexPtr()[row]; e < m.outerIndexPtr()[row + 1]; ++e) {
      const int c = index[static_cast<std::size_t>(cols[e])];
      if (c < 0 || vals[e] == 0.0) continue;
      inner[size] = offset + c;
      values[size] = vals[e] / divisor;
      ++size;
    }
  }
  void EndRow() { outer.push_back(static_cast<int>(size)); }
  void Reserve(Eigen::Index nonzeros) {
    inner.resize(static_cast<std::size_t>(nonzeros));
    values.resize(static_cast<std::size_t>(nonzeros));
  }
  RowSparse Build(int rows, int cols) const {
    RowSparse m(rows, cols);
    m.resizeNonZeros(static_cast<Eigen::Index>(size));
    std::copy(outer.begin(), outer.end(), m.outerIndexPtr());
    std::copy_n(inner.begin(), size, m.innerIndexPtr());
    std::copy_n(values.begin(), size, m.valuePtr());
    return m;
  }
};

// Visits the entries of the sum of two sparse vectors (inner vectors, sorted) as Eigen's sum of
// the matrices makes them: a + b where both store an entry, else the one that does.
template <class Iterator, class Visit>
void ForEachSumEntry(Iterator a, Iterator b, Visit visit) {
  while (a || b) {
    if (a && b && a.index() == b.index()) {
      visit(a.index(), a.value() + b.value());
      ++a;
      ++b;
    } else if (a && (!b || a.index() < b.index())) {
      visit(a.index(), a.value());
      ++a;
    } else {
      visit(b.index(), b.value());
      ++b;
    }
  }
}

// sum = base + band where sum already holds base + the last band of the columns (rows, row-major)
// `touched` (`in_place`; else sum is formed anew, as Eigen's sum): those back to base, then
// base + the new band's entries in place. The band's pattern lies in base's (the same triangles'
// couplings), so the sum keeps base's pattern and each entry is the sum's own a + b: the same bits
// as base + band, at the cost of the band's columns. `touched` becomes the new band's columns;
// in_place false where the band reaches outside base's pattern (the sum is then made whole).
template <class Matrix>
void AddBandInPlace(const Matrix& base, const Matrix& band, Matrix& sum, std::vector<int>& touched,
                    bool& in_place) {
  const int* outer = base.outerIndexPtr();
  if (in_place) {
    for (const int c : touched)
      std::copy(base.valuePtr() + outer[c], base.valuePtr() + outer[c + 1],
                sum.valuePtr() + outer[c]);
  }
  touched.clear();
  for (Eigen::Index c = 0; c < band.outerSize() && in_place; ++c) {
    int e = outer[c];
    for (typename Matrix::InnerIterator it(band, c); it; ++it) {
      while (e < outer[c + 1] && base.innerIndexPtr()[e] < it.index()) ++e;
      if (e == outer[c + 1] || base.innerIndexPtr()[e] != it.index()) {
        in_place = false;
        break;
      }
      sum.valuePtr()[e] = base.valuePtr()[e] + it.value();
    }
    if (band.outerIndexPtr()[c] < band.outerIndexPtr()[c + 1])
      touched.push_back(static_cast<int>(c));
  }
  if (in_place) return;
  sum = base + band;
  touched.clear();
  for (Eigen::Index c = 0; c < band.outerSize(); ++c)
    if (band.outerIndexPtr()[c] < band.outerIndexPtr()[c + 1])
      touched.push_back(static_cast<int>(c));
  in_place = sum.isCompressed() && sum.nonZeros() == base.nonZeros();
}

}  // namespace

struct CutCellStokes::Impl {
  // A periodic mesh's node numbering for the forms: a node of the repeated last column (row) of a
  // periodic pair is its first one's (mesh/boundary_topology.h), so the forms of the elements next
  // to a periodic side couple across it.
  struct PeriodicNodes {
    Grid mesh;
    bool x, y;
    int operator()(int node) const {
      int i = node % mesh.NodesX(), j = node / mesh.NodesX();
      if (x && i == mesh.nx) i = 0;
      if (y && j == mesh.ny) j = 0;
      return static_cast<int>(mesh.Index(i, j));
    }
    std::array<int, 3> operator()(const std::array<int, 3>& nodes) const {
      return {(*this)(nodes[0]), (*this)(nodes[1]), (*this)(nodes[2])};
    }
  };
  std::vector<const CutCellGeometry*> geos;  // one triangulation, or both (forms averaged)
  double weight;                             // 1 / geos.size()
  Grid grid, pgrid;
  BoundaryTopology vtopo, ptopo;
  PeriodicNodes vmap, pmap;  // the forms' node of a velocity (pressure) node
  double eta, rho, rho_over_dt;
  CutCellConstants constants;
  // Full-index forms (velocity nodes n, pressure nodes np).
  Sparse stiffness, nitsche, ghost_u, convection;  // n x n
  Eigen::VectorXd lumped_mass;                     // n
  Eigen::VectorXd pressure_fluid_mass;             // np: int_fluid q_Q
  Sparse div_x, div_y, chord_x, chord_y;           // np x n: -(q, d_c u); <q, u n_c>
  Sparse ghost_p;                                  // np x np
  Sparse band_stiffness;  // Recut: the stiffness less the uniform one (the band's correction)
  // Recut: stiffness, div_x and div_y hold the uniform forms plus the band's correction in these
  // columns (AddBandInPlace), updated in place where band_in_place.
  std::array<std::vector<int>, 5> band_columns;
  std::array<bool, 5> band_in_place{false, false, false, false, false};
  // Recut: div_x and div_y by rows (the uniform ones plus the band's, in place), for b's rows.
  RowSparse div_x_rows, div_y_rows;
  // Nitsche's load of the bodies' rigid motion (SetBodyMotion): momentum (n) and continuity (np);
  // empty for bodies at rest.
  Eigen::VectorXd boundary_u, boundary_v, boundary_p;
  // Unknowns.
  std::vector<int> vindex, pindex;  // full -> reduced, -1 if not an unknown
  std::vector<int> vnodes, pnodes;  // reduced -> full
  // The reduced operators; the velocity block over every node (MomentumFull: GMRES and the direct
  // solve only).
  Sparse momentum_full, velocity;
  // Row-major rows of the fluid forms for the force: eta K + rho C, and -B_x^T, -B_y^T of the
  // volume divergence (n x np).
  RowSparse momentum_rows, gradient_x_rows, gradient_y_rows;
  // Row-major copies for the products of the iterations: bt = [Bx^T; By^T] and b = [Bx, By] over
  // the unknowns, pp = -G_p / phi_p; A over the unknowns (velocity_rows) and the whole saddle point
  // (saddle_rows) for GMRES and the direct solve only, made when first needed.
  RowSparse saddle_rows, bt, b, pp, velocity_rows;
  bool exact_velocity = false;  // precondition the velocity by its own factorization
  Eigen::SparseLU<Sparse> velocity_lu;
  std::unique_ptr<SeparableHelmholtz> fast_velocity, fast_pressure;
  std::unique_ptr<CutCellCapacitance> capacitance;  // the exact solve of the Stokes velocity block
  // The pressure Laplacian of the fluid part plus the scaled ghost penalty against fast_pressure
  // (SchurInverse); null: the uniform grid's Laplacian.
  std::unique_ptr<CutCellCapacitance> pressure_capacitance;
  Eigen::VectorXd pressure_mass;  // at pressure unknowns
  // The earlier steps' pressure corrections for the Uzawa start (S fixed: cleared by BuildReduced).
  PressureCorrectionBasis corrections;
  std::vector<double> work_fu, work_fv, work_u, work_v, work_fp, work_p;
  // A moving body's steps (Recut): the uniform grid's fluid forms (every triangle whole, the same
  // assembly) and the fast solver's responses A_0^-1 e_s of the band.
  struct Uniform {
    Sparse stiffness, div_x, div_y;
    RowSparse div_x_rows, div_y_rows;  // the same by rows
    Eigen::VectorXd lumped_mass, pressure_fluid_mass;
  };
  std::unique_ptr<Uniform> uniform;
  std::unique_ptr<CutCellResponses> responses;
  bool band_forms = false;  // the forms are the uniform ones plus the band's correction

  Impl(std::vector<const CutCellGeometry*> g, const DomainParams& domain, double viscosity,
       double density, double rdt, const CutCellConstants& c);
  void AssembleFluidForms();
  // The fluid forms' sums being assembled: as triplets (the band's corrections), or, for the whole
  // grid's, summed entry by entry into matrices with room for the whole pattern (InPlace): each
  // entry's terms are added in the triangles' order either way, so the sums are the same to the
  // bit, and the whole grid's forms no longer pass through triplets (61 MB at D/h = 19.5 with both
  // triangulations, whose first touch and sort were 4 % of a run's CPU time: docs/evidence/
  // cut_cell_boundary.md, "The step's floor against the peer").
  struct FormSums {
    FormSums(Eigen::Index n, Eigen::Index np)
        : lumped_mass(Eigen::VectorXd::Zero(n)),
          pressure_fluid_mass(Eigen::VectorXd::Zero(np)) {}
    Triplets k, bx, by;
    Eigen::VectorXd lumped_mass, pressure_fluid_mass;
    bool in_place = false;
    Sparse dk, dbx, dby;
    // Matrices with room for the entries of a node's column: its 3 x 3 neighbourhood of velocity
    // nodes (stiffness), of pressure nodes (divergence), on either triangulation.
    void InPlace(Eigen::Index n, Eigen::Index np) {
      in_place = true;
      dk.resize(n, n);
      dk.reserve(Eigen::VectorXi::Constant(n, kColumnRoom));
      for (Sparse* d : {&dbx, &dby}) {
        d->resize(np, n);
        d->reserve(Eigen::VectorXi::Constant(n, kColumnRoom));
      }
    }
    void Add(int row, int col, double v, Triplets& t, Sparse& d) {
      if (in_place) {
        d.coeffRef(row, col) += v;
      } else {
        t.emplace_back(row, col, v);
      }
    }
  };
  static constexpr int kColumnRoom = 12;
  void AddTriangleForms(const CutCellGeometry& geo, int t, const std::array<int, 3>& mesh_nodes,
                        const std::array<Vec2, 3>& grads, double area, const Vec2& centroid,
                        const std::array<double, 3>& mass_rows, double scale, FormSums& out) const;
  void AddWholeTriangle(const CutCellGeometry& geo, int t, double scale, FormSums& out) const;
  void AddCutTriangle(const CutCellGeometry& geo, const CutTriangle& c, FormSums& out) const;
  void AssembleUniformForms();
  void AssembleBandForms();
  void Recut();
  void AssembleChordForms();
  void AddChordTerms(const CutCellGeometry& geo, Triplets& nit, Triplets& cx, Triplets& cy) const;
  void AddChordLoad(const CutCellGeometry& geo, const std::vector<RigidMotion>& motions);
  Vec2 Arm(const Vec2& x, const Vec2& centre) const;  // x - centre, to the nearest periodic image
  void NumberUnknowns();
  bool ActiveNode(std::size_t k) const {
    for (const CutCellGeometry* geo : geos)
      if (geo->NodeActive(k)) return true;
    return false;
  }
  bool ActivePressureNode(std::size_t k) const {
    for (const CutCellGeometry* geo : geos)
      if (geo->PressureNodeActive(k)) return true;
    return false;
  }
  void BuildReduced();
  // b = [Bx, By] and bt = b^T over the unknowns (BuildReduced), Bx = div_x + chord_x: bt row by
  // row from the columns of the divergence and the chords' terms, b from their rows.
  void BuildDivergenceRows();
  // (rho/dt) M_l + eta (K + N + G_u) + rho C over every node (made when first needed after
  // BuildReduced), and one of its columns' entries, and of Bx's or By's, without it
  // (RightHandSide).
  const Sparse& MomentumFull();
  void AddMomentumColumn(Eigen::Index j, double value, Eigen::VectorXd& out) const;
  mutable std::vector<Eigen::Index> column_rows;  // AddMomentumColumn's work
  static void AddDivergenceColumn(const Sparse& div, const Sparse& chord, Eigen::Index j,
                                  double value, Eigen::VectorXd& out);
  void BuildVelocityRows();
  void BuildSaddleRows();
  std::vector<char> BandNodes() const;
  Sparse UniformVelocityOperator(const std::vector<char>& columns) const;
  std::vector<char> fast_unknown;  // the fast solver's unknowns (velocity nodes), made once
  Sparse BandDifference(const std::vector<char>& unknown) const;
  void BuildCapacitance();
  void BuildPressureCapacitance();
  void Precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z);
  void SchurInverse(const Eigen::VectorXd& r, Eigen::VectorXd& z);
  void SolveVelocity(const Eigen::VectorXd& r, Eigen::VectorXd& z);
  // The loads of LoadStop's bodies as rows over the unknowns [u; v; p] (Load's sums, linear in
  // them): three a body (F_x, F_y, T), each a list of (unknown, coefficient).
  struct LoadRows {
    std::vector<std::vector<std::pair<int, double>>> rows;
    std::vector<double> force_bound, torque_bound;
    // Without a pressure side the solution's pressure has its mean removed (RemovePressureMean):
    // a row's pressure part then reads p less that mean, the weights w / sum w (else empty) and
    // each row's sum of pressure coefficients.
    Eigen::VectorXd mean_weights;
    std::vector<double> pressure_sums;
  };
  LoadRows BuildLoadRows(const LoadStop& stop) const;
  // Whether an iteration's change, alpha (-w, d) of (u, p), moves every load within its bound.
  static bool LoadSettled(const LoadRows& load, double alpha, const Eigen::VectorXd& w,
                          const Eigen::VectorXd& d, int nu);
  GmresResult SolveSchur(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, double tolerance,
                         int max_iterations, const LoadRows* load = nullptr);
  Eigen::VectorXd RightHandSide(const BoundaryData& data, const double* fu, const double* fv,
                                std::vector<double>& gu, std::vector<double>& gv) const;
  void Scatter(const Eigen::VectorXd& x, const std::vector<double>& gu,
               const std::vector<double>& gv, double* u, double* v, double* p) const;
  void RemovePressureMean(Eigen::VectorXd& p) const;
};

CutCellStokes::Impl::Impl(std::vector<const CutCellGeometry*> g, const DomainParams& domain,
                          double viscosity, double density, double rdt, const CutCellConstants& c)
    : geos(std::move(g)),
      weight(1.0 / static_cast<double>(geos.size())),
      grid(geos[0]->grid()),
      pgrid(geos[0]->grid().Coarse()),
      vtopo(BoundaryTopology::ForVelocity(domain)),
      ptopo(BoundaryTopology::ForPressure(domain)),
      vmap{grid, domain.PeriodicX(), domain.PeriodicY()},
      pmap{pgrid, domain.PeriodicX(), domain.PeriodicY()},
      eta(viscosity),
      rho(density),
      rho_over_dt(rdt),
      constants(c) {
  for (const CutCellGeometry* geo : geos)
    if (geo->periodic().x != domain.PeriodicX() || geo->periodic().y != domain.PeriodicY())
      throw std::invalid_argument(
          "CutCellStokes: the geometry's periodic axes are not the domain's");
  // The capacitance matrix stands on a regular fast solver (the mass term, or a Dirichlet side).
  if (rho_over_dt == 0.0 && vtopo.HasNullSpace())
    throw std::invalid_argument("CutCellStokes: a steady problem needs a Dirichlet velocity side");
  const std::size_t n = grid.NodeCount();
  convection.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  AssembleFluidForms();
  AssembleChordForms();
  NumberUnknowns();
  fast_velocity = std::make_unique<SeparableHelmholtz>(grid, vtopo, rho_over_dt, eta);
  BuildCapacitance();
  if (rho_over_dt > 0.0) {
    fast_pressure =
        std::make_unique<SeparableHelmholtz>(pgrid, ptopo, 0.0, 1.0, ptopo.HasNullSpace() ? 1 : 2);
    BuildPressureCapacitance();
  }
  work_fu.assign(n, 0.0);
  work_fv.assign(n, 0.0);
  work_u.assign(n, 0.0);
  work_v.assign(n, 0.0);
  work_fp.assign(pgrid.NodeCount(), 0.0);
  work_p.assign(pgrid.NodeCount(), 0.0);
  BuildReduced();
}

// The geometries have moved (a body in prescribed motion): the forms anew as the uniform ones plus
// the band's correction (in place in the last and the new band's columns: AddBandInPlace), the
// unknowns, the capacitance matrix from the responses held (fast solves for the rows new to the
// band only), the reduced operators (b and bt copied from the forms; the velocity block over every
// node only when GMRES or the direct solve needs it). The fast solvers are kept; the Oseen term and
// the bodies' motion are cleared.
void CutCellStokes::Impl::Recut() {
  const auto n = static_cast<Eigen::Index>(grid.NodeCount());
  if (!uniform) AssembleUniformForms();
  if (!responses) responses = std::make_unique<CutCellResponses>(*fast_velocity);
  band_forms = true;
  convection.resize(n, n);
  convection.setZero();
  boundary_u.resize(0);
  boundary_v.resize(0);
  boundary_p.resize(0);
  AssembleBandForms();
  AssembleChordForms();
  NumberUnknowns();
  BuildCapacitance();
  pressure_capacitance.reset();
  BuildReduced();
}

// Stiffness, lumped mass and divergence over the fluid part of every active h-triangle: whole
// triangles, and the fluid polygons of cut ones (the divergence by the one-point rule at the
// polygon's centroid, exact for linear q times the constant div u). Both triangulations: the mean.
void CutCellStokes::Impl::AddTriangleForms(const CutCellGeometry& geo, int t,
                                           const std::array<int, 3>& mesh_nodes,
                                           const std::array<Vec2, 3>& grads, double area,
                                           const Vec2& centroid,
                                           const std::array<double, 3>& mass_rows, double scale,
                                           FormSums& out) const {
  const int macro = geo.MacroOf(t);
  const std::array<int, 3> nodes = vmap(mesh_nodes), q = pmap(geo.MacroNodes(macro));
  const std::array<double, 3> lam = MacroBasis(geo, macro, centroid);
  const double wa = scale * weight * area;
  for (int a = 0; a < 3; ++a) {
    out.lumped_mass[nodes[a]] += scale * weight * mass_rows[a];
    out.pressure_fluid_mass[q[a]] += wa * lam[a];
    for (int b = 0; b < 3; ++b) {
      out.Add(nodes[a], nodes[b], wa * grads[a].dot(grads[b]), out.k, out.dk);
      out.Add(q[a], nodes[b], -wa * lam[a] * grads[b].x(), out.bx, out.dbx);
      out.Add(q[a], nodes[b], -wa * lam[a] * grads[b].y(), out.by, out.dby);
    }
  }
}

void CutCellStokes::Impl::AddWholeTriangle(const CutCellGeometry& geo, int t, double scale,
                                           FormSums& out) const {
  const double whole = 0.5 * grid.h * grid.h;
  const std::array<int, 3> nodes = geo.TriangleNodes(t);
  Vec2 centroid = Vec2::Zero();
  for (int a : nodes) centroid += NodePosition(grid, a) / 3.0;
  AddTriangleForms(geo, t, nodes, geo.TriangleGradients(t), whole, centroid,
                   {whole / 3.0, whole / 3.0, whole / 3.0}, scale, out);
}

void CutCellStokes::Impl::AddCutTriangle(const CutCellGeometry& geo, const CutTriangle& c,
                                         FormSums& out) const {
  std::array<double, 3> rows{};
  for (int a = 0; a < 3; ++a) rows[a] = c.mass[a][0] + c.mass[a][1] + c.mass[a][2];
  AddTriangleForms(geo, c.triangle, c.nodes, c.grads, c.area, c.centroid, rows, 1.0, out);
}

void CutCellStokes::Impl::AssembleFluidForms() {
  const auto n = static_cast<Eigen::Index>(grid.NodeCount());
  const auto np = static_cast<Eigen::Index>(pgrid.NodeCount());
  FormSums f(n, np);
  f.InPlace(n, np);
  for (const CutCellGeometry* geo : geos) {
    for (int t = 0; t < geo->TriangleCount(); ++t)
      if (geo->State(t) == ElementState::kFluid) AddWholeTriangle(*geo, t, 1.0, f);
    for (const CutTriangle& c : geo->cut_triangles()) AddCutTriangle(*geo, c, f);
  }
  lumped_mass = std::move(f.lumped_mass);
  pressure_fluid_mass = std::move(f.pressure_fluid_mass);
  stiffness.swap(f.dk);
  stiffness.makeCompressed();
  div_x.swap(f.dbx);
  div_x.makeCompressed();
  div_y.swap(f.dby);
  div_y.makeCompressed();
}

// The fluid forms of the uniform grid (every triangle whole).
void CutCellStokes::Impl::AssembleUniformForms() {
  const auto n = static_cast<Eigen::Index>(grid.NodeCount());
  const auto np = static_cast<Eigen::Index>(pgrid.NodeCount());
  FormSums f(n, np);
  f.InPlace(n, np);
  for (const CutCellGeometry* geo : geos)
    for (int t = 0; t < geo->TriangleCount(); ++t) AddWholeTriangle(*geo, t, 1.0, f);
  uniform = std::make_unique<Uniform>();
  uniform->lumped_mass = std::move(f.lumped_mass);
  uniform->pressure_fluid_mass = std::move(f.pressure_fluid_mass);
  uniform->stiffness.swap(f.dk);
  uniform->stiffness.makeCompressed();
  uniform->div_x.swap(f.dbx);
  uniform->div_x.makeCompressed();
  uniform->div_y.swap(f.dby);
  uniform->div_y.makeCompressed();
  uniform->div_x_rows = uniform->div_x;
  uniform->div_y_rows = uniform->div_y;
}

// The fluid forms as the uniform ones less every triangle that is not fluid plus the fluid parts of
// the cut ones: the triangles of the band and inside the bodies only (the same forms up to
// round-off, which leaves entries of order 1e-16 of the largest where the exact assembly has
// none: in rows and columns of nodes without fluid, which the solver does not read, and Load
// skips them). The lumped masses are set to 0 at the nodes without fluid.
void CutCellStokes::Impl::AssembleBandForms() {
  const auto n = static_cast<Eigen::Index>(grid.NodeCount());
  const auto np = static_cast<Eigen::Index>(pgrid.NodeCount());
  FormSums f(n, np);
  for (const CutCellGeometry* geo : geos) {
    for (int t = 0; t < geo->TriangleCount(); ++t)
      if (geo->State(t) != ElementState::kFluid) AddWholeTriangle(*geo, t, -1.0, f);
    for (const CutTriangle& c : geo->cut_triangles()) AddCutTriangle(*geo, c, f);
  }
  lumped_mass = uniform->lumped_mass + f.lumped_mass;
  pressure_fluid_mass = uniform->pressure_fluid_mass + f.pressure_fluid_mass;
  for (Eigen::Index k = 0; k < n; ++k)
    if (!ActiveNode(static_cast<std::size_t>(k))) lumped_mass[k] = 0.0;
  for (Eigen::Index k = 0; k < np; ++k)
    if (!ActivePressureNode(static_cast<std::size_t>(k))) pressure_fluid_mass[k] = 0.0;
  band_stiffness.resize(n, n);
  band_stiffness.setFromTriplets(f.k.begin(), f.k.end());
  AddBandInPlace(uniform->stiffness, band_stiffness, stiffness, band_columns[0], band_in_place[0]);
  // The divergence by columns and by rows (each entry's band sum in the triplets' order either
  // way).
  Sparse band(np, n);
  RowSparse band_rows(np, n);
  band.setFromTriplets(f.bx.begin(), f.bx.end());
  AddBandInPlace(uniform->div_x, band, div_x, band_columns[1], band_in_place[1]);
  band_rows.setFromTriplets(f.bx.begin(), f.bx.end());
  AddBandInPlace(uniform->div_x_rows, band_rows, div_x_rows, band_columns[3], band_in_place[3]);
  band.resize(np, n);
  band.setFromTriplets(f.by.begin(), f.by.end());
  AddBandInPlace(uniform->div_y, band, div_y, band_columns[2], band_in_place[2]);
  band_rows.resize(np, n);
  band_rows.setFromTriplets(f.by.begin(), f.by.end());
  AddBandInPlace(uniform->div_y_rows, band_rows, div_y_rows, band_columns[4], band_in_place[4]);
}

// Nitsche's terms on the chords (two-point Gauss) of one triangulation, weighted.
void CutCellStokes::Impl::AddChordTerms(const CutCellGeometry& geo, Triplets& nit, Triplets& cx,
                                        Triplets& cy) const {
  const double gauss[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  for (const CutTriangle& c : geo.cut_triangles()) {
    const Vec2 x0 = NodePosition(grid, c.nodes[0]);
    const double w = weight * 0.5 * (c.chord_b - c.chord_a).norm();
    std::array<double, 3> dn{};
    for (int a = 0; a < 3; ++a) dn[a] = c.grads[a].dot(c.normal);
    const int macro = geo.MacroOf(c.triangle);
    const std::array<int, 3> q = pmap(geo.MacroNodes(macro)), nodes = vmap(c.nodes);
    for (double s : gauss) {
      const Vec2 xq = c.chord_a + s * (c.chord_b - c.chord_a);
      const std::array<double, 3> phi = Basis(x0, c.grads, xq);
      const std::array<double, 3> lam = MacroBasis(geo, macro, xq);
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          nit.emplace_back(nodes[a], nodes[b],
                           w * (-phi[a] * dn[b] - dn[a] * phi[b] +
                                constants.nitsche / grid.h * phi[a] * phi[b]));
          cx.emplace_back(q[a], nodes[b], w * lam[a] * phi[b] * c.normal.x());
          cy.emplace_back(q[a], nodes[b], w * lam[a] * phi[b] * c.normal.y());
        }
      }
    }
  }
}

Vec2 CutCellStokes::Impl::Arm(const Vec2& x, const Vec2& centre) const {
  Vec2 arm = x - centre;
  if (vmap.x) arm.x() -= grid.Width() * std::round(arm.x() / grid.Width());
  if (vmap.y) arm.y() -= grid.Height() * std::round(arm.y() / grid.Height());
  return arm;
}

// Nitsche's load of the boundary value g = U + omega x (x - X) on the chords of one triangulation
// (the same quadrature as AddChordTerms): eta <-d_n phi_a + gamma / h phi_a, g> on the momentum
// rows and <lambda_a, g . n> on the continuity rows (the saddle point's sign of B).
void CutCellStokes::Impl::AddChordLoad(const CutCellGeometry& geo,
                                       const std::vector<RigidMotion>& motions) {
  const double gauss[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  for (const CutTriangle& c : geo.cut_triangles()) {
    const RigidMotion& body = motions.at(static_cast<std::size_t>(c.body));
    const Vec2 x0 = NodePosition(grid, c.nodes[0]);
    const double w = weight * 0.5 * (c.chord_b - c.chord_a).norm();
    const int macro = geo.MacroOf(c.triangle);
    const std::array<int, 3> q = pmap(geo.MacroNodes(macro)), nodes = vmap(c.nodes);
    for (double s : gauss) {
      const Vec2 xq = c.chord_a + s * (c.chord_b - c.chord_a);
      const Vec2 g = body.At(Arm(xq, body.centre));
      const std::array<double, 3> phi = Basis(x0, c.grads, xq);
      const std::array<double, 3> lam = MacroBasis(geo, macro, xq);
      for (int a = 0; a < 3; ++a) {
        const double test =
            w * eta * (-c.grads[a].dot(c.normal) + constants.nitsche / grid.h * phi[a]);
        boundary_u[nodes[a]] += test * g.x();
        boundary_v[nodes[a]] += test * g.y();
        boundary_p[q[a]] += w * lam[a] * g.dot(c.normal);
      }
    }
  }
}

// Nitsche's terms and the ghost penalties.
void CutCellStokes::Impl::AssembleChordForms() {
  const auto n = static_cast<Eigen::Index>(grid.NodeCount());
  const auto np = static_cast<Eigen::Index>(pgrid.NodeCount());
  Triplets nit, cx, cy, gu, gp;
  for (const CutCellGeometry* geo : geos) {
    AddChordTerms(*geo, nit, cx, cy);
    AddGhostPenalty(
        *geo, grid, [&](int t) { return vmap(geo->TriangleNodes(t)); },
        [&](int t) { return geo->TriangleGradients(t); }, [&](int t) { return geo->Active(t); },
        [&](int t) { return geo->State(t) == ElementState::kCut; },
        weight * constants.ghost_velocity * grid.h, gu);
    AddGhostPenalty(
        *geo, pgrid, [&](int m) { return pmap(geo->MacroNodes(m)); },
        [&](int m) { return geo->MacroGradients(m); }, [&](int m) { return geo->MacroActive(m); },
        [&](int m) { return geo->MacroTouched(m); },
        weight * constants.ghost_pressure * std::pow(pgrid.h, 3), gp);
  }
  nitsche.resize(n, n);
  nitsche.setFromTriplets(nit.begin(), nit.end());
  chord_x.resize(np, n);
  chord_x.setFromTriplets(cx.begin(), cx.end());
  chord_y.resize(np, n);
  chord_y.setFromTriplets(cy.begin(), cy.end());
  ghost_u.resize(n, n);
  ghost_u.setFromTriplets(gu.begin(), gu.end());
  ghost_p.resize(np, np);
  ghost_p.setFromTriplets(gp.begin(), gp.end());
}

void CutCellStokes::Impl::NumberUnknowns() {
  vnodes.clear();
  pnodes.clear();
  vindex.assign(grid.NodeCount(), -1);
  for (int j = 0; j <= grid.ny; ++j)
    for (int i = 0; i <= grid.nx; ++i) {
      const std::size_t k = grid.Index(i, j);
      if (!vtopo.IsUnknown(grid, i, j) || !ActiveNode(k)) continue;
      vindex[k] = static_cast<int>(vnodes.size());
      vnodes.push_back(static_cast<int>(k));
    }
  pindex.assign(pgrid.NodeCount(), -1);
  for (int j = 0; j <= pgrid.ny; ++j)
    for (int i = 0; i <= pgrid.nx; ++i) {
      const std::size_t k = pgrid.Index(i, j);
      if (!ptopo.IsUnknown(pgrid, i, j) || !ActivePressureNode(k)) continue;
      pindex[k] = static_cast<int>(pnodes.size());
      pnodes.push_back(static_cast<int>(k));
    }
}

// The reduced saddle point [[A, 0, Bx^T], [0, A, By^T], [Bx, By, -G_p / phi_p]] over the unknowns,
// and the row-major blocks of the iterations: the rows of the full forms at the unknowns, their
// columns renumbered (the numbering keeps the nodes' order, so no sorting).
void CutCellStokes::Impl::BuildReduced() {
  momentum_full.resize(0, 0);  // when GMRES or the direct solve needs it (BuildVelocityRows)
  // A moving body's steps read the force from the columns of the symmetric stiffness and of the
  // divergence instead (Load).
  momentum_rows.resize(0, 0);
  gradient_x_rows.resize(0, 0);
  gradient_y_rows.resize(0, 0);
  if (!band_forms || convection.nonZeros() > 0) {
    momentum_rows = eta * stiffness + rho * convection;
    gradient_x_rows = div_x.transpose();
    gradient_y_rows = div_y.transpose();
  }
  // The pressure penalty's scale phi_p = eta + (rho/dt) H^2 (header), and the Schur complement's
  // diagonal model M_p / eta + G_p / phi_p over the fluid part, held as eta times its inverse's
  // denominator: M_p + (eta / phi_p) G_p.
  const double phi_p = eta + rho_over_dt * pgrid.h * pgrid.h;
  pressure_mass.resize(static_cast<Eigen::Index>(pnodes.size()));
  const Eigen::VectorXd ghost_diagonal = ghost_p.diagonal();
  for (std::size_t k = 0; k < pnodes.size(); ++k)
    pressure_mass[k] = pressure_fluid_mass[pnodes[k]] + eta / phi_p * ghost_diagonal[pnodes[k]];
  const int npu = static_cast<int>(pnodes.size());
  const RowSparse g_rows = ghost_p;
  ReducedRows gg;
  gg.Reserve(g_rows.nonZeros());
  for (int r = 0; r < npu; ++r) {
    gg.Append(g_rows, pnodes[r], pindex, 0, -phi_p);
    gg.EndRow();
  }
  velocity_rows.resize(0, 0);  // when GMRES or the direct solve needs it (BuildVelocityRows)
  BuildDivergenceRows();
  pp = gg.Build(npu, npu);
  saddle_rows.resize(0, 0);
  corrections.Clear();
  // SolveVelocity writes the load at the unknowns only: off them it is 0, not what a node held
  // while it was an unknown (a moving body's former place), which the capacitance solve passes to
  // the unknowns at round-off (a resumed run would differ from the uninterrupted one there).
  std::fill(work_fu.begin(), work_fu.end(), 0.0);
  std::fill(work_fv.begin(), work_fv.end(), 0.0);
  std::fill(work_fp.begin(), work_fp.end(), 0.0);  // the same for SchurInverse's load
  if (exact_velocity) {
    BuildVelocityRows();
    velocity = velocity_rows;
    velocity_lu.compute(velocity);
  }
}

void CutCellStokes::Impl::BuildDivergenceRows() {
  const int nu = static_cast<int>(vnodes.size()), npu = static_cast<int>(pnodes.size());
  // Written straight into the matrices' storage (kept from step to step), at most every entry of
  // div + chord: then cut to the entries kept.
  const Eigen::Index most =
      div_x.nonZeros() + div_y.nonZeros() + chord_x.nonZeros() + chord_y.nonZeros();
  bt.resize(2 * nu, npu);
  bt.resizeNonZeros(most);
  int* outer = bt.outerIndexPtr();
  int* inner = bt.innerIndexPtr();
  double* values = bt.valuePtr();
  int count = 0;
  for (int comp = 0; comp < 2; ++comp) {
    const Sparse& div = comp == 0 ? div_x : div_y;
    const Sparse& chord = comp == 0 ? chord_x : chord_y;
    for (int r = 0; r < nu; ++r) {
      // Column vnodes[r] of div + chord (the sum's entries: d + c where both are stored), at the
      // pressure unknowns, without exact zeros (as ReducedRows).
      ForEachSumEntry(Sparse::InnerIterator(div, vnodes[r]),
                      Sparse::InnerIterator(chord, vnodes[r]), [&](Eigen::Index row, double value) {
                        const int q = pindex[static_cast<std::size_t>(row)];
                        if (q < 0 || value == 0.0) return;
                        inner[count] = q;
                        values[count++] = value;
                      });
      outer[comp * nu + r + 1] = count;
    }
  }
  bt.resizeNonZeros(count);
  // b row by row from the rows of div + chord: a moving body's divergence by rows (kept in place),
  // else made here (a fixed body's operator is built once). The same entries as bt's.
  RowSparse made_x, made_y;
  if (!band_forms) {
    made_x = div_x;
    made_y = div_y;
  }
  const RowSparse& dx = band_forms ? div_x_rows : made_x;
  const RowSparse& dy = band_forms ? div_y_rows : made_y;
  const RowSparse cx = chord_x, cy = chord_y;
  b.resize(npu, 2 * nu);
  b.resizeNonZeros(most);
  outer = b.outerIndexPtr();
  inner = b.innerIndexPtr();
  values = b.valuePtr();
  count = 0;
  for (int r = 0; r < npu; ++r) {
    for (int comp = 0; comp < 2; ++comp) {
      const int offset = comp * nu;
      ForEachSumEntry(RowSparse::InnerIterator(comp == 0 ? dx : dy, pnodes[r]),
                      RowSparse::InnerIterator(comp == 0 ? cx : cy, pnodes[r]),
                      [&](Eigen::Index col, double value) {
                        const int k = vindex[static_cast<std::size_t>(col)];
                        if (k < 0 || value == 0.0) return;
                        inner[count] = offset + k;
                        values[count++] = value;
                      });
    }
    outer[r + 1] = count;
  }
  b.resizeNonZeros(count);
}

const Sparse& CutCellStokes::Impl::MomentumFull() {
  if (momentum_full.rows() == 0) {
    const Sparse diag_mass = Sparse(lumped_mass.asDiagonal());
    momentum_full =
        rho_over_dt * diag_mass + eta * (stiffness + nitsche + ghost_u) + rho * convection;
  }
  return momentum_full;
}

// out += value times column j of MomentumFull, entry by entry as its sum makes them: (rho/dt) m_j
// on the diagonal + eta ((k + n) + g) + rho c, an entry that a matrix does not store read as 0
// (x + 0 is x: the same bits).
void CutCellStokes::Impl::AddMomentumColumn(Eigen::Index j, double value,
                                            Eigen::VectorXd& out) const {
  std::vector<Eigen::Index>& rows = column_rows;
  rows.assign(1, j);
  for (const Sparse* m : {&stiffness, &nitsche, &ghost_u, &convection})
    for (Sparse::InnerIterator it(*m, j); it; ++it) rows.push_back(it.row());
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  for (const Eigen::Index i : rows) {
    const double mass = i == j ? rho_over_dt * lumped_mass[j] : 0.0;
    const double a = mass +
                     eta * ((stiffness.coeff(i, j) + nitsche.coeff(i, j)) + ghost_u.coeff(i, j)) +
                     rho * convection.coeff(i, j);
    out[i] += a * value;
  }
}

// out += value times column j of div + chord (the sum's entries).
void CutCellStokes::Impl::AddDivergenceColumn(const Sparse& div, const Sparse& chord,
                                              Eigen::Index j, double value, Eigen::VectorXd& out) {
  ForEachSumEntry(Sparse::InnerIterator(div, j), Sparse::InnerIterator(chord, j),
                  [&](Eigen::Index i, double entry) { out[i] += entry * value; });
}

// The velocity block A over the unknowns, row by row: GMRES's and the direct solve's only (Uzawa
// solves it by the capacitance matrix), so made when they first need it.
void CutCellStokes::Impl::BuildVelocityRows() {
  if (velocity_rows.rows() > 0 || vnodes.empty()) return;
  const int nu = static_cast<int>(vnodes.size());
  const RowSparse a_full = MomentumFull();
  ReducedRows av;
  av.Reserve(a_full.nonZeros());
  for (int r = 0; r < nu; ++r) {
    av.Append(a_full, vnodes[r], vindex, 0, 1.0);
    av.EndRow();
  }
  velocity_rows = av.Build(nu, nu);
}

// The whole saddle point row by row from its blocks (GMRES and the direct solve).
void CutCellStokes::Impl::BuildSaddleRows() {
  if (saddle_rows.rows() > 0) return;
  BuildVelocityRows();
  const int nu = static_cast<int>(vnodes.size()), npu = static_cast<int>(pnodes.size());
  std::vector<int> identity_index(static_cast<std::size_t>(2 * nu + npu));
  std::iota(identity_index.begin(), identity_index.end(), 0);
  ReducedRows ss;
  ss.Reserve(2 * velocity_rows.nonZeros() + 2 * b.nonZeros() + pp.nonZeros());
  for (int comp = 0; comp < 2; ++comp)
    for (int r = 0; r < nu; ++r) {
      ss.Append(velocity_rows, r, identity_index, comp * nu, 1.0);
      ss.Append(bt, comp * nu + r, identity_index, 2 * nu, 1.0);
      ss.EndRow();
    }
  for (int r = 0; r < npu; ++r) {
    ss.Append(b, r, identity_index, 0, 1.0);
    ss.Append(pp, r, identity_index, 2 * nu, 1.0);
    ss.EndRow();
  }
  saddle_rows = ss.Build(2 * nu + npu, 2 * nu + npu);
}

// The nodes (forms' numbering) whose columns of the cut operator can differ from the uniform one's
// by more than round-off: the nodes of the triangles that are not wholly fluid (their mass,
// stiffness and Nitsche's terms; every node without fluid is one), and of the triangles that share
// a node with those (the ghost penalty's faces join a cut triangle to its neighbours).
std::vector<char> CutCellStokes::Impl::BandNodes() const {
  std::vector<char> touched(grid.NodeCount(), 0), band(grid.NodeCount(), 0);
  for (const CutCellGeometry* geo : geos)
    for (int t = 0; t < geo->TriangleCount(); ++t)
      if (geo->State(t) != ElementState::kFluid)
        for (const int k : vmap(geo->TriangleNodes(t))) touched[static_cast<std::size_t>(k)] = 1;
  for (const CutCellGeometry* geo : geos)
    for (int t = 0; t < geo->TriangleCount(); ++t) {
      const std::array<int, 3> nodes = vmap(geo->TriangleNodes(t));
      if (touched[static_cast<std::size_t>(nodes[0])] ||
          touched[static_cast<std::size_t>(nodes[1])] ||
          touched[static_cast<std::size_t>(nodes[2])])
        for (const int k : nodes) band[static_cast<std::size_t>(k)] = 1;
    }
  return band;
}

// (rho/dt) M_l + eta K over every whole triangle: the fast solver's operator, assembled as the
// fluid forms are (the mean over the triangulations); its columns at the nodes of `columns` only
// (the triangles with a node there, in the same order: those columns' entries are the whole
// assembly's to the bit; the other columns are partial).
Sparse CutCellStokes::Impl::UniformVelocityOperator(const std::vector<char>& columns) const {
  const auto n = static_cast<Eigen::Index>(grid.NodeCount());
  const double whole = 0.5 * grid.h * grid.h;
  Triplets a;
  for (const CutCellGeometry* geo : geos)
    for (int t = 0; t < geo->TriangleCount(); ++t) {
      const std::array<int, 3> nodes = vmap(geo->TriangleNodes(t));
      if (!columns[static_cast<std::size_t>(nodes[0])] &&
          !columns[static_cast<std::size_t>(nodes[1])] &&
          !columns[static_cast<std::size_t>(nodes[2])])
        continue;
      const std::array<Vec2, 3> grads = geo->TriangleGradients(t);
      for (int i = 0; i < 3; ++i) {
        a.emplace_back(nodes[i], nodes[i], weight * rho_over_dt * whole / 3.0);
        for (int j = 0; j < 3; ++j)
          a.emplace_back(nodes[i], nodes[j], weight * eta * whole * grads[i].dot(grads[j]));
      }
    }
  Sparse uniform(n, n);
  uniform.setFromTriplets(a.begin(), a.end());
  return uniform;
}

// A moving body's difference of the cut operator and the uniform one: the band's mass, the
// stiffness's correction, Nitsche and the ghost penalty (in a column of a node without fluid the
// correction is -A_0's entry up to round-off), (rho/dt) dM + eta ((dK + N) + G_u), in the columns
// of the unknowns and the rows of the active ones. Made column by column (a column without band
// entries skipped at once), each entry the sum's own terms in its order (a term that a matrix does
// not store is left out, as Eigen's sum of the matrices leaves it out), written straight into the
// matrix's storage: the same entries, to the bit, as that sum filtered, without the whole grid's
// sums and triplets.
// The mass's difference only where it is not 0 (the band's nodes).
Sparse CutCellStokes::Impl::BandDifference(const std::vector<char>& unknown) const {
  const auto n = static_cast<Eigen::Index>(grid.NodeCount());
  std::vector<int> outer(static_cast<std::size_t>(n) + 1, 0), inner;
  std::vector<double> values;
  struct Term {
    int row;
    int matrix;  // 0: dK, 1: N, 2: G_u
    double value;
  };
  std::vector<Term> terms;
  const std::array<const Sparse*, 3> parts{&band_stiffness, &nitsche, &ghost_u};
  for (Eigen::Index col = 0; col < n; ++col) {
    outer[static_cast<std::size_t>(col)] = static_cast<int>(values.size());
    if (!unknown[static_cast<std::size_t>(col)]) continue;
    const double mass = lumped_mass[col] - uniform->lumped_mass[col];
    terms.clear();
    for (int m = 0; m < 3; ++m)
      for (Sparse::InnerIterator it(*parts[static_cast<std::size_t>(m)], col); it; ++it)
        terms.push_back({static_cast<int>(it.row()), m, it.value()});
    if (terms.empty() && mass == 0.0) continue;
    // By row, and within a row in the matrices' order (each stores a row once).
    std::sort(terms.begin(), terms.end(), [](const Term& a, const Term& b) {
      return a.row != b.row ? a.row < b.row : a.matrix < b.matrix;
    });
    bool mass_done = mass == 0.0;
    auto emit = [&](int row, double value) {
      if (vindex[static_cast<std::size_t>(row)] < 0) return;
      inner.push_back(row);
      values.push_back(value);
    };
    for (std::size_t e = 0; e < terms.size();) {
      const int row = terms[e].row;
      if (!mass_done && col < row) {  // the mass alone on the diagonal, before this row
        emit(static_cast<int>(col), rho_over_dt * mass);
        mass_done = true;
      }
      // ((dK + N) + G_u): a sum of the terms present, left to right in the matrices' order.
      double sum = terms[e].value;
      for (++e; e < terms.size() && terms[e].row == row; ++e) sum = sum + terms[e].value;
      double value = eta * sum;
      if (!mass_done && row == col) {
        value = rho_over_dt * mass + value;
        mass_done = true;
      }
      emit(row, value);
    }
    if (!mass_done) emit(static_cast<int>(col), rho_over_dt * mass);
  }
  outer[static_cast<std::size_t>(n)] = static_cast<int>(values.size());
  Sparse difference(n, n);
  difference.resizeNonZeros(static_cast<Eigen::Index>(values.size()));
  std::copy(outer.begin(), outer.end(), difference.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), difference.innerIndexPtr());
  std::copy(values.begin(), values.end(), difference.valuePtr());
  return difference;
}

// The capacitance matrix of the Stokes velocity block (Oseen term left out) against the fast
// solver: the difference of the extended cut operator and the uniform one, over the fast solver's
// unknowns (particles/cut_cell_capacitance.h). Entries below 1e-12 of the largest are the two
// assemblies' round-off (the sums run in different orders).
void CutCellStokes::Impl::BuildCapacitance() {
  const auto n = static_cast<Eigen::Index>(grid.NodeCount());
  if (fast_unknown.empty()) {
    fast_unknown.assign(grid.NodeCount(), 0);
    for (int j = 0; j <= grid.ny; ++j)
      for (int i = 0; i <= grid.nx; ++i)
        fast_unknown[grid.Index(i, j)] = vtopo.IsUnknown(grid, i, j);
  }
  const std::vector<char>& unknown = fast_unknown;
  if (band_forms) {
    capacitance = std::make_unique<CutCellCapacitance>(*fast_velocity, BandDifference(unknown),
                                                       1e-12, responses.get());
    return;
  }
  // The columns off the band differ by the two assemblies' round-off only, which the capacitance
  // drops (below 1e-12 of the largest entry, a band's): they are not formed.
  const std::vector<char> band = BandNodes();
  const Sparse cut =
      rho_over_dt * Sparse(lumped_mass.asDiagonal()) + eta * (stiffness + nitsche + ghost_u);
  const Sparse uniform = UniformVelocityOperator(band);
  Triplets d;
  for (int col = 0; col < n; ++col) {
    if (!unknown[col] || !band[static_cast<std::size_t>(col)]) continue;
    for (Sparse::InnerIterator it(cut, col); it; ++it)
      if (vindex[it.row()] >= 0 && vindex[col] >= 0)
        d.emplace_back(static_cast<int>(it.row()), col, it.value());
    for (Sparse::InnerIterator it(uniform, col); it; ++it)
      if (vindex[it.row()] >= 0) d.emplace_back(static_cast<int>(it.row()), col, -it.value());
  }
  Sparse difference(n, n);
  difference.setFromTriplets(d.begin(), d.end());
  capacitance = std::make_unique<CutCellCapacitance>(*fast_velocity, difference, 1e-12);
}

// The Laplacian part of Cahouet-Chabard's S~ on the fluid part: the Schur complement is about
// (dt/rho) (K_p + (rho/dt) / phi_p G_p) where the mass term rules (B M_l^-1 B^T ~ K_p), K_p the
// P1 stiffness of the pressure over the fluid part of the macro-triangles (Neumann on the chords).
// It differs from the fast solver's (the whole grid's) in the rows of the macro-triangles cut by or
// inside the bodies, and by the ghost penalty: a capacitance matrix of that rank, extended by the
// uniform rows at the pressure nodes without fluid, as the velocity's. Fixed bodies with a
// Dirichlet pressure side only (a regular fast solver; a moving body's band changes every step).
void CutCellStokes::Impl::BuildPressureCapacitance() {
  pressure_capacitance.reset();
  if (ptopo.HasNullSpace() || band_forms || !constants.fluid_pressure_laplacian) return;
  const auto np = static_cast<Eigen::Index>(pgrid.NodeCount());
  Triplets band;
  auto add = [&](const CutCellGeometry& geo, int t, double area) {
    const int macro = geo.MacroOf(t);
    const std::array<int, 3> q = pmap(geo.MacroNodes(macro));
    const std::array<Vec2, 3> g = geo.MacroGradients(macro);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) band.emplace_back(q[a], q[b], weight * area * g[a].dot(g[b]));
  };
  const double whole = 0.5 * grid.h * grid.h;
  for (const CutCellGeometry* geo : geos) {
    for (int t = 0; t < geo->TriangleCount(); ++t)
      if (geo->State(t) != ElementState::kFluid) add(*geo, t, -whole);
    for (const CutTriangle& c : geo->cut_triangles()) add(*geo, c.triangle, c.area);
  }
  Sparse k_band(np, np);
  k_band.setFromTriplets(band.begin(), band.end());
  const double phi_p = eta + rho_over_dt * pgrid.h * pgrid.h;
  const Sparse cut = k_band + (rho_over_dt / phi_p) * ghost_p;
  Triplets d;
  for (int j = 0; j <= pgrid.ny; ++j)
    for (int i = 0; i <= pgrid.nx; ++i) {
      if (!ptopo.IsUnknown(pgrid, i, j)) continue;
      const auto col = static_cast<Eigen::Index>(pgrid.Index(i, j));
      for (Sparse::InnerIterator it(cut, col); it; ++it)
        if (pindex[static_cast<std::size_t>(it.row())] >= 0)
          d.emplace_back(static_cast<int>(it.row()), static_cast<int>(col), it.value());
    }
  Sparse difference(np, np);
  difference.setFromTriplets(d.begin(), d.end());
  pressure_capacitance = std::make_unique<CutCellCapacitance>(*fast_pressure, difference, 1e-12);
}

void CutCellStokes::Impl::Precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  const int nu = static_cast<int>(vnodes.size()), npu = static_cast<int>(pnodes.size());
  z.resize(r.size());
  // The pressure first: z_p = -S~^-1 r_p.
  Eigen::VectorXd zp;
  SchurInverse(r.tail(npu), zp);
  z.tail(npu) = -zp;
  // Then the velocity of r_u - B^T z_p (block upper-triangular).
  const Eigen::VectorXd ru = r.head(2 * nu) - bt * z.tail(npu);
  Eigen::VectorXd zu;
  if (exact_velocity) {
    zu.resize(2 * nu);
    zu.head(nu) = velocity_lu.solve(ru.head(nu));
    zu.tail(nu) = velocity_lu.solve(ru.tail(nu));
  } else {
    SolveVelocity(ru, zu);
  }
  z.head(2 * nu) = zu;
}

// Cahouet-Chabard's S~^-1 r = eta M_p^-1 r + (rho/dt) K_p^-1 r at the pressure unknowns.
void CutCellStokes::Impl::SchurInverse(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  const int npu = static_cast<int>(pnodes.size());
  z = eta * r.cwiseQuotient(pressure_mass);
  if (!fast_pressure) return;
  // work_fp is 0 off the pressure unknowns (BuildReduced) and the solves read it at the unknowns
  // only; work_p is read at the Dirichlet nodes only, which hold 0 (the fast solver leaves them,
  // the capacitance solve zeroes them).
  for (int k = 0; k < npu; ++k) work_fp[pnodes[k]] = r[k];
  if (pressure_capacitance) {
    pressure_capacitance->Solve(work_fp.data(), work_p.data());
  } else {
    fast_pressure->Solve(work_fp.data(), work_p.data());
  }
  for (int k = 0; k < npu; ++k) z[k] += rho_over_dt * work_p[pnodes[k]];
}

// z = A^-1 r for both components of the Stokes velocity block (no Oseen term), exactly: the
// capacitance solve.
void CutCellStokes::Impl::SolveVelocity(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  const int nu = static_cast<int>(vnodes.size());
  for (int k = 0; k < nu; ++k) {
    work_fu[vnodes[k]] = r[k];
    work_fv[vnodes[k]] = r[nu + k];
  }
  capacitance->SolvePair(work_fu.data(), work_u.data(), work_fv.data(), work_v.data());
  z.resize(2 * nu);
  for (int k = 0; k < nu; ++k) {
    z[k] = work_u[vnodes[k]];
    z[nu + k] = work_v[vnodes[k]];
  }
}

// Load's sums over the unknowns: F = -sum_k (eta K u + mass u - B^T p)_k over the body's nodes
// k within 1.5 h (no Oseen term: K and B's columns), T = -sum_k arm_k x (the same)_k.
CutCellStokes::Impl::LoadRows CutCellStokes::Impl::BuildLoadRows(const LoadStop& stop) const {
  const int nu = static_cast<int>(vnodes.size());
  const CutCellGeometry& geo = *geos[0];
  LoadRows out;
  out.force_bound = stop.force_bound;
  out.torque_bound = stop.torque_bound;
  for (std::size_t i = 0; i < stop.bodies.size(); ++i) {
    std::map<int, double> fx, fy, tq;
    for (std::size_t k = 0; k < grid.NodeCount(); ++k) {
      if (geo.NearestBody(k) != stop.bodies[i] || geo.distance()[k] >= 1.5 * grid.h) continue;
      if (!ActiveNode(k)) continue;
      const Vec2 arm = Arm(NodePosition(grid, static_cast<int>(k)), stop.centres[i]);
      // (ru, rv)_k = sum_j a_j (u_j, v_j) + sum_q (d_x, d_y)_q p_q: F -= (ru, rv),
      // T -= arm_x rv - arm_y ru.
      auto velocity = [&](int j, double a) {
        const int r = vindex[static_cast<std::size_t>(j)];
        if (r < 0 || a == 0.0) return;
        fx[r] -= a;
        fy[nu + r] -= a;
        tq[r] += arm.y() * a;
        tq[nu + r] -= arm.x() * a;
      };
      const auto col = static_cast<Eigen::Index>(k);
      for (Sparse::InnerIterator it(stiffness, col); it; ++it)
        velocity(static_cast<int>(it.row()), eta * it.value());
      velocity(static_cast<int>(k), rho_over_dt * lumped_mass[col]);
      for (Sparse::InnerIterator it(div_x, col); it; ++it) {
        const int r = pindex[static_cast<std::size_t>(it.row())];
        if (r < 0) continue;
        fx[2 * nu + r] -= it.value();
        tq[2 * nu + r] += arm.y() * it.value();
      }
      for (Sparse::InnerIterator it(div_y, col); it; ++it) {
        const int r = pindex[static_cast<std::size_t>(it.row())];
        if (r < 0) continue;
        fy[2 * nu + r] -= it.value();
        tq[2 * nu + r] -= arm.x() * it.value();
      }
    }
    for (const std::map<int, double>* row : {&fx, &fy, &tq}) {
      out.rows.emplace_back(row->begin(), row->end());
      double sum = 0.0;
      for (const auto& [unknown, c] : *row)
        if (unknown >= 2 * nu) sum += c;
      out.pressure_sums.push_back(sum);
    }
  }
  if (ptopo.HasNullSpace()) {
    out.mean_weights.resize(static_cast<Eigen::Index>(pnodes.size()));
    for (std::size_t k = 0; k < pnodes.size(); ++k)
      out.mean_weights[static_cast<Eigen::Index>(k)] = pressure_fluid_mass[pnodes[k]];
    out.mean_weights /= out.mean_weights.sum();
  }
  return out;
}

bool CutCellStokes::Impl::LoadSettled(const LoadRows& load, double alpha, const Eigen::VectorXd& w,
                                      const Eigen::VectorXd& d, int nu) {
  const int velocities = 2 * nu;
  const double mean = load.mean_weights.size() > 0 ? load.mean_weights.dot(d) : 0.0;
  std::vector<double> change;
  for (std::size_t i = 0; i < load.rows.size(); ++i) {
    double sum = -load.pressure_sums[i] * mean;
    for (const auto& [unknown, c] : load.rows[i])
      sum += c * (unknown < velocities ? -w[unknown] : d[unknown - velocities]);
    change.push_back(alpha * sum);
  }
  for (std::size_t i = 0; i < load.force_bound.size(); ++i) {
    if (std::hypot(change[3 * i], change[3 * i + 1]) > load.force_bound[i]) return false;
    if (std::abs(change[3 * i + 2]) > load.torque_bound[i]) return false;
  }
  return true;
}

// Uzawa / preconditioned CG on the pressure (header): u = A^-1 (f - B^T p) exactly, CG on
// S p = B A^-1 f - g with S = B A^-1 B^T + G_p / phi_p (symmetric positive definite) and Cahouet-
// Chabard's S~^-1, until the saddle point's residual, which is then its continuity part, is below
// tolerance |rhs|; then the true continuity residual b - B u + (G_p / phi_p) p decides (a restart
// from u(p) if round-off left it above). The momentum part is the exact velocity solves' round-off
// (at most 7.4e-13 |rhs| on Schaefer-Turek at D/h = 9.76 and 19.5, against the tolerance 1e-7:
// docs/evidence/cut_cell_boundary.md, "The Uzawa step's cost at D/h = 19.5"), so it is not formed.
// With a LoadStop (load) it also iterates, at least once, until an iteration changes each listed
// body's load within its bound.
GmresResult CutCellStokes::Impl::SolveSchur(const Eigen::VectorXd& rhs, Eigen::VectorXd& x,
                                            double tolerance, int max_iterations,
                                            const LoadRows* load) {
  const int nu = static_cast<int>(vnodes.size()), npu = static_cast<int>(pnodes.size());
  GmresResult result;
  const double b_norm = rhs.norm();
  if (b_norm == 0.0) {
    x.setZero();
    result.converged = true;
    return result;
  }
  Eigen::VectorXd u(2 * nu), p = x.tail(npu), w, z, d, sd, btd(2 * nu);
  RemovePressureMean(p);
  for (int restart = 0; restart < 3; ++restart) {
    SolveVelocity(rhs.head(2 * nu) - bt * p, u);
    Eigen::VectorXd r = b * u + pp * p - rhs.tail(npu);  // -(the continuity residual)
    // The first pass of a step that needs iterations starts from the Galerkin correction in the
    // span of the earlier steps' corrections, and adds its own correction to them.
    const bool keep = restart == 0 && r.norm() > tolerance * b_norm;
    Eigen::VectorXd p0, u0, r0;
    if (keep) {
      corrections.Project(p, u, r);
      p0 = p;
      u0 = u;
      r0 = r;
    }
    double rz = 0.0;
    bool started = false;  // S~^-1 r only once an iteration is needed
    // The loads' change over the last iteration within their bounds (LoadStop).
    bool settled = load == nullptr || result.iterations > 0;
    while ((r.norm() > tolerance * b_norm || !settled) && result.iterations < max_iterations) {
      if (!started) {
        SchurInverse(r, z);
        d = z;
        rz = r.dot(z);
        started = true;
      }
      btd.noalias() = bt * d;  // into the same storage every iteration (the same sums)
      SolveVelocity(btd, w);
      sd = b * w - pp * d;
      const double alpha = rz / d.dot(sd);
      p += alpha * d;
      u -= alpha * w;
      r -= alpha * sd;
      ++result.iterations;
      if (load) settled = LoadSettled(*load, alpha, w, d, nu);
      SchurInverse(r, z);
      const double rz_next = r.dot(z);
      d = z + (rz_next / rz) * d;
      rz = rz_next;
    }
    if (keep && started) corrections.Add(p - p0, r0 - r, u0 - u);
    RemovePressureMean(p);
    x.head(2 * nu) = u;
    x.tail(npu) = p;
    result.relative_residual = (rhs.tail(npu) - b * u - pp * p).norm() / b_norm;
    result.converged = result.relative_residual <= tolerance;
    if (result.converged || result.iterations >= max_iterations) break;
  }
  return result;
}

// The load at the unknowns less the coupling to the Dirichlet data (gu, gv: the data, 0 elsewhere).
Eigen::VectorXd CutCellStokes::Impl::RightHandSide(const BoundaryData& data, const double* fu,
                                                   const double* fv, std::vector<double>& gu,
                                                   std::vector<double>& gv) const {
  const std::size_t n = grid.NodeCount();
  gu.assign(n, 0.0);
  gv.assign(n, 0.0);
  data.Apply(gu.data(), gv.data());
  for (std::size_t k = 0; k < n; ++k)
    if (vindex[k] >= 0) gu[k] = gv[k] = 0.0;
  // A u_D and B u_D over the columns of the nodes with data only (the sides': the products of the
  // whole matrices, term by term in the same order, without the columns that would add 0).
  const auto nodes = static_cast<Eigen::Index>(n);
  Eigen::VectorXd au = Eigen::VectorXd::Zero(nodes), av = Eigen::VectorXd::Zero(nodes);
  Eigen::VectorXd bxu = Eigen::VectorXd::Zero(div_x.rows());
  Eigen::VectorXd byv = Eigen::VectorXd::Zero(div_y.rows());
  for (Eigen::Index j = 0; j < nodes; ++j) {
    const double dj = gu[static_cast<std::size_t>(j)], ej = gv[static_cast<std::size_t>(j)];
    if (dj != 0.0) {
      AddMomentumColumn(j, dj, au);
      AddDivergenceColumn(div_x, chord_x, j, dj, bxu);
    }
    if (ej != 0.0) {
      AddMomentumColumn(j, ej, av);
      AddDivergenceColumn(div_y, chord_y, j, ej, byv);
    }
  }
  const Eigen::VectorXd bu = bxu + byv;
  const int nu = static_cast<int>(vnodes.size()), npu = static_cast<int>(pnodes.size());
  Eigen::VectorXd rhs(2 * nu + npu);
  for (int k = 0; k < nu; ++k) {
    rhs[k] = (fu ? fu[vnodes[k]] : 0.0) - au[vnodes[k]];
    rhs[nu + k] = (fv ? fv[vnodes[k]] : 0.0) - av[vnodes[k]];
  }
  for (int k = 0; k < npu; ++k) rhs[2 * nu + k] = -bu[pnodes[k]];
  if (boundary_u.size() > 0) {
    for (int k = 0; k < nu; ++k) {
      rhs[k] += boundary_u[vnodes[k]];
      rhs[nu + k] += boundary_v[vnodes[k]];
    }
    for (int k = 0; k < npu; ++k) rhs[2 * nu + k] += boundary_p[pnodes[k]];
  }
  return rhs;
}

void CutCellStokes::Impl::Scatter(const Eigen::VectorXd& x, const std::vector<double>& gu,
                                  const std::vector<double>& gv, double* u, double* v,
                                  double* p) const {
  const int nu = static_cast<int>(vnodes.size());
  std::copy(gu.begin(), gu.end(), u);
  std::copy(gv.begin(), gv.end(), v);
  for (int k = 0; k < nu; ++k) {
    u[vnodes[k]] = x[k];
    v[vnodes[k]] = x[nu + k];
  }
  std::fill(p, p + pgrid.NodeCount(), 0.0);
  for (std::size_t k = 0; k < pnodes.size(); ++k) p[pnodes[k]] = x[2 * nu + static_cast<int>(k)];
  // The repeats of a periodic pair.
  for (std::size_t k = 0; k < grid.NodeCount(); ++k) {
    const auto first = static_cast<std::size_t>(vmap(static_cast<int>(k)));
    u[k] = u[first];
    v[k] = v[first];
  }
  for (std::size_t k = 0; k < pgrid.NodeCount(); ++k)
    p[k] = p[static_cast<std::size_t>(pmap(static_cast<int>(k)))];
}

// Without a Dirichlet pressure side (no outflow side: periodic or closed boxes) p is determined up
// to a constant, which the forms do not see (B^T 1 = 0: the fluid part's divergence theorem with
// the chords); the mean over the fluid part, weighted by int_fluid q_Q, is made 0.
void CutCellStokes::Impl::RemovePressureMean(Eigen::VectorXd& p) const {
  if (!ptopo.HasNullSpace()) return;
  double mean = 0.0, area = 0.0;
  for (std::size_t k = 0; k < pnodes.size(); ++k) {
    const double w = pressure_fluid_mass[pnodes[k]];
    mean += w * p[static_cast<Eigen::Index>(k)];
    area += w;
  }
  p.array() -= mean / area;
}

CutCellStokes::CutCellStokes(const CutCellGeometry& geometry, const DomainParams& domain,
                             double viscosity, double density, double rho_over_dt,
                             const CutCellConstants& constants)
    : impl_(std::make_unique<Impl>(std::vector<const CutCellGeometry*>{&geometry}, domain,
                                   viscosity, density, rho_over_dt, constants)) {}

CutCellStokes::CutCellStokes(const CutCellGeometry& sw_ne, const CutCellGeometry& nw_se,
                             const DomainParams& domain, double viscosity, double density,
                             double rho_over_dt, const CutCellConstants& constants)
    : impl_(std::make_unique<Impl>(std::vector<const CutCellGeometry*>{&sw_ne, &nw_se}, domain,
                                   viscosity, density, rho_over_dt, constants)) {
  if (sw_ne.triangulation() != CutTriangulation::kSwNe ||
      nw_se.triangulation() != CutTriangulation::kNwSe)
    throw std::invalid_argument("CutCellStokes: the SW-NE geometry first, then the NW-SE one");
}

CutCellStokes::~CutCellStokes() = default;

std::size_t CutCellStokes::NodeCount() const { return impl_->grid.NodeCount(); }
int CutCellStokes::VelocityUnknowns() const { return static_cast<int>(impl_->vnodes.size()); }
int CutCellStokes::PressureUnknowns() const { return static_cast<int>(impl_->pnodes.size()); }
int CutCellStokes::CapacitanceRank() const { return impl_->capacitance->Rank(); }
int CutCellStokes::CapacitanceFastSolves() const { return impl_->capacitance->FastSolvesAtSetUp(); }
bool CutCellStokes::CapacitanceSumsResponses() const {
  return impl_->capacitance->LocalCorrection();
}

void CutCellStokes::Recut() { impl_->Recut(); }

void CutCellStokes::SetExactVelocityPreconditioner(bool exact) {
  impl_->exact_velocity = exact;
  impl_->BuildReduced();
}

const PressureCorrections& CutCellStokes::Corrections() const { return impl_->corrections.Data(); }

void CutCellStokes::RestoreCorrections(PressureCorrections corrections) {
  const auto nu = static_cast<Eigen::Index>(impl_->vnodes.size());
  const auto npu = static_cast<Eigen::Index>(impl_->pnodes.size());
  const std::size_t count = corrections.q.size();
  bool fits = count <= PressureCorrectionBasis::kCapacity && corrections.sq.size() == count &&
              corrections.wq.size() == count;
  for (std::size_t i = 0; fits && i < count; ++i) {
    fits = corrections.q[i].size() == npu && corrections.sq[i].size() == npu &&
           corrections.wq[i].size() == 2 * nu;
  }
  if (!fits) {
    throw InvalidParameter("checkpoint:/cut_cell_start", "pressure corrections of other sizes",
                           "at most " + std::to_string(PressureCorrectionBasis::kCapacity) +
                               " of " + std::to_string(npu) + " pressure and " +
                               std::to_string(2 * nu) + " velocity unknowns (the same scene)");
  }
  impl_->corrections.Restore(std::move(corrections));
}

void CutCellStokes::SetBodyMotion(const std::vector<RigidMotion>& motions) {
  Impl& m = *impl_;
  m.boundary_u.resize(0);
  m.boundary_v.resize(0);
  m.boundary_p.resize(0);
  if (motions.empty()) return;
  const auto n = static_cast<Eigen::Index>(m.grid.NodeCount());
  m.boundary_u = Eigen::VectorXd::Zero(n);
  m.boundary_v = Eigen::VectorXd::Zero(n);
  m.boundary_p = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m.pgrid.NodeCount()));
  for (const CutCellGeometry* geo : m.geos) m.AddChordLoad(*geo, motions);
}

void CutCellStokes::SetAdvection(const double* wu, const double* wv) {
  Impl& m = *impl_;
  const auto n = static_cast<Eigen::Index>(m.grid.NodeCount());
  m.convection.resize(n, n);
  if (wu != nullptr) {
    // rho ((w . grad) u, v) with w the P1 interpolant: C_ij = sum_k M_ik w_k . grad phi_j.
    Triplets c;
    auto add = [&](const std::array<int, 3>& mesh_nodes, const std::array<Vec2, 3>& grads,
                   const std::array<std::array<double, 3>, 3>& mass) {
      const std::array<int, 3> nodes = m.vmap(mesh_nodes);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          double value = 0.0;
          for (int k = 0; k < 3; ++k)
            value += mass[i][k] * (wu[nodes[k]] * grads[j].x() + wv[nodes[k]] * grads[j].y());
          c.emplace_back(nodes[i], nodes[j], m.weight * value);
        }
    };
    const double e = m.grid.h * m.grid.h / 24.0;  // |T| / 12 with |T| = h^2 / 2
    const std::array<std::array<double, 3>, 3> whole{{{2 * e, e, e}, {e, 2 * e, e}, {e, e, 2 * e}}};
    for (const CutCellGeometry* geo : m.geos) {
      for (int t = 0; t < geo->TriangleCount(); ++t)
        if (geo->State(t) == ElementState::kFluid)
          add(geo->TriangleNodes(t), geo->TriangleGradients(t), whole);
      for (const CutTriangle& cut : geo->cut_triangles()) add(cut.nodes, cut.grads, cut.mass);
    }
    m.convection.setFromTriplets(c.begin(), c.end());
  }
  m.BuildReduced();
}

CutCellReport CutCellStokes::Solve(const BoundaryData& data, const double* fu, const double* fv,
                                   double* u, double* v, double* p, double tolerance,
                                   int max_iterations, const LoadStop* stop) {
  Impl& m = *impl_;
  std::vector<double> gu, gv;
  const Eigen::VectorXd rhs = m.RightHandSide(data, fu, fv, gu, gv);
  const int nu = static_cast<int>(m.vnodes.size());
  Eigen::VectorXd x(rhs.size());
  for (int k = 0; k < nu; ++k) {
    x[k] = u[m.vnodes[k]];
    x[nu + k] = v[m.vnodes[k]];
  }
  for (std::size_t k = 0; k < m.pnodes.size(); ++k)
    x[2 * nu + static_cast<int>(k)] = p[m.pnodes[k]];
  const bool uzawa = m.convection.nonZeros() == 0 && !m.exact_velocity;
  if (!uzawa) m.BuildSaddleRows();
  Impl::LoadRows load;
  if (uzawa && stop) load = m.BuildLoadRows(*stop);
  const GmresResult result =
      uzawa
          ? m.SolveSchur(rhs, x, tolerance, max_iterations, stop ? &load : nullptr)
          : SolveGmres(
                [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = m.saddle_rows * in; },
                [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { m.Precondition(in, out); },
                rhs, x, tolerance, max_iterations, m.constants.restart);
  if (!result.converged) {
    std::ostringstream what;
    what << "cut-cell Stokes: " << (uzawa ? "Uzawa" : "GMRES") << " did not reach " << tolerance
         << " in " << result.iterations << " iterations (relative residual "
         << result.relative_residual << ")";
    throw SolverNotConverged(what.str());
  }
  m.Scatter(x, gu, gv, u, v, p);
  return {result.iterations, result.relative_residual, static_cast<int>(rhs.size())};
}

void CutCellStokes::SolveDirect(const BoundaryData& data, const double* fu, const double* fv,
                                double* u, double* v, double* p) {
  Impl& m = *impl_;
  std::vector<double> gu, gv;
  const Eigen::VectorXd rhs = m.RightHandSide(data, fu, fv, gu, gv);
  Eigen::SparseLU<Sparse> lu;
  m.BuildSaddleRows();
  lu.compute(Sparse(m.saddle_rows));
  if (lu.info() != Eigen::Success)
    throw SolverNotConverged("cut-cell Stokes: singular saddle point");
  m.Scatter(lu.solve(rhs), gu, gv, u, v, p);
}

Vec2 CutCellStokes::Force(int body, const double* u, const double* v, const double* p) const {
  return Load(body, Vec2::Zero(), u, v, p, nullptr, nullptr).force;
}

CutCellStokes::BodyLoad CutCellStokes::Load(int body, const Vec2& centre, const double* u,
                                            const double* v, const double* p, const double* fu,
                                            const double* fv) const {
  const Impl& m = *impl_;
  const auto n = static_cast<Eigen::Index>(m.grid.NodeCount());
  const auto np = static_cast<Eigen::Index>(m.pgrid.NodeCount());
  const Eigen::Map<const Eigen::VectorXd> uu(u, n), vv(v, n), pp(p, np);
  BodyLoad load;
  const CutCellGeometry& geo = *m.geos[0];
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto node = static_cast<std::size_t>(k);
    if (geo.NearestBody(node) != body || geo.distance()[node] >= 1.5 * m.grid.h) continue;
    if (!m.ActiveNode(node)) continue;  // no fluid in its support: a residual of 0
    const double mass = m.rho_over_dt * m.lumped_mass[k];
    double ru = 0.0, rv = 0.0;
    if (m.momentum_rows.rows() > 0) {
      ru = m.momentum_rows.row(k).dot(uu) + m.gradient_x_rows.row(k).dot(pp);
      rv = m.momentum_rows.row(k).dot(vv) + m.gradient_y_rows.row(k).dot(pp);
    } else {  // no Oseen term: row k of K is its column, -B^T's rows are B's columns
      double ku = 0.0, kv = 0.0, gx = 0.0, gy = 0.0;
      for (Sparse::InnerIterator it(m.stiffness, k); it; ++it) {
        ku += m.eta * it.value() * uu[it.row()];
        kv += m.eta * it.value() * vv[it.row()];
      }
      for (Sparse::InnerIterator it(m.div_x, k); it; ++it) gx += it.value() * pp[it.row()];
      for (Sparse::InnerIterator it(m.div_y, k); it; ++it) gy += it.value() * pp[it.row()];
      ru = ku + gx;
      rv = kv + gy;
    }
    ru = ru + mass * uu[k] - (fu ? fu[k] : 0.0);  // the order of the sums of the rows' form
    rv = rv + mass * vv[k] - (fv ? fv[k] : 0.0);
    const Vec2 arm = m.Arm(NodePosition(m.grid, static_cast<int>(k)), centre);  // the image
    load.force -= Vec2(ru, rv);
    load.torque -= arm.x() * rv - arm.y() * ru;
  }
  return load;
}

const Eigen::VectorXd& CutCellStokes::FluidMass() const { return impl_->lumped_mass; }

int SolveSteadyNavierStokes(CutCellStokes& flow, const BoundaryData& data, double* u, double* v,
                            double* p, double tolerance, int max_iterations, double change,
                            int max_picard, CutCellLinearSolver solver) {
  const std::size_t n = flow.NodeCount();
  flow.SetExactVelocityPreconditioner(solver == CutCellLinearSolver::kGmresExactVelocity);
  auto solve_once = [&] {
    if (solver == CutCellLinearSolver::kDirect) {
      flow.SolveDirect(data, nullptr, nullptr, u, v, p);
    } else {
      flow.Solve(data, nullptr, nullptr, u, v, p, tolerance, max_iterations);
    }
  };
  flow.SetAdvection(nullptr, nullptr);
  solve_once();
  double last = 1.0;
  for (int solve = 2; solve <= max_picard + 1; ++solve) {
    const std::vector<double> wu(u, u + n), wv(v, v + n);
    flow.SetAdvection(wu.data(), wv.data());
    solve_once();
    double diff = 0.0, norm = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      diff += (u[k] - wu[k]) * (u[k] - wu[k]) + (v[k] - wv[k]) * (v[k] - wv[k]);
      norm += u[k] * u[k] + v[k] * v[k];
    }
    last = std::sqrt(diff / norm);
    if (last < change) return solve;
  }
  std::ostringstream what;
  what << "cut-cell steady Navier-Stokes: the velocity still changed by " << last << " after "
       << max_picard << " Oseen solves";
  throw SolverNotConverged(what.str());
}

}  // namespace dlmfd
