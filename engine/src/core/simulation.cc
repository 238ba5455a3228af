// Simulation: the Marchuk-Yanenko loop (paper section 4). This file owns the state and the substep
// solvers (built once, sized once); Step() runs the substeps as separate members:
//   SolveStokes (33) -> AdvectVelocity (34) -> [UpdateConformation (35)] -> [MoveParticles
//   (36)-(38)].
// A step models no more than the scene needs: a Newtonian liquid (relaxation_time = 0 or
// solvent_ratio = 1) has no conformation arrays, no polymer force and no step (35); a scene without
// particles has no step (36)-(38).
// Coupling: the polymer force -(eta_p / lambda) int grad phi : (A^n - I) enters (33) through the
// Stokes solver's dual forcing (the body force is added by the solver itself); step (35) uses
// u^{n+2/4} with A = I at the nodes inside the particles at X^n and A = A_L on inflow nodes; the
// particle step updates u^{n+2/4} to u^{n+1} in place.
// Initial state: u = 0 with the boundary data, A = I (A_L at inflow nodes), the particles of the
// scene at rest or at their given velocities (ParticleStep::InitialStates).
#include "dlmfd/core/simulation.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "../mesh/grid_kernels.h"
#include "dlmfd/conformation/conformation_step.h"
#include "dlmfd/conformation/inflow_state.h"
#include "dlmfd/conformation/polymer_force.h"
#include "dlmfd/core/errors.h"
#include "dlmfd/fluid/advection_least_squares.h"
#include "dlmfd/fluid/advection_wave.h"
#include "dlmfd/fluid/boundary_data.h"
#include "dlmfd/fluid/stokes_solver.h"
#include "dlmfd/particles/particle_step.h"

namespace dlmfd {
namespace {

using Clock = std::chrono::steady_clock;

double Milliseconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

std::string Text(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

void ValidateSupported(const Params& p) {
  const double gamma = 1.0 - p.splitting.alpha - p.splitting.beta;
  if (std::abs(gamma) > 1e-12) {
    throw InvalidParameter("splitting.beta", Text(p.splitting.beta),
                           "alpha + beta = 1 (gamma = 0: the engine puts no viscosity into (37))");
  }
  if (!(p.splitting.alpha > 0.0)) {
    throw InvalidParameter("splitting.alpha", Text(p.splitting.alpha),
                           "> 0 (the Stokes step (33) carries viscosity for its fast solver)");
  }
  if (!(p.time.dt > 0.0)) throw InvalidParameter("time.dt", Text(p.time.dt), "> 0");
}

Grid MakeGrid(const DomainParams& d) {
  Grid g;
  g.nx = static_cast<int>(std::lround(d.size.x() / d.h));
  g.ny = static_cast<int>(std::lround(d.size.y() / d.h));
  g.h = d.h;
  return g;
}

// Index of the output period that t_n = n dt falls in; deterministic in n.
long Period(long n, double dt, double every) {
  return static_cast<long>(std::floor(static_cast<double>(n) * dt / every + 1e-9));
}

}  // namespace

struct Simulation::Impl {
  explicit Impl(const Params& p)
      : params(p),
        grid(MakeGrid(p.domain)),
        pgrid(grid.Coarse()),
        boundary_data(grid, p.domain),
        stokes(grid, p.domain, p.fluid, p.time.dt, p.splitting.alpha, p.solvers, boundary_data),
        viscoelastic(!p.fluid.IsNewtonian()) {
    if (p.splitting.advection == AdvectionScheme::kLeastSquares) {
      least_squares = std::make_unique<AdvectionLeastSquares>(
          grid, p.domain, p.fluid, p.time.dt, p.splitting.beta, p.solvers, boundary_data);
    } else {
      wave = std::make_unique<AdvectionWave>(grid, p.domain, p.fluid, p.time.dt, p.splitting.beta,
                                             p.solvers, boundary_data);
    }
    state.u.assign(grid.NodeCount(), 0.0);
    state.v.assign(grid.NodeCount(), 0.0);
    state.p.assign(pgrid.NodeCount(), 0.0);
    boundary_data.Apply(state.u.data(), state.v.data());
    if (!p.particles.empty()) {
      state.particles = ParticleStep::InitialStates(p);
      particle_step = std::make_unique<ParticleStep>(p, grid);
    }
    if (viscoelastic) {
      conformation = std::make_unique<ConformationStep>(p, grid);
      polymer_modulus = p.fluid.PolymerViscosity() / p.fluid.relaxation_time;
      state.a11.assign(grid.NodeCount(), 1.0);
      state.a12.assign(grid.NodeCount(), 0.0);
      state.a22.assign(grid.NodeCount(), 1.0);
      SetInitialInflowConformation();
      stokes_fx.assign(grid.NodeCount(), 0.0);
      stokes_fy.assign(grid.NodeCount(), 0.0);
      if (!p.particles.empty()) inside_particle.assign(grid.NodeCount(), 0);
    }
  }

  // A = A_L at the nodes of velocity sides where the boundary data point into the domain (the rule
  // of ConformationStep, applied to u^0).
  void SetInitialInflowConformation() {
    struct SideWalk {
      Side side;
      int i0, j0, di, dj, count;
      double nx, ny;  // outward normal
    };
    const SideWalk walks[4] = {{Side::kLeft, 0, 0, 0, 1, grid.ny + 1, -1.0, 0.0},
                               {Side::kRight, grid.nx, 0, 0, 1, grid.ny + 1, 1.0, 0.0},
                               {Side::kBottom, 0, 0, 1, 0, grid.nx + 1, 0.0, -1.0},
                               {Side::kTop, 0, grid.ny, 1, 0, grid.nx + 1, 0.0, 1.0}};
    const double lambda = params.fluid.relaxation_time;
    for (const SideWalk& w : walks) {
      if (params.domain.side(w.side).type != SideType::kVelocity) continue;
      for (int k = 0; k < w.count; ++k) {
        const std::size_t n = grid.Index(w.i0 + k * w.di, w.j0 + k * w.dj);
        if (!(state.u[n] * w.nx + state.v[n] * w.ny < 0.0)) continue;
        const SymTensor a = InflowConformation(grid, params.domain, w.side, k, lambda);
        state.a11[n] = a.a11;
        state.a12[n] = a.a12;
        state.a22[n] = a.a22;
      }
    }
  }

  // Step (33): u^n -> u^{n+1/4}, p^{n+1/4}, with the polymer stress of A^n on the right side.
  void SolveStokes(StepReport& report) {
    const auto t0 = Clock::now();
    const double* fx = nullptr;
    const double* fy = nullptr;
    if (viscoelastic) {
      std::fill(stokes_fx.begin(), stokes_fx.end(), 0.0);
      std::fill(stokes_fy.begin(), stokes_fy.end(), 0.0);
      AddPolymerForce(grid, params.domain, polymer_modulus, state.a11.data(), state.a12.data(),
                      state.a22.data(), stokes_fx.data(), stokes_fy.data());
      fx = stokes_fx.data();
      fy = stokes_fy.data();
    }
    const StokesReport r = stokes.Solve(fx, fy, state.u.data(), state.v.data(), state.p.data());
    report.Set("stokes_iterations", r.iterations);
    report.Set("stokes_residual", r.residual);
    report.Set("divergence", r.divergence);
    report.Set("ms_stokes", Milliseconds(t0, Clock::now()));
  }

  // Step (34): u^{n+1/4} -> u^{n+2/4}.
  void AdvectVelocity(StepReport& report) {
    const auto t0 = Clock::now();
    if (least_squares) {
      const AdvectionReport r = least_squares->Solve(state.u.data(), state.v.data());
      report.Set("advection_iterations", r.iterations);
      report.Set("advection_residual", r.residual);
    } else {
      const AdvectionReport r = wave->Solve(state.u.data(), state.v.data());
      report.Set("wave_substeps", r.iterations);
    }
    report.Set("ms_advection", Milliseconds(t0, Clock::now()));
  }

  // Marks the velocity nodes strictly inside a particle at its current position (X^n), across
  // periodic sides by the minimum image.
  void MarkParticleNodes() {
    std::fill(inside_particle.begin(), inside_particle.end(), 0);
    const bool px = params.domain.PeriodicX(), py = params.domain.PeriodicY();
    for (const ParticleState& q : state.particles) {
      const double r = q.radius;
      int i_lo, i_hi, j_lo, j_hi;
      kernels::CoveredNodes(q.position.x() - r, q.position.x() + r, grid.x0, grid.h, grid.nx, px,
                            &i_lo, &i_hi);
      kernels::CoveredNodes(q.position.y() - r, q.position.y() + r, grid.y0, grid.h, grid.ny, py,
                            &j_lo, &j_hi);
      for (int jj = j_lo; jj <= j_hi; ++jj) {
        const double dy = grid.Y(jj) - q.position.y();
        const int j = py ? kernels::Wrap(jj, grid.ny) : jj;
        for (int ii = i_lo; ii <= i_hi; ++ii) {
          const double dx = grid.X(ii) - q.position.x();
          if (dx * dx + dy * dy >= r * r) continue;
          const int i = px ? kernels::Wrap(ii, grid.nx) : ii;
          inside_particle[grid.Index(i, j)] = 1;
          // The repeated last node of a periodic line mirrors the first.
          if (px && i == 0) inside_particle[grid.Index(grid.nx, j)] = 1;
          if (py && j == 0) inside_particle[grid.Index(i, grid.ny)] = 1;
          if (px && py && i == 0 && j == 0) inside_particle[grid.Index(grid.nx, grid.ny)] = 1;
        }
      }
    }
  }

  // Step (35): A^n -> A^{n+1} with u^{n+2/4}; A = I inside the particles at X^n.
  void UpdateConformation(StepReport& report) {
    const auto t0 = Clock::now();
    const unsigned char* inside = nullptr;
    if (!inside_particle.empty()) {
      MarkParticleNodes();
      inside = inside_particle.data();
    }
    conformation->Advance(state.time, params.time.dt, state.u.data(), state.v.data(), inside,
                          state.a11.data(), state.a12.data(), state.a22.data(), report);
    report.Set("ms_conformation", Milliseconds(t0, Clock::now()));
  }

  // Steps (36)-(38): particles X^n -> X^{n+1}, velocity u^{n+2/4} -> u^{n+1} in place.
  void MoveParticles(StepReport& report) {
    const auto t0 = Clock::now();
    particle_step->Advance(state.time, params.time.dt, state.particles, state.u.data(),
                           state.v.data(), report);
    report.Set("ms_particles", Milliseconds(t0, Clock::now()));
  }

  // NaN/Inf anywhere ends the run with the quantity, the time and a node position.
  void CheckFinite() const {
    auto check = [&](const std::vector<double>& f, const Grid& g, const char* name) {
      for (std::size_t k = 0; k < f.size(); ++k) {
        if (std::isfinite(f[k])) continue;
        const int i = static_cast<int>(k % std::size_t(g.nx + 1));
        const int j = static_cast<int>(k / std::size_t(g.nx + 1));
        std::ostringstream msg;
        msg << "numerical blow-up: " << name << " = " << f[k] << " at t = " << state.time
            << " (step " << state.step << "), node (" << i << ", " << j << ") at x = " << g.X(i)
            << ", y = " << g.Y(j) << "; reduce time.dt or refine domain.h";
        throw NumericalBlowUp(msg.str());
      }
    };
    check(state.u, grid, "velocity u");
    check(state.v, grid, "velocity v");
    check(state.p, pgrid, "pressure p");
  }

  double MaxSpeed() const {
    double m = 0.0;
    for (std::size_t k = 0; k < state.u.size(); ++k) {
      m = std::max(m, state.u[k] * state.u[k] + state.v[k] * state.v[k]);
    }
    return std::sqrt(m);
  }

  Params params;
  Grid grid, pgrid;
  BoundaryData boundary_data;
  StokesSolver stokes;
  bool viscoelastic;
  double polymer_modulus = 0.0;  // eta_p / lambda
  std::unique_ptr<AdvectionLeastSquares> least_squares;
  std::unique_ptr<AdvectionWave> wave;
  std::unique_ptr<ConformationStep> conformation;  // viscoelastic only
  std::unique_ptr<ParticleStep> particle_step;     // with particles only
  std::vector<double> stokes_fx, stokes_fy;        // polymer force of (33); viscoelastic only
  std::vector<unsigned char>
      inside_particle;  // nodes where A = I; viscoelastic with particles only
  StepReport report;    // reused: its columns are created by the first step, overwritten after
  FlowState state;
  std::vector<Observer*> observers;
};

Simulation::Simulation(const Params& params) {
  ValidateSupported(params);
  if (params.threads > 0) omp_set_num_threads(params.threads);
  impl_ = std::make_unique<Impl>(params);
}

Simulation::~Simulation() = default;

void Simulation::AddObserver(Observer* observer) { impl_->observers.push_back(observer); }

void Simulation::EmitInitial() {
  for (Observer* o : impl_->observers) {
    o->OnParticles(impl_->state);
    o->OnSnapshot(impl_->state);
  }
}

void Simulation::Step() {
  Impl& s = *impl_;
  const auto t0 = Clock::now();
  StepReport& report = s.report;
  s.SolveStokes(report);
  s.AdvectVelocity(report);
  if (s.conformation) s.UpdateConformation(report);
  if (s.particle_step) s.MoveParticles(report);
  s.state.step += 1;
  s.state.time = static_cast<double>(s.state.step) * s.params.time.dt;
  s.CheckFinite();
  report.Set("cfl", s.MaxSpeed() * s.params.time.dt / s.grid.h);
  report.step = s.state.step;
  report.time = s.state.time;
  report.wall_seconds = std::chrono::duration<double>(Clock::now() - t0).count();

  const OutputParams& out = s.params.output;
  const long n = s.state.step;
  const double dt = s.params.time.dt;
  const bool particles_due =
      out.particles_every <= 0.0 ||
      Period(n, dt, out.particles_every) > Period(n - 1, dt, out.particles_every);
  const bool fields_due = out.fields_every > 0.0 &&
                          Period(n, dt, out.fields_every) > Period(n - 1, dt, out.fields_every);
  for (Observer* o : s.observers) {
    o->OnStep(s.state, report);
    if (particles_due) o->OnParticles(s.state);
    if (fields_due) o->OnSnapshot(s.state);
  }
  for (Observer* o : s.observers) o->OnStepEnd(s.state);
}

void Simulation::Run(const std::atomic<bool>* stop) {
  while (!Done() && !(stop && stop->load())) Step();
  if (!Done()) {
    for (Observer* o : impl_->observers) o->OnStopped(impl_->state);
  }
}

bool Simulation::Done() const { return impl_->state.step >= TotalSteps(); }

long Simulation::TotalSteps() const {
  return static_cast<long>(std::llround(impl_->params.time.end / impl_->params.time.dt));
}

void Simulation::Restore(const FlowState& state) {
  const Impl& s = *impl_;
  if (state.u.size() != s.grid.NodeCount() || state.v.size() != s.grid.NodeCount() ||
      state.p.size() != s.pgrid.NodeCount()) {
    throw InvalidParameter("checkpoint", "fields of " + std::to_string(state.u.size()) + " nodes",
                           std::to_string(s.grid.NodeCount()) + " velocity and " +
                               std::to_string(s.pgrid.NodeCount()) +
                               " pressure nodes (the same scene)");
  }
  const std::size_t a_nodes = s.viscoelastic ? s.grid.NodeCount() : 0;
  if (state.a11.size() != a_nodes || state.a12.size() != a_nodes || state.a22.size() != a_nodes) {
    throw InvalidParameter(
        "checkpoint", "a configuration tensor of " + std::to_string(state.a11.size()) + " nodes",
        std::to_string(a_nodes) + " nodes (" + (s.viscoelastic ? "a viscoelastic" : "a Newtonian") +
            " scene)");
  }
  if (state.particles.size() != s.state.particles.size()) {
    throw InvalidParameter(
        "checkpoint", std::to_string(state.particles.size()) + " particles",
        std::to_string(s.state.particles.size()) + " particles (the same scene)");
  }
  for (std::size_t p = 0; p < state.particles.size(); ++p) {
    if (state.particles[p].multiplier.size() != s.state.particles[p].multiplier.size()) {
      throw InvalidParameter(
          "checkpoint",
          "particle " + std::to_string(p) + " with " +
              std::to_string(state.particles[p].multiplier.size()) + " multiplier values",
          std::to_string(s.state.particles[p].multiplier.size()) + " (the same scene)");
    }
  }
  impl_->state = state;
}

const Params& Simulation::params() const { return impl_->params; }
const Grid& Simulation::grid() const { return impl_->grid; }
const Grid& Simulation::pressure_grid() const { return impl_->pgrid; }
const FlowState& Simulation::state() const { return impl_->state; }
FlowState& Simulation::mutable_state() { return impl_->state; }

}  // namespace dlmfd
