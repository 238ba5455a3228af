// The drag of a fixed disk with the cut-cell boundary (particles/cut_cell_stokes.h) over sub-grid
// positions: the engine's side of docs/evidence/cut_cell_boundary.md, "A second-order boundary: the
// engine's cut cells". Prints one CSV line per shift in the format of bench/boundary_prototypes.py
// (method, D/h, shift in h, F_x, F_y, unknowns, seconds; then the solver's iterations), so that
// script's `table` command reads both:
//   cut_cell_drag creeping D_OVER_H SHIFT...        steady Stokes, the creeping disk (eta = 1, D =
//                                                    0.1 at (0.2 + s h, 0.2) in 0.8 x 0.4,
//                                                    Poiseuille inflow of maximum 0.3)
//   cut_cell_drag schaefer_turek D_OVER_H SHIFT...  Schaefer-Turek 2D-1 (2.2 x 0.41, nu = 1e-3,
//                                                    steady Navier-Stokes by Picard iterations to
//                                                    a velocity change of 1e-8; F_x, F_y printed
//                                                    as C_D = 500 F_x, C_L = 500 F_y)
// Options after the shifts: --ghost G_U --ghost-p G_P (the ghost penalties); --both (every form
// the mean over the SW-NE and NW-SE triangulations); --direct (sparse direct solves instead of
// the iterative solves); --exact-velocity (GMRES preconditioned by the velocity block's
// factorization). On stderr: the rank of the capacitance matrix (particles/cut_cell_capacitance.h).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/particles/cut_cell_stokes.h"

namespace {

using dlmfd::Vec2;

struct Case {
  bool navier_stokes = false;
  Vec2 size;
  double viscosity = 1.0;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr,
                 "usage: cut_cell_drag creeping|schaefer_turek D_OVER_H SHIFT... "
                 "[--ghost G_U --ghost-p G_P]\n");
    return 2;
  }
  const std::string name = argv[1];
  Case c;
  if (name == "creeping") {
    c.size = Vec2(0.8, 0.4);
  } else if (name == "schaefer_turek") {
    c = {true, Vec2(2.2, 0.41), 1e-3};
  } else {
    std::fprintf(stderr, "unknown case %s: creeping or schaefer_turek\n", name.c_str());
    return 2;
  }
  const double d_over_h = std::atof(argv[2]);
  std::vector<double> shifts;
  dlmfd::CutCellConstants constants;
  bool both = false;
  dlmfd::CutCellLinearSolver solver = dlmfd::CutCellLinearSolver::kGmres;
  for (int a = 3; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--both") {
      both = true;
    } else if (arg == "--direct") {
      solver = dlmfd::CutCellLinearSolver::kDirect;
    } else if (arg == "--exact-velocity") {
      solver = dlmfd::CutCellLinearSolver::kGmresExactVelocity;
    } else if (arg == "--ghost" && a + 1 < argc) {
      constants.ghost_velocity = std::atof(argv[++a]);
    } else if (arg == "--ghost-p" && a + 1 < argc) {
      constants.ghost_pressure = std::atof(argv[++a]);
    } else {
      shifts.push_back(std::atof(argv[a]));
    }
  }
  dlmfd::DomainParams d;
  d.diagonals = dlmfd::MeshDiagonals::kSwNe;  // the mesh of the numbers in docs/
  d.size = c.size;
  d.h = 0.1 / d_over_h;
  // The pressure's 2h grid needs an even whole number of cells of h across the box (the scene's
  // RequireEvenCells; this bench builds DomainParams without the scene's checks).
  for (const double length : {d.size.x(), d.size.y()}) {
    const double cells = length / d.h;
    const double whole = std::round(cells);
    if (std::abs(cells - whole) > 1e-9 * cells || static_cast<long long>(whole) % 2 != 0) {
      std::fprintf(stderr,
                   "D_OVER_H = %g: %g / h = %g cells; the pressure's 2h grid needs an even whole "
                   "number across the box (schaefer_turek: 0.41 / h even, e.g. D_OVER_H = 20, "
                   "40 or 9.75609756097561)\n",
                   d_over_h, length, cells);
      return 2;
    }
  }
  dlmfd::BoundarySide& inflow = d.sides[static_cast<int>(dlmfd::Side::kLeft)];
  inflow.type = dlmfd::SideType::kVelocity;
  inflow.profile = dlmfd::Profile::kPoiseuille;
  inflow.max = Vec2(0.3, 0.0);
  d.sides[static_cast<int>(dlmfd::Side::kRight)].type = dlmfd::SideType::kOutflow;
  const dlmfd::Grid g = d.VelocityGrid();
  const dlmfd::BoundaryData data(g, d);
  for (double shift : shifts) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<dlmfd::FixedBody> body(1);
    body[0].shape = dlmfd::Shape::Disk(0.05);
    body[0].centre = Vec2(0.2 + shift * d.h, 0.2);
    const dlmfd::CutCellGeometry geo(g, body);
    const dlmfd::CutCellGeometry mirror(g, body, dlmfd::CutTriangulation::kNwSe);
    dlmfd::CutCellStokes flow =
        both ? dlmfd::CutCellStokes(geo, mirror, d, c.viscosity, 1.0, 0.0, constants)
             : dlmfd::CutCellStokes(geo, d, c.viscosity, 1.0, 0.0, constants);
    std::vector<double> u(g.NodeCount()), v(g.NodeCount()), p(g.Coarse().NodeCount());
    int iterations = 0;
    if (c.navier_stokes) {
      iterations = dlmfd::SolveSteadyNavierStokes(flow, data, u.data(), v.data(), p.data(), 1e-10,
                                                  5000, 1e-8, 60, solver);
    } else {
      iterations =
          flow.Solve(data, nullptr, nullptr, u.data(), v.data(), p.data(), 1e-10, 5000).iterations;
    }
    Vec2 f = flow.Force(0, u.data(), v.data(), p.data());
    if (c.navier_stokes) f *= 500.0;  // C_D, C_L: 2 F / (rho U_mean^2 D), U_mean = 0.2
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("engine,%g,%g,%.7f,%.7f,%d,%.2f,%d\n", d_over_h, shift, f.x(), f.y(),
                2 * flow.VelocityUnknowns() + flow.PressureUnknowns(), seconds, iterations);
    std::fflush(stdout);
    std::fprintf(stderr, "D/h %g, shift %g: capacitance rank %d\n", d_over_h, shift,
                 flow.CapacitanceRank());
  }
  return 0;
}
